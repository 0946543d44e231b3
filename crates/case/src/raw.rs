//! The case file as written: serde structures that reject unknown fields and keep the byte
//! spans of the values that validation judges.

use serde::Deserialize;
use toml::Spanned;

/// A case file as written.
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a case: a table of name, friction, solvers, body1, path …"
)]
pub struct RawCase {
    pub name: Option<Spanned<String>>,
    pub description: Option<String>,
    pub friction: Spanned<f64>,
    pub solvers: Spanned<Vec<Spanned<String>>>,
    pub focus: Option<Spanned<i64>>,
    pub ranks: Option<Spanned<i64>>,
    pub labels: Option<Spanned<Vec<Spanned<String>>>>,
    pub fields: Option<Spanned<toml::Value>>,
    pub body1: RawBody,
    pub body2: Option<RawBody>,
    pub path: RawPath,
    pub domain: Option<RawDomain>,
    pub resolution: Option<std::collections::BTreeMap<Spanned<String>, Spanned<toml::Value>>>,
    pub calculix: Option<RawCalculix>,
    pub kratos: Option<RawKratos>,
    #[serde(rename = "fem-3d")]
    pub fem3d: Option<RawFem3d>,
    #[serde(default)]
    pub checks: Vec<RawCheck>,
    #[serde(default)]
    pub command_solvers: Vec<RawCommandSolver>,
    #[serde(default)]
    pub stored_results: Vec<RawStoredResults>,
}

/// A program named as a solver, as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCommandSolver {
    pub name: Spanned<String>,
    pub command: Spanned<Vec<String>>,
    pub timeout: Option<Spanned<f64>>,
    pub kind: Spanned<String>,
    pub description: Option<String>,
}

/// Results computed elsewhere, named as a solver, as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStoredResults {
    pub name: Spanned<String>,
    pub file: Spanned<String>,
    pub kind: Spanned<String>,
    pub description: Option<String>,
}

/// The `[domain]` table as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDomain {
    pub kind: Option<Spanned<String>>,
    pub height: Option<Spanned<f64>>,
    pub grip: Option<Spanned<String>>,
    pub mesher: Option<Spanned<String>>,
}

/// The `[calculix]` table as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCalculix {
    pub contact: Option<Spanned<String>>,
    pub penalty: Option<Spanned<f64>>,
    pub element: Option<Spanned<String>>,
}

/// The `[kratos]` table as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawKratos {
    pub contact: Option<Spanned<String>>,
    pub element: Option<Spanned<String>>,
    pub alm_factor: Option<Spanned<f64>>,
    pub penalty: Option<Spanned<f64>>,
    pub operator_threshold: Option<Spanned<f64>>,
    pub mixed_ulm_solver: Option<Spanned<bool>>,
}

/// The `[fem-3d]` table as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFem3d {
    pub stick_slope: Option<Spanned<f64>>,
}

/// A body as written.
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a body: a table of radius, young and poisson"
)]
pub struct RawBody {
    pub radius: Spanned<f64>,
    pub young: Spanned<f64>,
    pub poisson: Spanned<f64>,
}

/// The loading path as written.
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a path: a table of unit, delta_n, delta_t and substeps"
)]
pub struct RawPath {
    pub unit: Spanned<String>,
    pub delta_n: Spanned<Vec<Spanned<f64>>>,
    pub delta_t: Spanned<Vec<Spanned<f64>>>,
    pub substeps: Spanned<toml::Value>,
}

/// A check as written.
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a check: a table of solver, quantity, at, reference, tolerance and reason"
)]
pub struct RawCheck {
    pub solver: Spanned<String>,
    pub quantity: Spanned<String>,
    pub at: Spanned<toml::Value>,
    pub reference: Spanned<toml::Value>,
    pub error: Option<Spanned<String>>,
    pub tolerance: Option<Spanned<f64>>,
    pub reason: Option<String>,
    #[serde(default)]
    pub informational: bool,
    pub known_failure: Option<Spanned<String>>,
    pub abs_zero: Option<Spanned<f64>>,
}

/// One stored reference value in a `reference/*.toml` file.
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a reference value: a table of quantity, value, unit and source"
)]
pub struct RawReferenceValue {
    pub quantity: String,
    pub value: f64,
    pub unit: String,
    pub source: String,
}
