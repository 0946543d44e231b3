//! An impact case file as written (serde's view, with spans for the messages): validated by
//! [`super::impact_rules`].

use serde::Deserialize;
use toml::Spanned;

/// An impact case file as written.
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "an impact case: a table of kind, friction, solvers, body1 … (and command_solvers, stored_results)"
)]
pub(super) struct RawImpact {
    pub(super) kind: Spanned<String>,
    pub(super) name: Option<Spanned<String>>,
    pub(super) description: Option<String>,
    pub(super) labels: Option<Spanned<Vec<Spanned<String>>>>,
    pub(super) friction: Spanned<f64>,
    pub(super) restitution: Option<Spanned<f64>>,
    pub(super) solvers: Spanned<Vec<Spanned<String>>>,
    pub(super) steps: Option<Spanned<i64>>,
    pub(super) springs: Option<Spanned<i64>>,
    pub(super) body1: RawImpactBody,
    pub(super) body2: Option<RawImpactBody>,
    pub(super) sweep: Option<RawSweep>,
    #[serde(default)]
    pub(super) checks: Vec<RawImpactCheck>,
    #[serde(default)]
    pub(super) command_solvers: Vec<super::raw::RawCommandSolver>,
    #[serde(default)]
    pub(super) stored_results: Vec<RawImpactStored>,
}

/// An impact's results computed elsewhere, named as a solver, as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawImpactStored {
    pub(super) name: Spanned<String>,
    pub(super) kind: Spanned<String>,
    pub(super) file: Spanned<String>,
    pub(super) elastic_file: Option<Spanned<String>>,
    pub(super) description: Option<String>,
}

/// A body of an impact as written.
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a body: radius, young, poisson, density, velocity, spin"
)]
pub(super) struct RawImpactBody {
    pub(super) rigid_flat: Option<Spanned<bool>>,
    pub(super) radius: Option<Spanned<f64>>,
    pub(super) young: Option<Spanned<f64>>,
    pub(super) poisson: Option<Spanned<f64>>,
    pub(super) density: Option<Spanned<f64>>,
    pub(super) velocity: Option<Spanned<Vec<f64>>>,
    pub(super) spin: Option<Spanned<f64>>,
}

/// A sweep as written.
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a sweep: variable, unit, values, body2_spin"
)]
pub(super) struct RawSweep {
    pub(super) variable: Spanned<String>,
    pub(super) unit: Option<Spanned<String>>,
    pub(super) values: Spanned<Vec<Spanned<f64>>>,
    pub(super) body2_spin: Option<Spanned<String>>,
}

/// A check as written.
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a check: solver, quantity, variant, reference, tolerance, reason"
)]
pub(super) struct RawImpactCheck {
    pub(super) solver: Spanned<String>,
    pub(super) quantity: Spanned<String>,
    pub(super) variant: Option<Spanned<String>>,
    pub(super) reference: Spanned<toml::Value>,
    pub(super) error: Option<Spanned<String>>,
    pub(super) tolerance: Option<Spanned<f64>>,
    pub(super) reason: Spanned<String>,
    #[serde(default)]
    pub(super) informational: bool,
}
