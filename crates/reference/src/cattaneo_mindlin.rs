//! Cattaneo–Mindlin: tangential loading of a Hertz contact at constant normal load, with
//! Masing's rules for unloading and reloading (Mindlin 1949; Mindlin & Deresiewicz 1953;
//! Johnson 1985, §7.1).
//!
//! At normal load P and contact radius c, a tangential displacement δ from a virgin state gives
//!
//! ```text
//! Q(δ) = f(δ) = μP [1 − (1 − δ/δs)^{3/2}]   for 0 ≤ δ ≤ δs,   μP beyond (gross sliding)
//! δs   = 3μP / (16 c G*)                    (G*: Mindlin's effective shear modulus)
//! stick radius  c_s = c (1 − Q/μP)^{1/3}
//! ```
//! so that dQ/dδ at δ = 0 is K_T0 = 8 G* c. The traction of that virgin state is the difference
//! of two Hertz-like ellipsoids (Johnson 1985, eq. 7.50):
//!
//! ```text
//! q_v(r; S) = (μ p0 / c) [ √(c² − r²) − √(c_s² − r²) ],   c_s = c (1 − S/μP)^{1/3},
//! ```
//! (each root taken as zero where its argument is negative), S the load the stick zone has shed,
//! S = |Q| on the virgin curve. Masing: from a reversal point (δr, Qr) the branch is
//! Q = Qr ± 2 f(|δ − δr|/2), with stick radius c (1 − |Q − Qr|/2μP)^{1/3}, and by superposition
//! q = q_r ± 2 q_v(r; |Q − Qr|/2), q_r the traction at the reversal. The memory rules
//! of Masing and Madelung close the loops: a branch that reaches the reversal point before its
//! own start continues on the branch that led there, and the first branch off the virgin curve
//! rejoins the virgin curve at the mirror of its start.
//!
//! The normal load must be constant while the tangential displacement changes; this solver
//! reports itself not applicable otherwise (MDR covers varying loads).

use spherecontact_model::hertz::Hertz;
use spherecontact_model::history::{
    History, Layout, Metadata, StepResult, SurfaceField, TangentialComponents,
};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};

/// The virgin tangential curve of one Hertz contact.
#[derive(Clone, Copy, Debug)]
struct VirginCurve {
    /// Full-sliding force μP [N].
    sliding_force: f64,
    /// Displacement at the onset of gross sliding δs [m].
    sliding_displacement: f64,
}

impl VirginCurve {
    /// q_v(r; S) / (μ p0 / c) = √(c² − r²)₊ − √(c_s² − r²)₊, c_s = c (1 − S/μP)^{1/3}.
    fn traction_shape(&self, r: f64, contact_radius: f64, shed: f64) -> f64 {
        let stick = stick_radius(contact_radius, shed, self.sliding_force);
        let root = |a: f64| (a * a - r * r).max(0.0).sqrt();
        root(contact_radius) - root(stick)
    }

    /// f(δ) for δ ≥ 0.
    fn force(&self, delta: f64) -> f64 {
        if delta >= self.sliding_displacement {
            return self.sliding_force;
        }
        self.sliding_force * (1.0 - (1.0 - delta / self.sliding_displacement).powf(1.5))
    }
}

/// A reversal point of the tangential history.
#[derive(Clone, Copy, Debug)]
struct Reversal {
    delta: f64,
    force: f64,
}

/// Masing's hysteresis with Masing–Madelung memory over a virgin curve.
#[derive(Debug)]
struct Masing {
    curve: VirginCurve,
    /// Reversal points still remembered, oldest first.
    reversals: Vec<Reversal>,
    /// Current displacement, force and direction of motion (±1, 0 before any motion).
    delta: f64,
    force: f64,
    direction: f64,
}

impl Masing {
    fn new(curve: VirginCurve) -> Self {
        Self {
            curve,
            reversals: Vec::new(),
            delta: 0.0,
            force: 0.0,
            direction: 0.0,
        }
    }

    /// Moves to displacement `delta` and returns (Q, |Q − Q_branch start| / 2 on a Masing branch,
    /// or |Q| on the virgin curve): the load the stick zone has shed.
    fn move_to(&mut self, delta: f64) -> (f64, f64) {
        let direction = (delta - self.delta).signum();
        if delta != self.delta {
            if self.direction != 0.0 && direction != self.direction {
                self.reversals.push(Reversal {
                    delta: self.delta,
                    force: self.force,
                });
            }
            self.direction = direction;
            self.forget_closed_loops(delta);
        }
        self.delta = delta;
        let (force, shed) = match self.reversals.last() {
            Some(r) => {
                let half = self.curve.force(0.5 * (delta - r.delta).abs());
                (r.force + direction_of(delta - r.delta) * 2.0 * half, half)
            }
            None => {
                let f = self.curve.force(delta.abs());
                (f.copysign(delta), f)
            }
        };
        self.force = force;
        (force, shed)
    }

    /// The traction q(r) of the current state, as a multiple of μ p0 / c: the virgin branch and
    /// every remembered Masing branch superposed (factor 1 for the virgin branch, 2 after it).
    fn traction_shape(&self, r: f64, contact_radius: f64) -> f64 {
        let forces = self
            .reversals
            .iter()
            .map(|rev| rev.force)
            .chain(std::iter::once(self.force));
        let (mut q, mut previous, mut factor) = (0.0, 0.0, 1.0);
        for force in forces {
            let change = force - previous;
            let shed = change.abs() / factor;
            q += factor * direction_of(change) * self.curve.traction_shape(r, contact_radius, shed);
            (previous, factor) = (force, 2.0);
        }
        q
    }

    /// Pops the reversal points that the motion to `delta` has passed.
    fn forget_closed_loops(&mut self, delta: f64) {
        while let Some(&last) = self.reversals.last() {
            let target = match self.reversals.len() {
                1 => -last.delta, // the mirror point on the virgin curve
                n => self.reversals[n - 2].delta,
            };
            if self.direction * (delta - target) <= 0.0 {
                break;
            }
            let pop = if self.reversals.len() == 1 { 1 } else { 2 };
            self.reversals.truncate(self.reversals.len() - pop);
        }
    }
}

/// The stick radius c (1 − S/μP)^{1/3} once the stick zone has shed the load S (0 in gross sliding).
fn stick_radius(contact_radius: f64, shed: f64, sliding_force: f64) -> f64 {
    if sliding_force > 0.0 && shed < sliding_force {
        contact_radius * (1.0 - shed / sliding_force).cbrt()
    } else {
        0.0
    }
}

/// Cattaneo–Mindlin's traction q(r) [Pa] of a Hertz contact at approach `delta_n`, loaded
/// tangentially from a virgin state to the force `force` at constant normal load, signed as
/// the force: (μ p0 / c) [√(c² − r²)₊ − √(c_s² − r²)₊] with c_s = c (1 − |Q|/μP)^{1/3}
/// (Johnson 1985, eq. 7.50); μ p(r) in gross sliding. Zero outside a closed contact.
pub fn virgin_traction(hertz: &Hertz, friction: f64, delta_n: f64, force: f64, r: f64) -> f64 {
    let c = hertz.contact_radius(delta_n);
    if c <= 0.0 {
        return 0.0;
    }
    let curve = VirginCurve {
        sliding_force: friction * hertz.force(delta_n),
        // The traction's shape does not depend on the displacement scale.
        sliding_displacement: f64::INFINITY,
    };
    let scale = friction * hertz.peak_pressure(delta_n) / c;
    scale * curve.traction_shape(r, c, force.abs()).copysign(force)
}

/// Cattaneo–Mindlin's stick radius c (1 − |Q|/μP)^{1/3} [m] at approach `delta_n` and tangential
/// force `force` (0 in gross sliding).
pub fn virgin_stick_radius(hertz: &Hertz, friction: f64, delta_n: f64, force: f64) -> f64 {
    stick_radius(
        hertz.contact_radius(delta_n),
        force.abs(),
        friction * hertz.force(delta_n),
    )
}

/// Sample points of the surface fields along x: from the centre to beyond the largest contact.
const FIELD_POINTS: usize = 101;

/// The sign of a non-zero displacement change (+1 for zero).
fn direction_of(change: f64) -> f64 {
    if change < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// p(r), q(r) and stick status along x at one path position (traction zero before tangential
/// loading starts).
fn surface_field(
    scene: &Scene,
    position: usize,
    delta_n: f64,
    masing: Option<&Masing>,
    stick_radius: Option<f64>,
) -> SurfaceField {
    let hertz = scene.hertz();
    let c = hertz.contact_radius(delta_n);
    let scale = scene.friction * hertz.peak_pressure(delta_n) / c;
    let spacing = 1.05 * scene.max_contact_radius() / (FIELD_POINTS - 1) as f64;
    let radii: Vec<f64> = (0..FIELD_POINTS).map(|k| k as f64 * spacing).collect();
    let traction = |r: f64| masing.map_or(0.0, |m| scale * m.traction_shape(r, c));
    SurfaceField {
        position,
        points: radii.iter().map(|&r| [r, 0.0]).collect(),
        pressure: radii.iter().map(|&r| hertz.pressure(delta_n, r)).collect(),
        traction: Some(radii.iter().map(|&r| [traction(r), 0.0]).collect()),
        stick: Some(radii.iter().map(|&r| r < stick_radius.unwrap_or(c)).collect()),
        slip: None,
        components: TangentialComponents::AlongX,
        layout: Layout::Profile,
    }
}

/// The Cattaneo–Mindlin closed form as a solver.
pub struct CattaneoMindlin;

impl CattaneoMindlin {
    /// The first step at which the tangential displacement leaves its starting value.
    fn tangential_start(scene: &Scene) -> Result<usize, SolveError> {
        let steps = scene.steps();
        let start = steps
            .iter()
            .position(|s| s.delta_t != steps[0].delta_t)
            .unwrap_or(steps.len());
        let base = if start > 0 { steps[start - 1] } else { steps[0] };
        if let Some(bad) = steps[start..].iter().find(|s| s.delta_n != base.delta_n) {
            return Err(SolveError::NotApplicable(format!(
                "cattaneo-mindlin needs a constant normal approach once tangential loading starts \
                 (δn = {:.4e} m at step {}, {:.4e} m at step {})",
                base.delta_n, base.index, bad.delta_n, bad.index
            )));
        }
        if start < steps.len() && base.delta_n <= 0.0 {
            return Err(SolveError::NotApplicable(format!(
                "tangential loading starts at step {} with the gap open (δn = {:.4e} m)",
                base.index, base.delta_n
            )));
        }
        Ok(start)
    }
}

impl Solver for CattaneoMindlin {
    fn name(&self) -> &'static str {
        "cattaneo-mindlin"
    }

    fn kind(&self) -> Kind {
        Kind::Analytic
    }

    fn description(&self) -> &'static str {
        "Cattaneo–Mindlin at constant normal load, Masing unloading and reloading"
    }

    fn estimated_seconds(&self, scene: &Scene) -> Option<f64> {
        Some(spherecontact_model::cost::law(scene.steps().len()))
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        let start = Self::tangential_start(scene)?;
        let hertz = scene.hertz();
        let steps = scene.steps();
        let origin = steps[0].delta_t;
        let mut masing: Option<Masing> = None;
        let mut fields = Vec::new();
        let rows = steps
            .iter()
            .map(|step| {
                let (p, c) = (hertz.force(step.delta_n), hertz.contact_radius(step.delta_n));
                let mut row = StepResult {
                    normal_force: Some(p),
                    contact_radius: Some(c),
                    peak_pressure: Some(hertz.peak_pressure(step.delta_n)),
                    tangential_force: Some(0.0),
                    stick_radius: (c > 0.0).then_some(c),
                    ..StepResult::at(step)
                };
                if step.index >= start {
                    let sliding_force = scene.friction * p;
                    let state = masing.get_or_insert_with(|| {
                        Masing::new(VirginCurve {
                            sliding_force,
                            sliding_displacement: 3.0 * sliding_force
                                / (16.0 * c * scene.pair.mindlin_shear_modulus()),
                        })
                    });
                    let (q, shed) = state.move_to(step.delta_t - origin);
                    row.tangential_force = Some(q);
                    row.stick_radius = Some(stick_radius(c, shed, sliding_force));
                }
                if let (Some(position), true) =
                    (step.position.filter(|&p| scene.records_fields_at(p)), c > 0.0)
                {
                    fields.push(surface_field(
                        scene,
                        position,
                        step.delta_n,
                        masing.as_ref(),
                        row.stick_radius,
                    ));
                }
                row
            })
            .collect();
        Ok(History {
            metadata: Metadata {
                model: "Cattaneo–Mindlin: Hertz contact, constant normal load, Masing hysteresis".into(),
                resolution: "closed form".into(),
                ..Metadata::default()
            },
            steps: rows,
            fields,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use spherecontact_model::fixtures::paper_pair;
    use spherecontact_model::hertz::Hertz;
    use spherecontact_model::pair::ContactPair;

    /// The paper's spheres at δn = 17 µm: P = 803.76 N, c = 0.92195 mm, μ = 0.2.
    fn paper_contact() -> (Hertz, ContactPair, f64) {
        let pair = paper_pair();
        (Hertz::of(&pair), pair, 17e-6)
    }

    fn masing() -> (Masing, f64, f64) {
        let (hertz, pair, delta) = paper_contact();
        let (p, c) = (hertz.force(delta), hertz.contact_radius(delta));
        let sliding_force = 0.2 * p;
        let curve = VirginCurve {
            sliding_force,
            sliding_displacement: 3.0 * sliding_force / (16.0 * c * pair.mindlin_shear_modulus()),
        };
        (Masing::new(curve), c, hertz.peak_pressure(delta))
    }

    /// ∫ q 2πr dr by the midpoint rule on 20 000 rings (the square-root edges limit it to ~1e-5).
    fn integrated(m: &Masing, c: f64, p0: f64) -> f64 {
        let n = 20_000;
        let dr = c / n as f64;
        let scale = 0.2 * p0 / c;
        (0..n)
            .map(|i| {
                let r = (i as f64 + 0.5) * dr;
                scale * m.traction_shape(r, c) * 2.0 * std::f64::consts::PI * r * dr
            })
            .sum()
    }

    #[test]
    fn virgin_traction_is_the_first_branch_of_the_solver() {
        // The public closed form equals the Masing state's traction on the virgin curve.
        let (mut m, c, p0) = masing();
        let (q, _) = m.move_to(0.4 * m.curve.sliding_displacement);
        let (hertz, _, delta) = paper_contact();
        for r in [0.0, 0.3 * c, 0.7 * c, 0.95 * c] {
            let expected = 0.2 * p0 / c * m.traction_shape(r, c);
            assert_relative_eq!(
                virgin_traction(&hertz, 0.2, delta, q, r),
                expected,
                max_relative = 1e-12
            );
        }
        let cs = virgin_stick_radius(&hertz, 0.2, delta, q);
        assert_relative_eq!(
            cs,
            c * (1.0 - q / (0.2 * hertz.force(delta))).cbrt(),
            max_relative = 1e-12
        );
        assert_eq!(
            virgin_traction(&hertz, 0.2, 0.0, q, 0.0),
            0.0,
            "no contact, no traction"
        );
    }

    #[test]
    fn traction_integrates_to_the_force_on_every_branch() {
        // Virgin loading, unloading past zero, reloading: a Masing loop, then a nested one.
        let (mut m, c, p0) = masing();
        for delta in [1.5e-6, 3.0e-6, -1.0e-6, 0.5e-6, -0.2e-6, 2.0e-6, 6.0e-6, -7.0e-6] {
            let (q, _) = m.move_to(delta);
            // Tolerance: the rings' midpoint rule at the √ edges of c and c_s, ~1e-5 of μP.
            assert_relative_eq!(integrated(&m, c, p0), q, epsilon = 1e-5 * m.curve.sliding_force);
        }
    }

    #[test]
    fn traction_never_exceeds_coulomb_and_equals_it_in_the_slip_annulus() {
        let (mut m, c, p0) = masing();
        let hertz_p = |r: f64| p0 * (1.0 - (r / c).powi(2)).max(0.0).sqrt();
        let scale = 0.2 * p0 / c;
        for delta in [2.0e-6, -1.0e-6, 1.0e-6, 5.0e-6] {
            m.move_to(delta);
            for k in 0..200 {
                let r = c * k as f64 / 200.0;
                let q = scale * m.traction_shape(r, c);
                assert!(
                    q.abs() <= 0.2 * hertz_p(r) * (1.0 + 1e-12) + 1e-9,
                    "|q({r})| = {q}"
                );
            }
        }
        // Virgin loading to δ = 2 µm: slip annulus c_s < r < c carries exactly μp.
        let (mut m, c, _) = masing(); // the same contact: hertz_p and scale still apply
        let (q, _) = m.move_to(2.0e-6);
        let stick = stick_radius(c, q.abs(), m.curve.sliding_force);
        for k in 1..10 {
            let r = stick + (c - stick) * k as f64 / 10.0;
            assert_relative_eq!(
                scale * m.traction_shape(r, c),
                0.2 * hertz_p(r),
                max_relative = 1e-12
            );
        }
    }

    #[test]
    fn masing_memory_rejoins_the_virgin_curve() {
        // Load to 2 µm, unload to 1 µm, reload past 2 µm: beyond it Q is on the virgin curve.
        let (mut m, _, _) = masing();
        m.move_to(2.0e-6);
        m.move_to(1.0e-6);
        let (q, _) = m.move_to(3.0e-6);
        assert_relative_eq!(q, m.curve.force(3.0e-6), max_relative = 1e-12);
        assert!(m.reversals.is_empty(), "the closed loop is forgotten");
        // First unloading branch reaches the mirror point and continues on the virgin curve.
        let (q, _) = m.move_to(-3.5e-6);
        assert_relative_eq!(q, -m.curve.force(3.5e-6), max_relative = 1e-12);
    }
}
