//! The state of the boundary-element contact along a path: the fields carried from one increment
//! to the next (pressure, traction, accumulated slip) and the step that advances them.

use crate::scene::Scene;

use super::convolution::Convolver;
use super::grid::Grid;
use super::influence::{Kernels, PairCompliance};
use super::normal::{NormalOperator, NormalProblem};
use super::tangential::{TangentialOperator, TangentialProblem, Vector2Field};

/// Solver settings that an increment needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances {
    /// Normal problem: rms gap on the contact over δ.
    pub normal: f64,
    /// Tangential problem: projected-gradient step over μ p_max.
    pub tangential: f64,
    /// Iteration cap of either problem.
    pub max_iterations: usize,
}

/// A panel sticks when its traction is below the Coulomb bound by more than this fraction: the
/// projection puts slipping panels exactly on the bound, so this only absorbs rounding.
const STICK_MARGIN: f64 = 1e-6;

/// The fields on the grid after an increment.
#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot {
    /// The grid.
    pub grid: Grid,
    /// Pressure p [Pa] per panel.
    pub pressure: Vec<f64>,
    /// Traction q on body 1 [Pa] per panel.
    pub traction: Vector2Field,
    /// Stick (true) or slip (false) for panels in contact; false outside.
    pub stick: Vec<bool>,
    /// Slip accumulated since the panel last came into contact [m]; zero outside.
    pub slip: Vector2Field,
    /// The friction coefficient μ that bounds the traction.
    pub friction: f64,
}

impl Snapshot {
    /// Indices of panels in contact.
    fn contact(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.pressure.len()).filter(|&k| self.pressure[k] > 0.0)
    }

    /// P = Σ p h² [N].
    pub fn normal_force(&self) -> f64 {
        self.pressure.iter().sum::<f64>() * self.grid.panel_area()
    }

    /// Q = Σ q_x h² [N].
    pub fn tangential_force(&self) -> f64 {
        self.traction.x.iter().sum::<f64>() * self.grid.panel_area()
    }

    /// Where a field that vanishes like a square root at an edge (p at the contact edge, μp − |q|
    /// at the stick edge) reaches zero along the four half-axes +x, −x, +y, −y [m], each fitted
    /// through the panels from the centre out while the value is positive
    /// ([`crate::fit::square_root_edge`]). `None` when an axis has fewer than two panels in the
    /// outer half of the zone.
    fn axis_edges(&self, value: impl Fn(usize) -> f64) -> Option<[f64; 4]> {
        let grid = &self.grid;
        let centre = grid.n / 2;
        let half_axes: [&dyn Fn(usize) -> Option<usize>; 4] = [
            &|i| (centre + i < grid.n).then(|| centre * grid.n + centre + i),
            &|i| (i <= centre).then(|| centre * grid.n + centre - i),
            &|i| (centre + i < grid.n).then(|| (centre + i) * grid.n + centre),
            &|i| (i <= centre).then(|| (centre - i) * grid.n + centre),
        ];
        let mut edges = [0.0; 4];
        for (edge, panel) in edges.iter_mut().zip(half_axes) {
            let samples: Vec<(f64, f64)> = (0..)
                .map_while(panel)
                .map(&value)
                .take_while(|&v| v > 0.0)
                .enumerate()
                .map(|(i, v)| (i as f64 * grid.h, v))
                .collect();
            *edge = crate::fit::square_root_edge(&samples)?;
        }
        Some(edges)
    }

    /// The contact radius [m]: the mean of the pressure's edges on the four half-axes, or the
    /// area-equivalent radius of the contact panels when the contact is too small to fit.
    pub fn contact_radius(&self) -> f64 {
        match self.axis_edges(|k| self.pressure[k]) {
            Some(edges) => edges.iter().sum::<f64>() / 4.0,
            None => self.grid.equivalent_radius(self.contact().count()),
        }
    }

    /// The radius of the disc with the stick area [m] (0 in gross sliding).
    pub fn stick_radius(&self) -> f64 {
        self.grid
            .equivalent_radius(self.contact().filter(|&k| self.stick[k]).count())
    }

    /// The largest panel pressure [Pa] (the centre panel's, for a Hertz contact).
    pub fn peak_pressure(&self) -> f64 {
        self.pressure.iter().copied().fold(0.0, f64::max)
    }

    /// The stick zone's semi-axes along x (the loading direction) and y [m]: the mean edge of the
    /// stick deficit μp − |q| on the ±x and on the ±y half-axes (see `axis_edges`); `None` when the
    /// stick zone is too small to fit. Valid in partial slip under monotonic loading from a virgin
    /// state, where the deficit has Cattaneo's √ form; after a reversal it does not (the locked-in
    /// traction of the previous branch), and the area-equivalent `stick_radius` is the measure.
    pub fn stick_semi_axes(&self) -> Option<[f64; 2]> {
        let deficit = |k: usize| {
            if self.stick[k] {
                self.friction * self.pressure[k] - self.traction.magnitude(k)
            } else {
                0.0
            }
        };
        self.axis_edges(deficit)
            .map(|e| [0.5 * (e[0] + e[1]), 0.5 * (e[2] + e[3])])
    }
}

/// What an increment reports besides the fields.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IncrementCost {
    /// Conjugate-gradient iterations of the normal problem.
    pub normal_iterations: usize,
    /// Projected-gradient iterations of the tangential problem.
    pub tangential_iterations: usize,
}

/// Why an increment failed.
#[derive(Debug, PartialEq)]
pub enum IncrementError {
    /// A panel on the window's edge is in contact: the window is too small.
    ContactAtEdge {
        /// Contact radius reached [m].
        radius: f64,
        /// Window half-width [m].
        half_width: f64,
    },
    /// A problem did not converge.
    NotConverged {
        /// "normal" or "tangential".
        problem: &'static str,
        /// Iterations spent.
        iterations: usize,
        /// Last residual.
        residual: f64,
    },
}

/// The contact's state on one grid.
pub struct ContactState {
    grid: Grid,
    normal: NormalOperator,
    /// The pair's compliances, for the tangential operator built when friction is first needed.
    compliance: PairCompliance,
    tangential: Option<TangentialOperator>,
    /// Initial separation r²/2R* of each panel [m].
    separation: Vec<f64>,
    /// Pressure per unit overlap of Hertz's order, E*/c_max, to seed the normal solver [Pa/m].
    stiffness: f64,
    tolerances: Tolerances,
    snapshot: Snapshot,
    /// The last increment's traction change and shift, to extrapolate the next starting guess.
    last_change: Vector2Field,
    last_shift: f64,
}

impl ContactState {
    /// The unloaded contact of `scene` on `grid`.
    pub fn new(scene: &Scene, grid: Grid, tolerances: Tolerances) -> Self {
        let compliance = PairCompliance::of(&scene.pair);
        let r_star = scene.pair.effective_radius();
        let separation = grid
            .centres()
            .iter()
            .map(|[x, y]| (x * x + y * y) / (2.0 * r_star))
            .collect();
        let len = grid.len();
        Self {
            normal: NormalOperator::new(Convolver::new(grid.n), &Kernels::normal(&grid, &compliance)),
            compliance,
            tangential: None,
            separation,
            stiffness: scene.pair.effective_modulus() / scene.max_contact_radius().max(grid.h),
            tolerances,
            snapshot: Snapshot {
                grid,
                pressure: vec![0.0; len],
                traction: Vector2Field::zeros(len),
                stick: vec![false; len],
                slip: Vector2Field::zeros(len),
                friction: scene.friction,
            },
            last_change: Vector2Field::zeros(len),
            last_shift: 0.0,
            grid,
        }
    }

    /// The fields after the last increment.
    pub fn snapshot(&self) -> &Snapshot {
        &self.snapshot
    }

    /// Moves to approach `delta_n` with a tangential shift increment `shift` along x.
    pub fn advance(&mut self, delta_n: f64, shift: f64) -> Result<IncrementCost, IncrementError> {
        let normal_iterations = self.solve_normal(delta_n)?;
        self.check_window()?;
        let tangential_iterations = self.solve_tangential(shift)?;
        Ok(IncrementCost {
            normal_iterations,
            tangential_iterations,
        })
    }

    fn solve_normal(&mut self, delta_n: f64) -> Result<usize, IncrementError> {
        let pressure = &mut self.snapshot.pressure;
        if delta_n <= 0.0 {
            pressure.fill(0.0);
            return Ok(0);
        }
        let problem = NormalProblem {
            separation: &self.separation,
            approach: delta_n,
            tolerance: self.tolerances.normal,
            max_iterations: self.tolerances.max_iterations,
            stiffness: self.stiffness,
        };
        if pressure.iter().all(|&p| p == 0.0) {
            *pressure = problem.starting_pressure();
        }
        problem
            .solve(&mut self.normal, pressure)
            .map_err(|e| IncrementError::NotConverged {
                problem: "normal",
                iterations: e.iterations,
                residual: e.residual,
            })
    }

    fn check_window(&self) -> Result<(), IncrementError> {
        let grid = &self.grid;
        let touches = (0..grid.len()).any(|k| grid.is_on_edge(k) && self.snapshot.pressure[k] > 0.0);
        if touches {
            return Err(IncrementError::ContactAtEdge {
                radius: self.snapshot.contact_radius(),
                half_width: grid.coordinate(grid.n - 1) + 0.5 * grid.h,
            });
        }
        Ok(())
    }

    fn solve_tangential(&mut self, shift: f64) -> Result<usize, IncrementError> {
        let snapshot = &mut self.snapshot;
        let bound: Vec<f64> = snapshot.pressure.iter().map(|p| snapshot.friction * p).collect();
        if shift == 0.0
            && snapshot
                .traction
                .x
                .iter()
                .chain(&snapshot.traction.y)
                .all(|&q| q == 0.0)
        {
            // No shift and no traction: q = 0 solves the increment exactly (zero gradient), and
            // every panel in contact sticks where friction can hold it.
            for (k, &g) in bound.iter().enumerate() {
                snapshot.stick[k] = g > 0.0;
                if snapshot.pressure[k] <= 0.0 {
                    snapshot.slip.x[k] = 0.0;
                    snapshot.slip.y[k] = 0.0;
                }
            }
            return Ok(0);
        }
        let (grid, compliance) = (&self.grid, &self.compliance);
        let operator = self.tangential.get_or_insert_with(|| {
            let kernels = Kernels::tangential(grid, compliance);
            TangentialOperator::new(Convolver::new(grid.n), &kernels.xx, &kernels.xy, &kernels.yy)
        });
        let ratio = if self.last_shift != 0.0 {
            shift / self.last_shift
        } else {
            0.0
        };
        let extrapolate =
            |q: &[f64], dq: &[f64]| -> Vec<f64> { q.iter().zip(dq).map(|(q, dq)| q + ratio * dq).collect() };
        let problem = TangentialProblem {
            bound: &bound,
            previous: &snapshot.traction,
            guess: Vector2Field {
                x: extrapolate(&snapshot.traction.x, &self.last_change.x),
                y: extrapolate(&snapshot.traction.y, &self.last_change.y),
            },
            shift,
            tolerance: self.tolerances.tangential,
            max_iterations: self.tolerances.max_iterations,
        };
        let solution = problem
            .solve(operator)
            .map_err(|e| IncrementError::NotConverged {
                problem: "tangential",
                iterations: e.iterations,
                residual: e.residual,
            })?;
        for (k, &g) in bound.iter().enumerate() {
            let in_contact = snapshot.pressure[k] > 0.0;
            snapshot.stick[k] = in_contact && solution.traction.magnitude(k) < (1.0 - STICK_MARGIN) * g;
            // Stick panels take the shift up elastically: their slip increment is zero up to the
            // solver's residual, which is not accumulated.
            let (sx, sy) = if in_contact && !snapshot.stick[k] {
                (
                    snapshot.slip.x[k] + solution.slip.x[k],
                    snapshot.slip.y[k] + solution.slip.y[k],
                )
            } else if in_contact {
                (snapshot.slip.x[k], snapshot.slip.y[k])
            } else {
                (0.0, 0.0)
            };
            snapshot.slip.x[k] = sx;
            snapshot.slip.y[k] = sy;
        }
        let change =
            |new: &[f64], old: &[f64]| -> Vec<f64> { new.iter().zip(old).map(|(a, b)| a - b).collect() };
        self.last_change = Vector2Field {
            x: change(&solution.traction.x, &snapshot.traction.x),
            y: change(&solution.traction.y, &snapshot.traction.y),
        };
        self.last_shift = shift;
        snapshot.traction = solution.traction;
        Ok(solution.iterations)
    }
}
