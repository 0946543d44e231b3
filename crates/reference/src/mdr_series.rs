//! Mindlin–Deresiewicz for a finite body: the exact MD model (the MDR spring bed, [`super::mdr`])
//! in series with the body's compliances relative to the half-space, normal and tangential.
//!
//! A finite element model of a cap or hemisphere is the half-space contact plus, to first order,
//! a far-field spring: the gripped face moves by the local Hertz / Mindlin–Deresiewicz approach and
//! shift plus Λ_n P and Λ_t Q, with Λ = Σ over the bodies of each body's compliance relative to the
//! half-space (computed by `fem::axisym::compliance`; tabulated against the contact radius, since
//! the sphere's own curvature adds a weak ln c dependence). Each increment solves
//!
//! ```text
//! x_n + Λ_n(c(x_n)) P(x_n) = δn,                     c(x) = √(R* x)
//! x_t + Λ_t(c(x_n)) Q(x_t − x_t,prev | bed) = δt
//! ```
//! for the local approach x_n and the local shift x_t; the bed's P is monotone in x_n, and its Q
//! in the shift increment (each spring's clamp is monotone), so each is one scalar monotone root,
//! found by Newton's method on the piecewise-linear bed safeguarded by bisection. The bed keeps
//! its memory (every spring's displacement) exactly as MDR does; with Λ = 0 the local values are
//! the imposed ones without a solve, so the model reduces exactly to MDR.
//!
//! The contact radius and peak pressure are Hertz's at the local approach, and so is the pressure
//! profile at path positions (the corrected Hertz profile); q(r) comes from the bed's inverse
//! transform as in MDR.

use serde_json::json;

use super::mdr::SpringBed;
use spherecontact_model::history::{History, Metadata, StepResult};
use spherecontact_model::progress;
use spherecontact_model::scene::Scene;

/// Sample points of the surface fields (the reference profile of field checks: 4× MDR's).
const FIELD_POINTS: usize = 401;

/// The compliances in series with the contact [m/N] (summed over both bodies), tabulated against
/// the contact radius and interpolated linearly in ln c; constant beyond the table's ends.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SeriesCompliance {
    radii: Vec<f64>,
    normal: Vec<f64>,
    tangential: Vec<f64>,
}

impl SeriesCompliance {
    /// Constant compliances (one entry).
    pub fn constant(normal: f64, tangential: f64) -> Self {
        Self {
            radii: vec![1.0],
            normal: vec![normal],
            tangential: vec![tangential],
        }
    }

    /// A table at increasing positive `radii`; `None` if they are not, or the lengths differ, or
    /// a value is not finite.
    pub fn try_new(radii: Vec<f64>, normal: Vec<f64>, tangential: Vec<f64>) -> Option<Self> {
        let ok = !radii.is_empty()
            && radii.len() == normal.len()
            && radii.len() == tangential.len()
            && radii[0] > 0.0
            && radii.windows(2).all(|w| w[1] > w[0])
            && radii
                .iter()
                .chain(&normal)
                .chain(&tangential)
                .all(|v| v.is_finite());
        ok.then_some(Self {
            radii,
            normal,
            tangential,
        })
    }

    /// (Λ_n, Λ_t) at contact radius `c`.
    pub fn at(&self, c: f64) -> (f64, f64) {
        let k = self.radii.partition_point(|&r| r < c);
        if k == 0 || self.radii.len() == 1 {
            return (self.normal[0], self.tangential[0]);
        }
        if k == self.radii.len() {
            return (self.normal[k - 1], self.tangential[k - 1]);
        }
        let s = (c / self.radii[k - 1]).ln() / (self.radii[k] / self.radii[k - 1]).ln();
        let lerp = |v: &[f64]| v[k - 1] + s * (v[k] - v[k - 1]);
        (lerp(&self.normal), lerp(&self.tangential))
    }

    /// The table: (c, Λ_n, Λ_t) rows.
    pub fn rows(&self) -> Vec<[f64; 3]> {
        (0..self.radii.len())
            .map(|k| [self.radii[k], self.normal[k], self.tangential[k]])
            .collect()
    }

    fn is_zero(&self) -> bool {
        self.normal.iter().chain(&self.tangential).all(|&v| v == 0.0)
    }
}

/// The root of x + k(x) = `target` for a non-decreasing x + k(x), given `f(x) = (x + k(x) − target,
/// slope)`: Newton's method, exact on each linear piece of the bed, kept inside a bracket by
/// bisection where a kink would throw it out.
fn series_root(target: f64, f: impl Fn(f64) -> (f64, f64)) -> f64 {
    let (g0, _) = f(target);
    if g0 == 0.0 {
        return target;
    }
    // Bracket the root: from the uncoupled answer, step against the residual, doubling.
    let mut step = 2.0 * g0.abs();
    let (mut lo, mut hi) = if g0 > 0.0 {
        (target - step, target)
    } else {
        (target, target + step)
    };
    for _ in 0..200 {
        let (edge, inside) = if g0 > 0.0 {
            (lo, f(lo).0 <= 0.0)
        } else {
            (hi, f(hi).0 >= 0.0)
        };
        if inside || !edge.is_finite() {
            break;
        }
        step *= 2.0;
        if g0 > 0.0 {
            lo = target - step;
        } else {
            hi = target + step;
        }
    }
    let mut x = target;
    for _ in 0..200 {
        let (g, slope) = f(x);
        if g == 0.0 {
            return x;
        }
        if g > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let newton = x - g / slope;
        let next = if slope > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if next == x || hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(lo.abs()) {
            return next;
        }
        x = next;
    }
    x
}

/// MDR in series with a finite body's compliances.
pub struct SeriesMdr {
    /// Springs of the bed on [0, 1.05 c_max].
    pub springs: usize,
    /// The compliances in series.
    pub compliance: SeriesCompliance,
}

/// One increment's local state.
struct Local {
    approach: f64,
    normal_force: f64,
    tangential_force: f64,
    stick_radius: f64,
}

impl SeriesMdr {
    /// The history of `scene` along its whole path (the scene must close its gap somewhere).
    pub fn history(&self, scene: &Scene) -> History {
        let hertz = scene.hertz();
        let steps = scene.steps();
        let mut bed = SpringBed::new(scene, self.springs.max(1));
        // The local shift the bed has been moved to (the imposed one when Λ = 0).
        let (mut local_t, mut previous_t) = (steps[0].delta_t, steps[0].delta_t);
        let exact = self.compliance.is_zero();
        let mut rows = Vec::with_capacity(steps.len());
        let mut fields = Vec::new();
        for (k, step) in steps.iter().enumerate() {
            progress::tick(k, steps.len());
            let local = if exact {
                Self::commit(&mut bed, step.delta_n, step.delta_t - previous_t)
            } else {
                self.increment(
                    &mut bed,
                    &mut local_t,
                    step.delta_n,
                    step.delta_t,
                    hertz.effective_radius,
                )
            };
            previous_t = step.delta_t;
            let in_contact = local.approach > 0.0;
            if let (Some(position), true) =
                (step.position.filter(|&p| scene.records_fields_at(p)), in_contact)
            {
                let mut field = bed.surface_field(position, local.approach, local.stick_radius, FIELD_POINTS);
                field.pressure = field
                    .points
                    .iter()
                    .map(|x| hertz.pressure(local.approach, x[0]))
                    .collect();
                fields.push(field);
            }
            rows.push(StepResult {
                normal_force: Some(local.normal_force),
                tangential_force: Some(local.tangential_force),
                contact_radius: Some(hertz.contact_radius(local.approach)),
                peak_pressure: Some(hertz.peak_pressure(local.approach)),
                // The bed resolves the stick edge to one spring cell; the stick zone lies
                // within Hertz's contact radius, which this model reports.
                stick_radius: in_contact
                    .then(|| local.stick_radius.min(hertz.contact_radius(local.approach))),
                ..StepResult::at(step)
            });
        }
        let table: Vec<_> = self.compliance.rows().iter().map(|r| json!(r)).collect();
        History {
            metadata: Metadata {
                model: "MDR (exact Mindlin–Deresiewicz for half-spaces) in series with the modelled finite body's \
                        compliances relative to the half-space; Hertz's c, p0 and p(r) at the local approach"
                    .into(),
                resolution: format!(
                    "{} springs on [0, {:.3e} m]",
                    self.springs,
                    1.05 * scene.max_contact_radius()
                ),
                extra: [("compliance_c_normal_tangential_m_per_n".to_owned(), json!(table))]
                    .into_iter()
                    .collect(),
                ..Metadata::default()
            },
            steps: rows,
            fields,
        }
    }

    /// Solves one increment for the local approach and shift, then commits it to the bed.
    fn increment(
        &self,
        bed: &mut SpringBed,
        local_t: &mut f64,
        delta_n: f64,
        delta_t: f64,
        r_star: f64,
    ) -> Local {
        let compliance = |x: f64| self.compliance.at((r_star * x.max(0.0)).sqrt());
        let approach = series_root(delta_n, |x| {
            let (p, slope) = bed.normal_force(x);
            let lambda = compliance(x).0;
            (x + lambda * p - delta_n, 1.0 + lambda * slope)
        });
        let lambda_t = compliance(approach).1;
        let increment = series_root(delta_t - *local_t, |d| {
            let (q, slope) = bed.trial(approach, d);
            (d + lambda_t * q - (delta_t - *local_t), 1.0 + lambda_t * slope)
        });
        *local_t += increment;
        Self::commit(bed, approach, increment)
    }

    /// Advances the bed to local approach `approach` by shift increment `increment`.
    fn commit(bed: &mut SpringBed, approach: f64, increment: f64) -> Local {
        let state = bed.advance(approach, increment);
        Local {
            approach,
            normal_force: state.normal_force,
            tangential_force: state.tangential_force,
            stick_radius: state.stick_radius,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mdr::Mdr;
    use spherecontact_model::path::{LoadingPath, Position};
    use spherecontact_model::solver::Solver;

    /// The paper's spheres along `positions` (µm) with `substeps` per segment.
    fn scene(positions: &[(f64, f64)], substeps: usize) -> Scene {
        let positions: Vec<Position> = positions
            .iter()
            .map(|&(n, t)| Position {
                delta_n: n * 1e-6,
                delta_t: t * 1e-6,
            })
            .collect();
        let segments = positions.len() - 1;
        Scene {
            name: "series".into(),
            pair: spherecontact_model::fixtures::paper_pair(),
            friction: 0.2,
            path: LoadingPath::try_new(positions, vec![substeps; segments]).unwrap(),
            domain: Default::default(),
            fields: Default::default(),
        }
    }

    /// The paper's Figure 7 path.
    fn paper() -> Scene {
        let n = [
            0.0, 10.0, 14.0, 17.0, 17.0, 17.0, 17.0, 17.0, 20.0, 15.0, 12.0, 0.0,
        ];
        let t = [0.0, 0.0, 1.0, 1.0, 2.0, 3.0, 6.0, 2.0, -2.0, 0.0, -1.0, 0.0];
        let positions: Vec<(f64, f64)> = n.into_iter().zip(t).collect();
        scene(&positions, 20)
    }

    #[test]
    fn zero_compliance_is_mdr_exactly() {
        let s = paper();
        let mdr = Mdr::default().solve(&s).unwrap();
        let series = SeriesMdr {
            springs: Mdr::default().springs,
            compliance: SeriesCompliance::constant(0.0, 0.0),
        }
        .history(&s);
        for (a, b) in mdr.steps.iter().zip(&series.steps) {
            assert_eq!(
                (
                    a.normal_force,
                    a.tangential_force,
                    a.contact_radius,
                    // This model keeps the bed's stick edge within Hertz's c (MDR's may lie one
                    // spring cell beyond it at first touch).
                    a.stick_radius.zip(a.contact_radius).map(|(s, c)| s.min(c))
                ),
                (
                    b.normal_force,
                    b.tangential_force,
                    b.contact_radius,
                    b.stick_radius
                ),
                "step {}",
                a.step
            );
        }
    }

    /// P from δn = (9P²/(16 R* E*²))^(1/3) + Λ P by bisection on P: Hertz in series with a
    /// linear spring, solved for the force, independently of the model's own root finder.
    fn series_hertz_force(s: &Scene, delta_n: f64, lambda: f64) -> f64 {
        let h = s.hertz();
        let (mut lo, mut hi) = (0.0, 2.0 * h.force(delta_n.max(0.0)) + 1.0);
        for _ in 0..200 {
            let p = 0.5 * (lo + hi);
            if h.approach(p) + lambda * p < delta_n {
                lo = p;
            } else {
                hi = p;
            }
        }
        0.5 * (lo + hi)
    }

    #[test]
    fn hertz_in_series_with_a_linear_spring_matches_the_closed_form() {
        // Λ_n = ±2e-10 m/N moves P at 17 µm (803.8 N) by ∓1.4 % of δn, four times the hemisphere's.
        let s = scene(&[(0.0, 0.0), (17.0, 0.0), (20.0, 0.0), (5.0, 0.0)], 10);
        for lambda in [2e-10, -2e-10] {
            let h = SeriesMdr {
                springs: 16_000,
                compliance: SeriesCompliance::constant(lambda, 0.0),
            }
            .history(&s);
            for row in h.steps.iter().skip(1) {
                let exact = series_hertz_force(&s, row.delta_n, lambda);
                let p = row.normal_force.unwrap();
                // Reason: the bed's midpoint rule on 16000 springs, error ≤ 1.5 (Δx/c)² = 1.3e-6
                // at the smallest contact here (δn = 1.7 µm); the root is solved to round-off.
                assert!(
                    (p / exact - 1.0).abs() < 1.5e-6,
                    "Λ {lambda:e}, δn {:e}: {p} vs {exact}",
                    row.delta_n
                );
                let c = row.contact_radius.unwrap();
                assert!((c - s.hertz().contact_radius(s.hertz().approach(exact))).abs() < 1e-6 * c);
            }
        }
    }

    #[test]
    fn cattaneo_in_series_with_a_linear_spring_matches_the_closed_form() {
        // Constant δn = 17 µm, δt from 0 to 6 µm (past gross sliding), Λ_t = 5e-10 m/N (about
        // the hemisphere's shear compliance, twice): δt = x + Λ_t Q with Cattaneo's
        // Q = μP(1 − (1 − x/δs)^(3/2)), δs = 3μP/(16 G* c).
        let s = scene(&[(0.0, 0.0), (17.0, 0.0), (17.0, 6.0)], 60);
        let lambda = 5e-10;
        let h = SeriesMdr {
            springs: 16_000,
            compliance: SeriesCompliance::constant(0.0, lambda),
        }
        .history(&s);
        let pair = &s.pair;
        let p = s.hertz().force(17e-6);
        let c = s.hertz().contact_radius(17e-6);
        let slip = 3.0 * s.friction * p / (16.0 * pair.mindlin_shear_modulus() * c);
        let cattaneo = |x: f64| s.friction * p * (1.0 - (1.0 - (x / slip).min(1.0)).powf(1.5));
        for row in h.steps.iter().filter(|r| r.delta_t > 0.0) {
            let (mut lo, mut hi) = (0.0, row.delta_t);
            for _ in 0..200 {
                let x = 0.5 * (lo + hi);
                if x + lambda * cattaneo(x) < row.delta_t {
                    lo = x;
                } else {
                    hi = x;
                }
            }
            let exact = cattaneo(0.5 * (lo + hi));
            let q = row.tangential_force.unwrap();
            // Reason: the bed on 16000 springs; cells cut by the contact and stick edges bound
            // the error by 2 × 1.5 (Δx/c)² = 2.5e-7 of μP.
            assert!(
                (q - exact).abs() < 1e-6 * s.friction * p,
                "δt {:e}: {q} vs {exact}",
                row.delta_t
            );
        }
    }

    #[test]
    fn the_table_interpolates_in_ln_c_and_is_constant_beyond_its_ends() {
        let t = SeriesCompliance::try_new(vec![1.0, 4.0], vec![1.0, 3.0], vec![-1.0, 1.0]).unwrap();
        assert_eq!(t.at(0.5), (1.0, -1.0));
        assert_eq!(t.at(8.0), (3.0, 1.0));
        let (n, tt) = t.at(2.0); // halfway in ln c
        assert!((n - 2.0).abs() < 1e-15 && tt.abs() < 1e-15);
        assert!(SeriesCompliance::try_new(vec![2.0, 1.0], vec![0.0; 2], vec![0.0; 2]).is_none());
        assert!(SeriesCompliance::try_new(vec![1.0], vec![f64::NAN], vec![0.0]).is_none());
    }

    #[test]
    fn the_root_of_a_kinked_monotone_function_is_found_to_round_off() {
        // x + k(x) with k piecewise linear (a kink at 1): root of x + 3 max(0, x − 1) = 5 is 2.
        let f = |x: f64| {
            let (k, slope) = if x > 1.0 {
                (3.0 * (x - 1.0), 3.0)
            } else {
                (0.0, 0.0)
            };
            (x + k - 5.0, 1.0 + slope)
        };
        assert!((series_root(5.0, f) - 2.0).abs() < 1e-15);
        // A decreasing k (negative compliance) that keeps x + k increasing.
        let g = |x: f64| (x - 0.5 * x.max(0.0) - 1.0, if x > 0.0 { 0.5 } else { 1.0 });
        assert!((series_root(1.0, g) - 2.0).abs() < 1e-15);
    }
}
