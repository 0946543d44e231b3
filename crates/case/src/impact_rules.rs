//! Impact case files (`kind = "impact"`, `cases/impact/`): read and validated into an
//! [`ImpactCase`] with the rules and errors of every case field (file, field, line and column,
//! the allowed range).
//!
//! ```toml
//! kind = "impact"
//! name = "chung-ooi-4"                  # optional, defaults to the file stem
//! description = "…"
//! labels = ["impact", "dem", "fast"]    # optional, as a path case's (`verify --label`); default
//!                                       # these three
//! friction = 0.092                      # Coulomb 0 ≤ μ ≤ 10
//! restitution = 0.98                    # optional, 0.01 ≤ e ≤ 1 (default 1: elastic); e < 1
//!                                       # also runs the elastic variant
//! solvers = ["mdr", "thornton"]         # mdr and the DEM laws (`spherecontact list`)
//! steps = 2000                          # optional: time steps per Hertz contact duration,
//!                                       # 100 ≤ steps ≤ 100 000 (default 2000)
//! springs = 4000                        # optional: MDR springs, 100 ≤ n ≤ 1 000 000 (default 4000)
//!
//! [body1]                               # the impacting sphere; SI
//! radius = 0.0025                       # 1e-9 ≤ R ≤ 1e3 m (finite)
//! young = 3.8e11                        # 1e3 ≤ E ≤ 1e13 Pa
//! poisson = 0.23                        # −1 < ν < 0.5
//! density = 4000                        # 1 ≤ ρ ≤ 1e5 kg/m³
//! velocity = [0, -3.9]                  # [tangential x, normal z] m/s, each |v| ≤ 1e3
//! spin = 0                              # rad/s, |ω| ≤ 1e6; ω > 0 moves the contact point to +x
//!
//! [body2]                               # a sphere as body1 (velocity and spin default 0),
//! rigid_flat = true                     # or a rigid flat (infinite mass and modulus), at rest
//!
//! [sweep]                               # optional: one impact per value
//! variable = "incident_angle"           # incident_angle (unit "deg" or "rad", 0 ≤ θ < 90°,
//!                                       # body 1's speed kept), tangential_velocity (m/s),
//!                                       # spin (rad/s), restitution (0.01 ≤ e ≤ 1)
//! unit = "deg"
//! values = [5, 10, 15]                  # 1 to 200 values
//! body2_spin = "opposite"               # spin sweeps of two spheres: body 2's contact point
//!                                       # moves opposite to body 1's (default "kept")
//!
//! [[checks]]
//! solver = "mdr"
//! quantity = "contact_duration"         # a column of the output (docs/impact.md)
//! variant = "elastic"                   # "prescribed" (default) or "elastic" (cases with e < 1)
//! reference = "hertz"                   # Hertz's closed forms (normal quantities, elastic runs
//!                                       # only), or { solver = "mdr" }
//! error = "relative"                    # or "absolute"
//! tolerance = 1e-4
//! reason = "why this tolerance"         # always required; informational = true to score only
//! ```
//!
//! **Physical ranges.** At every sweep point the bodies approach along the normal, and Hertz's
//! largest overlap of the elastic impact is positive, finite and below the smaller radius.

use toml::Spanned;

use super::impact_solvers::solver_names;
use super::raw::RawBody;
use crate::{input, CaseError, Validator};
use spherecontact_model::hertz::Hertz;
use spherecontact_model::limits;
use spherecontact_reference::impact::closed_form::HertzImpact;
use spherecontact_reference::impact::problem::{
    Body2Spin, ImpactBody, ImpactCase, ImpactCheck, ImpactReference, Quantity, Sweep, SweepVariable, Variant,
};

use super::impact_raw::{RawImpact, RawImpactBody, RawImpactCheck, RawSweep};

/// Default time steps per Hertz contact duration (converged: docs/impact.md).
const DEFAULT_STEPS: i64 = 2000;
/// Default MDR springs.
const DEFAULT_SPRINGS: i64 = 4000;
/// Most sweep values.
const MAX_SWEEP_VALUES: usize = 200;
/// Largest velocity component [m/s] and spin [rad/s].
const MAX_SPEED: f64 = 1e3;
const MAX_SPIN: f64 = 1e6;

/// True when `text` is an impact case: a TOML table whose `kind` is "impact".
pub fn is_impact(text: &str) -> bool {
    toml::from_str::<toml::Table>(text)
        .ok()
        .and_then(|t| t.get("kind").and_then(|k| k.as_str().map(|k| k == "impact")))
        .unwrap_or(false)
}

/// True when `file` holds an impact case (`kind = "impact"`); false when it cannot be read (the
/// path-case loader then reports why).
pub fn is_impact_file(file: &std::path::Path) -> bool {
    input::read_text(file).is_ok_and(|text| is_impact(&text))
}

/// Reads and validates the impact case at `file`.
pub fn load_impact(file: &std::path::Path) -> Result<ImpactCase, CaseError> {
    parse_impact(file, &super::read_case_file(file)?)
}

/// Validates the text of an impact case file.
pub fn parse_impact(file: &std::path::Path, text: &str) -> Result<ImpactCase, CaseError> {
    let raw: RawImpact = toml::from_str(text).map_err(|e| {
        let field = e.span().and_then(|s| super::error::field_at(text, s.start));
        CaseError::new(
            file,
            e.span().map(|s| (text, s)),
            field.unwrap_or_default(),
            super::error::parser_message(&e),
        )
    })?;
    let own = raw
        .command_solvers
        .iter()
        .map(|s| &s.name)
        .chain(raw.stored_results.iter().map(|s| &s.name))
        .map(|name| name.get_ref().clone())
        .collect();
    let validator = Validator {
        file,
        text,
        // The files an impact case names (its stored results) lie in the case file's own tree.
        tree: super::ReadRoots::default().tree(file),
        own,
    };
    validator.impact(raw)
}

impl Validator<'_> {
    fn impact(&self, raw: RawImpact) -> Result<ImpactCase, CaseError> {
        if raw.kind.get_ref() != "impact" {
            return Err(self.error(&raw.kind, "kind", "allowed: \"impact\" (absent for a path case)"));
        }
        let name = self.name(raw.name.as_ref())?;
        let labels = match &raw.labels {
            Some(labels) => self.labels(Some(labels))?,
            None => spherecontact_reference::impact::problem::DEFAULT_LABELS
                .map(String::from)
                .to_vec(),
        };
        let friction = self.friction(&raw.friction)?;
        let restitution = match &raw.restitution {
            Some(e) => self.number(e, "restitution", |e| (0.01..=1.0).contains(&e), "0.01 ≤ e ≤ 1")?,
            None => 1.0,
        };
        let body1 = self.impact_body(&raw.body1, "body1")?;
        if body1.is_rigid() {
            let at = raw
                .body1
                .rigid_flat
                .as_ref()
                .expect("a rigid body was declared so");
            return Err(self.error(
                at,
                "body1.rigid_flat",
                "body 1 is the impacting sphere (allowed: body2 only)",
            ));
        }
        let body2 = match &raw.body2 {
            Some(b) => self.impact_body(b, "body2")?,
            None => ImpactBody {
                velocity: [0.0, 0.0],
                spin: 0.0,
                ..body1
            },
        };
        let sweep = match &raw.sweep {
            Some(s) => Some(self.sweep(s, &body2)?),
            None => None,
        };
        let steps = self.count(raw.steps.as_ref(), "steps", DEFAULT_STEPS, 100, 100_000)?;
        let max_springs = limits::MAX_MDR_SPRINGS as i64;
        let springs = self.count(raw.springs.as_ref(), "springs", DEFAULT_SPRINGS, 100, max_springs)?;
        let solvers = self.impact_solvers(&raw.solvers)?;
        let mut case = ImpactCase {
            file: self.file.to_path_buf(),
            name,
            description: raw.description.clone().unwrap_or_default(),
            labels,
            friction,
            restitution,
            body1,
            body2,
            sweep,
            solvers,
            steps,
            springs,
            checks: Vec::new(),
            own_solvers: Vec::new(),
        };
        self.impact_physics(&case, &raw)?;
        case.own_solvers = self.impact_own_solvers(&raw, &case)?;
        case.checks = raw
            .checks
            .iter()
            .enumerate()
            .map(|(i, c)| self.impact_check(c, &format!("checks[{i}]"), &case))
            .collect::<Result<_, _>>()?;
        Ok(case)
    }

    /// An optional count in `min..=max`.
    fn count(
        &self,
        raw: Option<&Spanned<i64>>,
        field: &str,
        default: i64,
        min: i64,
        max: i64,
    ) -> Result<usize, CaseError> {
        let Some(value) = raw else {
            return Ok(default as usize);
        };
        let n = *value.get_ref();
        if (min..=max).contains(&n) {
            Ok(n as usize)
        } else {
            Err(self.error(
                value,
                field,
                format!("{n} is out of range (allowed: {min} ≤ {field} ≤ {max})"),
            ))
        }
    }

    fn impact_body(&self, raw: &RawImpactBody, field: &str) -> Result<ImpactBody, CaseError> {
        if let Some(flag) = raw.rigid_flat.as_ref().filter(|f| *f.get_ref()) {
            let extra = [&raw.radius, &raw.young, &raw.poisson, &raw.density, &raw.spin]
                .iter()
                .any(|v| v.is_some())
                || raw.velocity.is_some();
            if extra {
                return Err(self.error(
                    flag,
                    format!("{field}.rigid_flat"),
                    "a rigid flat is at rest with infinite radius, modulus and mass (allowed: no other field)",
                ));
            }
            return Ok(ImpactBody::rigid_flat());
        }
        let missing = |name: &str| {
            CaseError::new(
                self.file,
                None,
                format!("{field}.{name}"),
                "missing (required for a sphere)",
            )
        };
        let required = |v: &Option<Spanned<f64>>, name: &str| v.clone().ok_or_else(|| missing(name));
        let shape = RawBody {
            radius: required(&raw.radius, "radius")?,
            young: required(&raw.young, "young")?,
            poisson: required(&raw.poisson, "poisson")?,
        };
        let body = self.body(&shape, field)?;
        if body.radius.is_infinite() {
            return Err(self.error(
                &shape.radius,
                format!("{field}.radius"),
                "a sphere needs a finite radius (allowed: 1e-9 ≤ R ≤ 1e3 m; `rigid_flat = true` for a flat)",
            ));
        }
        let density = self.number(
            &required(&raw.density, "density")?,
            &format!("{field}.density"),
            |r| (1.0..=1e5).contains(&r),
            "1 ≤ ρ ≤ 1e5 kg/m³",
        )?;
        let velocity = match &raw.velocity {
            None => [0.0, 0.0],
            Some(v) => match v.get_ref()[..] {
                [x, z] if x.abs() <= MAX_SPEED && z.abs() <= MAX_SPEED => [x, z],
                _ => {
                    return Err(self.error(
                        v,
                        format!("{field}.velocity"),
                        "allowed: [tangential, normal] in m/s, each |v| ≤ 1e3",
                    ))
                }
            },
        };
        let spin = match &raw.spin {
            None => 0.0,
            Some(s) => self.number(
                s,
                &format!("{field}.spin"),
                |w| w.abs() <= MAX_SPIN,
                "|ω| ≤ 1e6 rad/s",
            )?,
        };
        Ok(ImpactBody {
            body,
            density: Some(density),
            velocity,
            spin,
        })
    }

    fn sweep(&self, raw: &RawSweep, body2: &ImpactBody) -> Result<Sweep, CaseError> {
        let name = raw.variable.get_ref();
        let variable = SweepVariable::ALL
            .into_iter()
            .find(|v| v.name() == name)
            .ok_or_else(|| {
                let allowed: Vec<&str> = SweepVariable::ALL.iter().map(|v| v.name()).collect();
                self.error(
                    &raw.variable,
                    "sweep.variable",
                    format!("unknown variable `{name}` (allowed: {})", allowed.join(", ")),
                )
            })?;
        let (scale, unit_allowed): (f64, &str) =
            match (variable, raw.unit.as_ref().map(|u| u.get_ref().as_str())) {
                (SweepVariable::IncidentAngle, Some("deg")) => (std::f64::consts::PI / 180.0, ""),
                (SweepVariable::IncidentAngle, Some("rad")) => (1.0, ""),
                (SweepVariable::IncidentAngle, _) => (f64::NAN, "\"deg\" or \"rad\""),
                (SweepVariable::TangentialVelocity, None | Some("m/s")) => (1.0, ""),
                (SweepVariable::Spin, None | Some("rad/s")) => (1.0, ""),
                (SweepVariable::Restitution, None) => (1.0, ""),
                (SweepVariable::TangentialVelocity, _) => (f64::NAN, "\"m/s\""),
                (SweepVariable::Spin, _) => (f64::NAN, "\"rad/s\""),
                (SweepVariable::Restitution, _) => (f64::NAN, "none (a restitution has no unit)"),
            };
        if scale.is_nan() {
            let message = format!("{name} needs unit {unit_allowed}");
            return Err(match &raw.unit {
                Some(u) => self.error(u, "sweep.unit", format!("allowed: {unit_allowed}")),
                None => self.error(&raw.variable, "sweep.unit", message),
            });
        }
        let count = raw.values.get_ref().len();
        if !(1..=MAX_SWEEP_VALUES).contains(&count) {
            return Err(self.error(
                &raw.values,
                "sweep.values",
                format!("{count} values (allowed: 1 to {MAX_SWEEP_VALUES})"),
            ));
        }
        let (ok, allowed): (fn(f64) -> bool, &str) = match variable {
            SweepVariable::IncidentAngle => {
                (|t| (0.0..std::f64::consts::FRAC_PI_2).contains(&t), "0 ≤ θ < 90°")
            }
            SweepVariable::TangentialVelocity => (|v| v.abs() <= MAX_SPEED, "|v| ≤ 1e3 m/s"),
            SweepVariable::Spin => (|w| w.abs() <= MAX_SPIN, "|ω| ≤ 1e6 rad/s"),
            SweepVariable::Restitution => (|e| (0.01..=1.0).contains(&e), "0.01 ≤ e ≤ 1"),
        };
        let values = raw
            .values
            .get_ref()
            .iter()
            .enumerate()
            .map(|(i, v)| {
                let value = *v.get_ref() * scale;
                if ok(value) {
                    Ok(value)
                } else {
                    Err(self.error(
                        v,
                        format!("sweep.values[{i}]"),
                        format!(
                            "{} is out of range (allowed: {allowed})",
                            spherecontact_model::number::Short(*v.get_ref())
                        ),
                    ))
                }
            })
            .collect::<Result<Vec<_>, _>>()?;
        let body2_spin = match raw.body2_spin.as_ref() {
            None => Body2Spin::Kept,
            Some(s) if s.get_ref() == "kept" => Body2Spin::Kept,
            Some(s) if s.get_ref() == "opposite" && variable == SweepVariable::Spin && !body2.is_rigid() => {
                Body2Spin::Opposite
            }
            Some(s) => {
                return Err(self.error(
                    s,
                    "sweep.body2_spin",
                    "allowed: \"kept\", or \"opposite\" in a spin sweep of two spheres",
                ))
            }
        };
        Ok(Sweep {
            variable,
            values,
            body2_spin,
        })
    }

    fn impact_solvers(&self, raw: &Spanned<Vec<Spanned<String>>>) -> Result<Vec<String>, CaseError> {
        if raw.get_ref().is_empty() {
            return Err(self.error(raw, "solvers", "no solvers (allowed: at least one)"));
        }
        let mut names: Vec<String> = Vec::new();
        for name in raw.get_ref() {
            let name = self.impact_solver_name(name, "solvers")?;
            if names.contains(&name) {
                return Err(self.error(raw, "solvers", format!("`{name}` is listed twice")));
            }
            names.push(name);
        }
        Ok(names)
    }

    fn impact_solver_name(&self, name: &Spanned<String>, field: &str) -> Result<String, CaseError> {
        let known = solver_names();
        if known.contains(&name.get_ref().as_str()) || self.own.contains(name.get_ref()) {
            Ok(name.get_ref().clone())
        } else {
            Err(self.error(
                name,
                field,
                format!(
                    "unknown impact solver `{}` (allowed: {})",
                    name.get_ref(),
                    known.join(", ")
                ),
            ))
        }
    }

    /// Every sweep point approaches, with a positive, finite Hertz overlap below the smaller radius.
    fn impact_physics(&self, case: &ImpactCase, raw: &RawImpact) -> Result<(), CaseError> {
        let hertz = Hertz::of(&case.pair());
        let r_min = case.body1.body.radius.min(case.body2.body.radius);
        for (i, point) in case.points().iter().enumerate() {
            let at = if case.sweep.is_some() {
                format!(" (sweep value {i})")
            } else {
                String::new()
            };
            let v = point.approach_speed();
            let closed = HertzImpact::of(&point.elastic(), &hertz);
            // Velocities are validated finite: v is a number.
            let message = if v <= 0.0 {
                format!(
                    "the bodies do not approach{at}: normal approach speed v2z − v1z = {} m/s (allowed: > 0)",
                    spherecontact_model::number::Short(v)
                )
            } else if !(closed.max_overlap.is_normal()
                && closed.duration.is_normal()
                && closed.max_force.is_normal())
            {
                format!("Hertz's overlap, force or duration is not a normal positive number{at}")
            } else if closed.max_overlap >= r_min {
                format!(
                    "Hertz's largest overlap {} m reaches the smaller radius{at} (allowed: below it)",
                    spherecontact_model::number::Short(closed.max_overlap)
                )
            } else {
                continue;
            };
            let span = raw
                .body1
                .velocity
                .as_ref()
                .map(|v| v.span())
                .unwrap_or(raw.friction.span());
            return Err(CaseError::new(
                self.file,
                Some((self.text, span)),
                "body1.velocity",
                message,
            ));
        }
        Ok(())
    }

    fn impact_check(
        &self,
        raw: &RawImpactCheck,
        field: &str,
        case: &ImpactCase,
    ) -> Result<ImpactCheck, CaseError> {
        let solver = self.impact_solver_name(&raw.solver, &format!("{field}.solver"))?;
        let quantity = Quantity::from_name(raw.quantity.get_ref()).ok_or_else(|| {
            let allowed: Vec<&str> = Quantity::ALL.iter().map(|q| q.name()).collect();
            self.unknown_quantity(&raw.quantity, field, &allowed)
        })?;
        let variant = match raw.variant.as_ref().map(|v| (v, v.get_ref().as_str())) {
            None | Some((_, "prescribed")) => Variant::Prescribed,
            Some((_, "elastic")) if case.restitution < 1.0 => Variant::Elastic,
            Some((v, _)) => {
                return Err(self.error(
                    v,
                    format!("{field}.variant"),
                    "allowed: \"prescribed\", or \"elastic\" when the case prescribes restitution < 1",
                ))
            }
        };
        let reference = match raw.reference.get_ref() {
            toml::Value::String(s) if s == "hertz" => ImpactReference::Hertz,
            toml::Value::Table(t) if t.len() == 1 && t.get("solver").is_some_and(|s| s.is_str()) => {
                let name = t["solver"].as_str().unwrap_or_default();
                if !solver_names().contains(&name) && !self.own.iter().any(|o| o == name) {
                    return Err(self.error(
                        &raw.reference,
                        format!("{field}.reference"),
                        format!(
                            "unknown impact solver `{name}` (allowed: {})",
                            solver_names().join(", ")
                        ),
                    ));
                }
                ImpactReference::Solver(name.to_owned())
            }
            _ => {
                return Err(self.error(
                    &raw.reference,
                    format!("{field}.reference"),
                    "allowed: \"hertz\" or { solver = \"NAME\" }",
                ))
            }
        };
        let elastic_run = variant == Variant::Elastic
            || (case.restitution == 1.0
                && case
                    .sweep
                    .as_ref()
                    .is_none_or(|s| s.variable != SweepVariable::Restitution));
        if reference == ImpactReference::Hertz && !(quantity.is_normal() && elastic_run) {
            return Err(self.error(
                &raw.reference,
                format!("{field}.reference"),
                "Hertz's closed forms give the normal quantities (contact_duration, max_normal_force, \
                 max_overlap, normal_restitution) of an elastic run only",
            ));
        }
        let relative = match raw.error.as_ref().map(|e| (e, e.get_ref().as_str())) {
            None | Some((_, "relative")) => true,
            Some((_, "absolute")) => false,
            Some((e, _)) => {
                return Err(self.error(e, format!("{field}.error"), "allowed: \"relative\", \"absolute\""))
            }
        };
        let tolerance = match (&raw.tolerance, raw.informational) {
            (Some(t), false) => Some(self.number(
                t,
                &format!("{field}.tolerance"),
                |t| t > 0.0 && t.is_finite(),
                "a positive number",
            )?),
            (None, true) => None,
            (Some(t), true) => {
                return Err(self.error(
                    t,
                    format!("{field}.tolerance"),
                    "an informational check has no tolerance",
                ))
            }
            (None, false) => {
                return Err(self.error(
                    &raw.solver,
                    format!("{field}.tolerance"),
                    "missing (required unless informational = true)",
                ))
            }
        };
        if raw.reason.get_ref().trim().is_empty() {
            return Err(self.error(
                &raw.reason,
                format!("{field}.reason"),
                "empty (allowed: why this tolerance)",
            ));
        }
        Ok(ImpactCheck {
            solver,
            quantity,
            variant,
            reference,
            relative,
            tolerance,
            reason: raw.reason.get_ref().clone(),
        })
    }
}
