//! The method of dimensionality reduction (Popov & Heß 2015, *Method of Dimensionality Reduction
//! in Contact Mechanics and Friction*, ch. 2–4): exact Mindlin–Deresiewicz for any oblique history.
//!
//! The 3D contact of two elastically similar bodies with gap profile f(r) maps onto a rigid 1D
//! profile g(x) pressed into a Winkler foundation of independent springs of spacing Δx with
//! normal stiffness E* Δx and tangential stiffness G̃ Δx, where
//!
//! ```text
//! g(x) = |x| ∫₀^|x| f'(r) / √(x² − r²) dr      (f = r²/2R*  ⇒  g = x²/R*)
//! G̃   = [(2 − ν1)/(4 G1) + (2 − ν2)/(4 G2)]⁻¹ = 4 G*   (G*: Mindlin's, see `ContactPair`)
//! ```
//! At approach d a spring at x carries w(x) = d − g(x) when positive; the springs in contact span
//! |x| < c = √(R* d), the Hertz radius, and P = 2 ∫₀^c E* w dx = 4/3 E* c d (Hertz).
//!
//! Tangentially every spring in contact keeps its own displacement u(x) and obeys Coulomb's law
//! on its own: an increment Δδt is first taken up elastically (u ← u + Δδt); where that would
//! exceed |G̃ u| ≤ μ E* w(x), the spring slips and u is set to the limit. A spring leaving contact
//! forgets its history. Q = 2 ∫₀^c G̃ u dx. The stick zone is where no spring slipped in the step:
//! its radius is the innermost slipping spring (c when none slips, 0 in gross sliding); in the
//! MDR that 1D radius equals the 3D stick radius.
//!
//! Surface tractions come back from the bed by the MDR inverse transform (Popov & Heß 2015,
//! eqs. 3.22 and 4.27): with the linear force densities f_z = E* w and f_x = G̃ u,
//!
//! ```text
//! p(r) = −(1/π) ∫_r^∞ f_z'(x) / √(x² − r²) dx,    q(r) = −(1/π) ∫_r^∞ f_x'(x) / √(x² − r²) dx.
//! ```
//! They are evaluated at path positions only, with f linear between the nodes of the bed
//! averaged in blocks down to at most `TRANSFORM_NODES` nodes, so that each segment integrates
//! in closed form: ∫ dx / √(x² − r²) = ln(x + √(x² − r²)).
//!
//! Discretisation: springs at the midpoints of `springs` equal cells on [0, 1.05 c_max] (the
//! problem is even in x, so one half is modelled and doubled). P then has a relative error of
//! order (Δx/c)², from the one cell cut by the contact edge.

use spherecontact_model::driver::{self, PathIncrement, PathModel};
use spherecontact_model::hertz::Hertz;
use spherecontact_model::history::{
    History, Layout, Metadata, StepResult, SurfaceField, TangentialComponents,
};
use spherecontact_model::limits::MAX_MDR_SPRINGS;
use spherecontact_model::pair::ContactPair;
use spherecontact_model::path::Step;
use spherecontact_model::resolution::{self, ResolutionError};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};

/// Most nodes of the bed used by the inverse transform (a block average of the springs).
const TRANSFORM_NODES: usize = 500;

/// Sample points of the surface fields along x.
const FIELD_POINTS: usize = 101;

/// Partial sums kept apart in the spring loop.
const LANES: usize = 8;

/// Springs beyond the largest contact radius, as a fraction of it: keeps the contact edge inside
/// the window at every step.
const WINDOW_MARGIN: f64 = 0.05;

/// The MDR solver with a given number of springs on the half-line.
pub struct Mdr {
    /// Springs on [0, 1.05 c_max].
    pub springs: usize,
}

impl Default for Mdr {
    fn default() -> Self {
        Self { springs: 4000 }
    }
}

/// The state of the spring bed along a path (or an impact, `spherecontact-impact`).
pub struct SpringBed {
    /// Profile g(x_i) = x_i²/R* [m].
    profile: Vec<f64>,
    /// Tangential displacement u_i of each spring [m].
    u: Vec<f64>,
    /// Prefix sums of the profile: profile_sums[k] = Σ_{i<k} g(x_i) [m].
    profile_sums: Vec<f64>,
    /// Springs [0, touched) were in contact at the previous step.
    touched: usize,
    /// Spacing Δx [m].
    dx: f64,
    /// E* [Pa].
    normal_modulus: f64,
    /// G̃ = 4 G* [Pa].
    tangential_modulus: f64,
    /// μ.
    friction: f64,
}

/// The bed's forces after one increment.
pub struct BedState {
    /// P [N].
    pub normal_force: f64,
    /// Q [N].
    pub tangential_force: f64,
    /// The stick radius [m].
    pub stick_radius: f64,
}

impl SpringBed {
    /// A bed of `springs` springs for `scene`'s pair, friction and largest contact.
    pub(super) fn new(scene: &Scene, springs: usize) -> Self {
        Self::with_window(&scene.pair, scene.friction, scene.max_contact_radius(), springs)
    }

    /// A bed of `springs` springs for `pair` and friction `friction`, whose window holds every
    /// contact radius up to `max_contact_radius` [m] (with the margin `WINDOW_MARGIN`).
    pub fn with_window(pair: &ContactPair, friction: f64, max_contact_radius: f64, springs: usize) -> Self {
        let half_width = (1.0 + WINDOW_MARGIN) * max_contact_radius;
        let dx = half_width / springs as f64;
        let r_star = pair.effective_radius();
        // Spring i sits at the midpoint x_i = (i + ½) Δx of its cell.
        let profile: Vec<f64> = (0..springs)
            .map(|i| ((i as f64 + 0.5) * dx).powi(2) / r_star)
            .collect();
        let profile_sums = std::iter::once(0.0)
            .chain(profile.iter().scan(0.0, |sum, g| {
                *sum += g;
                Some(*sum)
            }))
            .collect();
        Self {
            profile,
            profile_sums,
            u: vec![0.0; springs],
            touched: 0,
            dx,
            normal_modulus: pair.effective_modulus(),
            tangential_modulus: 4.0 * pair.mindlin_shear_modulus(),
            friction,
        }
    }

    /// The largest approach at which every spring in contact lies inside the window [m]: the
    /// profile height of the outermost spring.
    pub fn reach(&self) -> f64 {
        self.profile.last().copied().unwrap_or(0.0)
    }

    /// Friction μ from the next increment on (the impact's total-force bound changes it per step).
    pub fn set_friction(&mut self, friction: f64) {
        self.friction = friction;
    }

    /// Every spring leaves contact and forgets its history.
    pub fn release(&mut self) {
        self.u[..self.touched].fill(0.0);
        self.touched = 0;
    }

    /// P at approach `delta_n` (no state changes: the normal bed has no memory) and its slope
    /// dP/dδn = 2E* Δx k, k the springs in contact.
    pub fn normal_force(&self, delta_n: f64) -> (f64, f64) {
        let in_contact = self.profile.partition_point(|&g| g < delta_n);
        let normal = in_contact as f64 * delta_n - self.profile_sums[in_contact];
        let scale = 2.0 * self.normal_modulus * self.dx;
        (scale * normal, scale * in_contact as f64)
    }

    /// Q after a trial step to approach `delta_n` with shift increment `increment_t`, without
    /// committing it, and its slope dQ/d(increment) = 2G̃ Δx (springs that stick). Springs beyond
    /// those that touched before carry u = 0, as [`Self::advance`] leaves them.
    pub fn trial(&self, delta_n: f64, increment_t: f64) -> (f64, f64) {
        let in_contact = self.profile.partition_point(|&g| g < delta_n);
        let slip_ratio = self.friction * self.normal_modulus / self.tangential_modulus;
        let (mut sum, mut sticking) = (0.0, 0usize);
        for (&u, g) in self.u[..in_contact.min(self.touched)].iter().zip(&self.profile) {
            let limit = slip_ratio * (delta_n - g);
            let moved = u + increment_t;
            sum += moved.clamp(-limit, limit);
            sticking += usize::from(moved.abs() < limit);
        }
        for g in &self.profile[self.touched.min(in_contact)..in_contact] {
            let limit = slip_ratio * (delta_n - g);
            sum += increment_t.clamp(-limit, limit);
            sticking += usize::from(increment_t.abs() < limit);
        }
        let scale = 2.0 * self.tangential_modulus * self.dx;
        (scale * sum, scale * sticking as f64)
    }

    /// Moves the rigid profile to approach `delta_n` and shifts it by `increment_t`.
    pub fn advance(&mut self, delta_n: f64, increment_t: f64) -> BedState {
        // The springs in contact, w = δn − g(x) > 0, are a prefix of the bed (g grows with x);
        // those beyond it that touched before have left contact and forget their history.
        let in_contact = self.profile.partition_point(|&g| g < delta_n);
        if in_contact < self.touched {
            self.u[in_contact..self.touched].fill(0.0);
        }
        self.touched = in_contact;
        let slip_ratio = self.friction * self.normal_modulus / self.tangential_modulus;
        // Independent partial sums of u: a serial float sum would bind the loop to the
        // latency of one addition per spring.
        let mut lanes = [0.0_f64; LANES];
        let mut innermost_slip = usize::MAX;
        let chunks = self.u[..in_contact]
            .chunks_mut(LANES)
            .zip(self.profile.chunks(LANES));
        for (c, (u_chunk, g_chunk)) in chunks.enumerate() {
            // Which lanes slipped, as bits: no branch inside the chunk.
            let mut slipped = 0_u32;
            for (lane, (u, g)) in u_chunk.iter_mut().zip(g_chunk).enumerate() {
                let limit = slip_ratio * (delta_n - g);
                let trial = *u + increment_t;
                *u = trial.clamp(-limit, limit);
                slipped |= u32::from(*u != trial) << lane;
                lanes[lane] += *u;
            }
            if slipped != 0 && innermost_slip == usize::MAX {
                innermost_slip = c * LANES + slipped.trailing_zeros() as usize;
            }
        }
        let tangential: f64 = lanes.iter().sum();
        // Σ w = k δn − Σ_{i<k} g_i, from the prefix sums of the profile.
        let normal = in_contact as f64 * delta_n - self.profile_sums[in_contact];
        let edge = |index: usize| index as f64 * self.dx; // the left edge of a spring's cell
        BedState {
            normal_force: 2.0 * self.normal_modulus * normal * self.dx,
            tangential_force: 2.0 * self.tangential_modulus * tangential * self.dx,
            stick_radius: edge(innermost_slip.min(in_contact)),
        }
    }
}

/// The bed as the path walker drives it, keeping the surface fields of the path positions.
struct Walker<'a> {
    scene: &'a Scene,
    bed: SpringBed,
    hertz: Hertz,
    fields: Vec<SurfaceField>,
}

impl PathModel for Walker<'_> {
    fn advance(&mut self, increment: &PathIncrement) -> Result<StepResult, SolveError> {
        let step = increment.step;
        let state = self.bed.advance(step.delta_n, increment.shift());
        if let Some(position) = step.position.filter(|&p| self.scene.records_fields_at(p)) {
            self.fields.push(self.bed.surface_field(
                position,
                step.delta_n,
                state.stick_radius,
                FIELD_POINTS,
            ));
        }
        Ok(StepResult {
            normal_force: Some(state.normal_force),
            tangential_force: Some(state.tangential_force),
            contact_radius: Some(self.hertz.contact_radius(step.delta_n)),
            // The bed resolves the stick edge to one spring cell (a cell edge, at or beyond the
            // last sticking spring); the stick zone lies within Hertz's contact radius, which
            // this model reports (as mdr-domain's series model).
            stick_radius: Some(state.stick_radius.min(self.hertz.contact_radius(step.delta_n))),
            ..StepResult::at(step)
        })
    }

    /// Every spring leaves contact and forgets its history.
    fn release(&mut self, _step: &Step) {
        self.bed.release();
    }

    /// The bed gives P and Q; p0 is not among its rows.
    fn reports_peak_pressure(&self) -> bool {
        false
    }
}

impl SpringBed {
    /// p(r) and q(r) at the radii `radii` by the inverse transform, for approach `delta_n`.
    fn tractions(&self, delta_n: f64, radii: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let block = self.u.len().div_ceil(TRANSFORM_NODES);
        let nodes: Vec<(f64, f64, f64)> = self
            .u
            .chunks(block)
            .zip(self.profile.chunks(block))
            .enumerate()
            .map(|(j, (u, g))| {
                let x = (j as f64 + 0.5) * block as f64 * self.dx;
                let mean = |values: &mut dyn Iterator<Item = f64>| values.sum::<f64>() / u.len() as f64;
                let w = mean(&mut g.iter().map(|g| (delta_n - g).max(0.0)));
                (
                    x,
                    self.normal_modulus * w,
                    self.tangential_modulus * mean(&mut u.iter().copied()),
                )
            })
            .collect();
        // Slopes of the linear force densities (f_z, f_x) on each segment between nodes.
        let slopes: Vec<(f64, f64)> = nodes
            .windows(2)
            .map(|pair| {
                let (a, b) = (pair[0], pair[1]);
                ((b.1 - a.1) / (b.0 - a.0), (b.2 - a.2) / (b.0 - a.0))
            })
            .collect();
        radii
            .iter()
            .map(|&r| {
                // Segments ending beyond r contribute; the antiderivative at each node is shared
                // by the segment it ends and the one it starts, and by p and q.
                let antiderivative = |x: f64| (x + (x * x - r * r).max(0.0).sqrt()).ln();
                let first = nodes[1..].partition_point(|n| n.0 <= r);
                let mut lower = antiderivative(nodes.get(first).map_or(r, |n| n.0.max(r)));
                let (mut p, mut q) = (0.0, 0.0);
                for (node, slope) in nodes[first + 1..].iter().zip(&slopes[first..]) {
                    let upper = antiderivative(node.0);
                    p += slope.0 * (upper - lower);
                    q += slope.1 * (upper - lower);
                    lower = upper;
                }
                (-p / std::f64::consts::PI, -q / std::f64::consts::PI)
            })
            .unzip()
    }

    /// The surface field at a path position, sampled at `points` radii.
    pub(super) fn surface_field(
        &self,
        position: usize,
        delta_n: f64,
        stick_radius: f64,
        points: usize,
    ) -> SurfaceField {
        let spacing = self.u.len() as f64 * self.dx / (points - 1) as f64;
        let radii: Vec<f64> = (0..points).map(|k| k as f64 * spacing).collect();
        let (pressure, traction) = self.tractions(delta_n, &radii);
        SurfaceField {
            position,
            points: radii.iter().map(|&r| [r, 0.0]).collect(),
            pressure,
            traction: Some(traction.into_iter().map(|q| [q, 0.0]).collect()),
            stick: Some(radii.iter().map(|&r| r < stick_radius).collect()),
            slip: None,
            components: TangentialComponents::AlongX,
            layout: Layout::Profile,
        }
    }
}

impl Solver for Mdr {
    fn name(&self) -> &'static str {
        "mdr"
    }

    fn kind(&self) -> Kind {
        Kind::Analytic
    }

    fn description(&self) -> &'static str {
        "method of dimensionality reduction (Popov & Heß): exact Mindlin–Deresiewicz for any history"
    }

    fn resolution_ladder(&self, _scene: &Scene) -> Vec<Box<dyn Solver>> {
        [250, 500, 1000, 2000, 4000, 8000, 16000]
            .into_iter()
            .map(|springs| Box::new(Mdr { springs }) as Box<dyn Solver>)
            .collect()
    }

    fn estimated_seconds(&self, scene: &Scene) -> Option<f64> {
        Some(spherecontact_model::cost::mdr(self.springs, scene.steps().len()))
    }

    /// `n`: springs on the half-line, 1 ≤ n ≤ [`MAX_MDR_SPRINGS`].
    fn at_resolution(&self, _scene: &Scene, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        let springs = resolution::count(self.name(), value, 1, MAX_MDR_SPRINGS, false)?;
        Ok(Box::new(Mdr { springs }))
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        if !(1..=MAX_MDR_SPRINGS).contains(&self.springs) {
            let message = format!("mdr needs 1 to {MAX_MDR_SPRINGS} springs (got {})", self.springs);
            return Err(SolveError::Failed(message));
        }
        let mut warnings = Vec::new();
        let (rows, fields) = match driver::never_closed(scene, false) {
            Some(rows) => {
                // No spring ever touches.
                warnings.push(driver::NEVER_CLOSES.to_string());
                (rows, Vec::new())
            }
            None => {
                let mut walker = Walker {
                    scene,
                    bed: SpringBed::new(scene, self.springs),
                    hertz: scene.hertz(),
                    fields: Vec::new(),
                };
                (driver::walk(scene, &mut walker)?, walker.fields)
            }
        };
        Ok(History {
            metadata: Metadata {
                model: "MDR: 1D Winkler bed equivalent to elastically similar half-spaces".into(),
                resolution: format!(
                    "{} springs on [0, {:.3e} m]",
                    self.springs,
                    (1.0 + WINDOW_MARGIN) * scene.max_contact_radius()
                ),
                warnings,
                // The stick radius is a cell edge: within one spacing of the true one.
                extra: [(
                    "spring_spacing_m".to_owned(),
                    serde_json::json!(
                        (1.0 + WINDOW_MARGIN) * scene.max_contact_radius() / self.springs as f64
                    ),
                )]
                .into(),
                ..Metadata::default()
            },
            steps: rows,
            fields,
        })
    }
}
