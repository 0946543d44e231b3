//! The state of the boundary-element contact along a path: the shared contact engine
//! ([`spherecontact_contact`]) on the grid's FFT compliances, and the fields it carries from one
//! increment to the next (pressure, traction, accumulated slip) as a [`Snapshot`].

use crate::fit::stick::{self, StickZone};
use spherecontact_contact::{Contact, ContactError, FrictionSet, Method, Settings};
use spherecontact_model::scene::Scene;

use super::grid::Grid;
use super::influence::PairCompliance;
use super::operator::FftCompliance;

/// Per-panel vectors (x, y) of a component-major engine vector (x of every panel, then y);
/// zeros when the engine carries none (no friction).
fn panel_vectors(values: &[f64], len: usize) -> Vec<[f64; 2]> {
    if values.is_empty() {
        return vec![[0.0; 2]; len];
    }
    (0..len).map(|k| [values[k], values[len + k]]).collect()
}

/// Solver settings that an increment needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances {
    /// Normal problem: rms gap on the contact over δ.
    pub normal: f64,
    /// Tangential problem: the engine's stick and slip conditions over λ_max μ p_max (see
    /// [`spherecontact_contact::coulomb`]).
    pub tangential: f64,
    /// Iteration cap of either problem.
    pub max_iterations: usize,
}

/// The fields on the grid after an increment.
#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot {
    /// The grid.
    pub grid: Grid,
    /// Pressure p [Pa] per panel.
    pub pressure: Vec<f64>,
    /// Traction (q_x, q_y) on body 1 [Pa] per panel.
    pub traction: Vec<[f64; 2]>,
    /// Stick (true) or slip (false) for panels in contact; false outside.
    pub stick: Vec<bool>,
    /// Slip (x, y) accumulated since the panel last came into contact [m]; zero outside.
    pub slip: Vec<[f64; 2]>,
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
        self.traction.iter().map(|q| q[0]).sum::<f64>() * self.grid.panel_area()
    }

    /// Where a field that vanishes like a square root at an edge (p at the contact edge) reaches
    /// zero along the four half-axes +x, −x, +y, −y [m], each fitted
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

    /// The stick zone by the measure of every solver ([`stick::stick_zone`]): the stick radius
    /// c √(N_stick / N_contact) (equal panels) and the semi-axes of the stick panels' second
    /// moments; `None` when no panel sticks.
    pub fn stick_zone(&self) -> Option<StickZone> {
        let weights = vec![self.grid.panel_area(); self.grid.len()];
        let points = self.grid.centres();
        stick::stick_zone(
            self.contact_radius(),
            &points,
            &weights,
            &self.pressure,
            &self.stick,
        )
    }

    /// The stick radius [m] ([`Snapshot::stick_zone`]): c at full stick, never above it, 0 in
    /// gross sliding.
    pub fn stick_radius(&self) -> f64 {
        self.stick_zone().map_or(0.0, |z| z.radius)
    }

    /// |q| at panel `k` [Pa].
    pub fn traction_magnitude(&self, k: usize) -> f64 {
        let [x, y] = self.traction[k];
        x.hypot(y)
    }

    /// The largest panel pressure [Pa] (the centre panel's, for a Hertz contact).
    pub fn peak_pressure(&self) -> f64 {
        self.pressure.iter().copied().fold(0.0, f64::max)
    }
}

/// What an increment reports besides the fields.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IncrementCost {
    /// Conjugate-gradient iterations of the normal problem (with those on the coarser grids of a
    /// contact from rest, each a quarter of the cost of the finer).
    pub normal_iterations: usize,
    /// Accelerated projected-gradient iterations of the tangential problem.
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
    /// The contact engine failed (a problem did not converge).
    Engine(ContactError),
}

/// The precision of the tangential products. f32: half the cost of a product, and its relative
/// error (about 1e-7 · log₂ 2n of the largest displacement) is far below the tangential
/// tolerance (3e-5 of the traction scale, [`super::Bem::with_grid`]); measured on the paper path
/// at 128², Ft moves by less than 1e-6 of its peak and Cattaneo's Q by less than 1e-6 at
/// 128²–256² (examples/bem_timing.rs). The normal products stay f64 (the normal tolerance,
/// 1e-6 (128/n)² of the approach, is within two decades of f32's round-off; all-f32 normal
/// products moved p0 at 256² from 2.7e-6 to −1.1e-5 off Hertz), but its conjugate-gradient
/// corrections run in f32 ([`FftCompliance::with_f32_corrections`]): their errors are relative
/// to the correction, and the solver forms the answer in f64 before it stops.
type TangentialPrecision = f32;

/// The engine on a grid: the Boussinesq compliance (f64 products, f32 corrections) and, with
/// friction, the Cerruti one.
type GridContact = Contact<FftCompliance<f64>, FftCompliance<TangentialPrecision>>;

/// Nested iteration goes no coarser than this many panels a side: below it the coarse level costs
/// more than it saves. Measured on Hertz at δn = 17 µm (`bem_timing normal`, CPU): at 64² a 32²
/// level took the solve from 2.24 to 2.51 ms; at 128² a 64² level from 14.5 to 12 ms.
const COARSEST: usize = 64;

/// A guess needs no more accuracy than its interpolation onto the finer grid keeps (the pressure
/// near the edge is off by O(h) there), so the coarser levels stop at this multiple of the
/// normal tolerance. Measured on Hertz at δn = 17 µm (`bem_timing normal`, CPU, with levels down
/// to 32²): at 256² 84, 80, 82 and 87 ms for 1×, 10×, 100× and 1000× (99 ms without nested
/// iteration), at 512² 555, 544, 580 and 776 ms (749 ms without).
const COARSE_TOLERANCE_FACTOR: f64 = 10.0;

/// What it takes to set up the normal problem on any grid of the window: nested iteration solves
/// the same problem on coarser grids.
#[derive(Clone, Copy, Debug)]
struct NormalModel {
    compliance: PairCompliance,
    /// The effective radius R*: the separation of the undeformed surfaces is r²/2R*.
    r_star: f64,
    settings: Settings,
}

impl NormalModel {
    /// The frictionless contact on `grid`, at rest.
    fn contact(&self, grid: &Grid, settings: Settings) -> GridContact {
        let separation = grid
            .centres()
            .iter()
            .map(|[x, y]| (x * x + y * y) / (2.0 * self.r_star))
            .collect();
        Contact::new(
            FftCompliance::<f64>::normal(grid, &self.compliance).with_f32_corrections(),
            separation,
            settings,
        )
        .expect("one separation a panel")
    }

    /// Nested iteration (e.g. Venner & Lubrecht 2000, *Multilevel Methods in Lubrication*, §3):
    /// the pressure at approach `delta_n` solved on the grid of half as many panels a side over
    /// the same window (itself started so, down to [`COARSEST`]), interpolated bilinearly onto
    /// the centres of `grid`; with the coarse iterations spent. A start for the conjugate
    /// gradients of a contact from rest, in place of the seed from the overlap: the smooth part of
    /// the pressure is right from the start, and the fine iterations only correct the rest.
    /// `None` where nothing overlaps (δn ≤ 0: the answer is no pressure, found without a
    /// solve), where `grid` has no even coarser level, or when the coarse solve fails (the fine
    /// solve then starts from the seed, as without a guess).
    fn coarse_guess(&self, grid: &Grid, delta_n: f64) -> Option<(Vec<f64>, usize)> {
        let n = grid.n / 2;
        if delta_n <= 0.0 || n < COARSEST || !n.is_multiple_of(2) {
            return None;
        }
        let coarse = Grid::covering(n, grid.coordinate(grid.n - 1) + 0.5 * grid.h);
        let settings = Settings {
            normal_tolerance: COARSE_TOLERANCE_FACTOR * self.settings.normal_tolerance,
            ..self.settings
        };
        let mut contact = self.contact(&coarse, settings);
        let mut iterations = self.start_from_coarse(&mut contact, &coarse, delta_n).ok()?;
        iterations += contact.advance(delta_n, &[]).ok()?.normal_iterations;
        let pressure = contact.pressure();
        let guess = grid
            .centres()
            .into_iter()
            .map(|c| coarse.interpolate(pressure, c).max(0.0));
        Some((guess.collect(), iterations))
    }

    /// Gives `contact` (on `grid`, at rest) the coarser grids' answer at `delta_n` as the start
    /// of its next normal solve, where there is one ([`NormalModel::coarse_guess`]); returns the
    /// coarse iterations spent.
    fn start_from_coarse(
        &self,
        contact: &mut GridContact,
        grid: &Grid,
        delta_n: f64,
    ) -> Result<usize, ContactError> {
        match self.coarse_guess(grid, delta_n) {
            Some((guess, spent)) => contact.guess_normal(guess).map(|()| spent),
            None => Ok(0),
        }
    }
}

/// The contact's state on one grid.
pub struct ContactState {
    grid: Grid,
    model: NormalModel,
    contact: GridContact,
    snapshot: Snapshot,
}

impl ContactState {
    /// The unloaded contact of `scene` on `grid`; the Cerruti compliance is built only when the
    /// scene has friction and a tangential path.
    pub fn new(scene: &Scene, grid: Grid, tolerances: Tolerances) -> Self {
        let compliance = PairCompliance::of(&scene.pair);
        let settings = Settings {
            normal_tolerance: tolerances.normal,
            tangential_tolerance: tolerances.tangential,
            max_iterations: tolerances.max_iterations,
            method: Method::Iterative,
            // Pressure per unit overlap of Hertz's order, E*/c_max, to seed the normal solver.
            seed_stiffness: Some(scene.pair.effective_modulus() / scene.max_contact_radius().max(grid.h)),
        };
        let model = NormalModel {
            compliance,
            r_star: scene.pair.effective_radius(),
            settings,
        };
        let contact = model.contact(&grid, settings);
        let contact = if scene.friction > 0.0 && !scene.path.is_normal_only() {
            contact
                .with_friction(
                    FftCompliance::<TangentialPrecision>::tangential(&grid, &compliance),
                    FrictionSet::Disc,
                    scene.friction,
                )
                .expect("the grid's two compliances fit")
        } else {
            contact
        };
        let len = grid.len();
        Self {
            model,
            contact,
            snapshot: Snapshot {
                grid,
                pressure: vec![0.0; len],
                traction: vec![[0.0; 2]; len],
                stick: vec![false; len],
                slip: vec![[0.0; 2]; len],
                friction: scene.friction,
            },
            grid,
        }
    }

    /// The fields after the last increment.
    pub fn snapshot(&self) -> &Snapshot {
        &self.snapshot
    }

    /// The gap opened: the engine forgets the contact and the fields are zero.
    pub fn release(&mut self) {
        self.contact.release();
        let s = &mut self.snapshot;
        s.pressure.fill(0.0);
        s.traction.fill([0.0; 2]);
        s.slip.fill([0.0; 2]);
        s.stick.fill(false);
    }

    /// Moves to approach `delta_n` with a tangential shift increment `shift` along x.
    pub fn advance(&mut self, delta_n: f64, shift: f64) -> Result<IncrementCost, IncrementError> {
        // A contact from rest starts from the coarser grids' answer (nested iteration).
        let coarse_iterations = if self.contact.normal_force() == 0.0 {
            (self.model)
                .start_from_coarse(&mut self.contact, &self.grid, delta_n)
                .map_err(IncrementError::Engine)?
        } else {
            0
        };
        let cost = self
            .contact
            .advance(delta_n, &[shift, 0.0])
            .map_err(IncrementError::Engine)?;
        let len = self.grid.len();
        let s = &mut self.snapshot;
        s.pressure.copy_from_slice(self.contact.pressure());
        s.traction = panel_vectors(self.contact.traction(), len);
        s.slip = panel_vectors(self.contact.slip(), len);
        s.stick = if s.friction > 0.0 && self.contact.traction().is_empty() {
            // Friction without a tangential path (no Cerruti operator built): nothing loads the
            // traction, so every panel in contact sticks.
            s.pressure.iter().map(|&p| p > 0.0).collect()
        } else {
            self.contact.stick()
        };
        self.check_window()?;
        Ok(IncrementCost {
            normal_iterations: coarse_iterations + cost.normal_iterations,
            tangential_iterations: cost.tangential.iterations,
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
}
