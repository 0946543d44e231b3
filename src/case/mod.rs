//! Case files (`cases/*.toml`): the bodies, friction, loading path, solvers and checks of one
//! verification case, read and validated into a [`Case`].
//!
//! ```toml
//! name = "hertz-normal"                 # optional, defaults to the file stem
//! description = "…"
//! friction = 0.2                        # Coulomb μ ≥ 0
//! solvers = ["hertz", "mdr"]
//! focus = 2                             # optional: the position whose surface fields reports
//!                                       # show (default: the first of largest δn)
//!
//! [body1]                               # SI: m, Pa
//! radius = 0.1                          # > 0; `inf` for a flat
//! young = 70e9                          # > 0
//! poisson = 0.3                         # −1 < ν < 0.5
//! # [body2] is optional: absent means two identical spheres
//!
//! [path]
//! unit = "um"                           # "m", "mm", "um" or "µm"
//! delta_n = [0, 10, 17]                 # total approach of the far points
//! delta_t = [0, 0, 2]                   # relative tangential displacement
//! substeps = 20                         # per segment: one count, or one per segment
//!
//! [domain]                              # optional: the finite body FEM solvers and decks mesh
//! kind = "hemisphere"                   # "hemisphere" (default) or "cap"
//! height = 0.02                         # cap only: cut this far from the pole [m],
//!                                       # 10 c_max ≤ height ≤ the smallest finite radius
//! grip = "rigid"                        # "rigid" (default) or "axial" (frictionless scenes only)
//!
//! [[checks]]
//! solver = "mdr"
//! quantity = "normal_force"             # normal_force, tangential_force, contact_radius,
//!                                       # peak_pressure, stick_radius
//! at = "every-step"                     # "every-position", { position = 2 }, { positions = [1, 2] }
//! reference = { solver = "hertz" }      # or { file = "../reference/x.toml", key = "…" }
//! error = "relative"                    # "relative-to-peak", "absolute"
//! tolerance = 1e-6
//! reason = "why this tolerance"         # required unless informational = true
//! ```
//!
//! Every rule broken gives a [`CaseError`] naming the file, the field, its line and column where
//! known, and the allowed range.

mod domain;
mod error;
mod raw;
pub mod reference;

pub use error::CaseError;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use toml::Spanned;

use crate::check::{CheckSpec, ErrorMeasure, Reference, Where};
use crate::domain::Domain;
use crate::history::Quantity;
use crate::pair::{Body, ContactPair, Material};
use crate::path::{LoadingPath, Position};
use crate::registry;
use crate::scene::Scene;
use raw::{RawBody, RawCase, RawCheck, RawPath};
use reference::LoadError;

/// The most increments a path may have in all: each step keeps a row of every solver's history,
/// so this bounds the memory a case can ask for (about 100 bytes a row and solver).
pub const MAX_INCREMENTS: usize = 1_000_000;

/// A validated case.
#[derive(Clone, Debug)]
pub struct Case {
    /// The file it was read from.
    pub file: PathBuf,
    /// A one-paragraph description.
    pub description: String,
    /// The problem.
    pub scene: Scene,
    /// The solvers the case runs, in its order.
    pub solvers: Vec<String>,
    /// The path position whose surface fields reports show.
    pub focus: usize,
    /// Its checks.
    pub checks: Vec<CheckSpec>,
}

impl Case {
    /// Reads and validates the case file at `file`.
    pub fn load(file: &Path) -> Result<Self, CaseError> {
        let text = std::fs::read_to_string(file)
            .map_err(|e| CaseError::new(file, None, "", format!("cannot read the case file: {e}")))?;
        Self::parse(file, &text)
    }

    /// Validates the text of a case file; `file` names it in errors and anchors reference paths.
    pub fn parse(file: &Path, text: &str) -> Result<Self, CaseError> {
        let raw: RawCase = toml::from_str(text).map_err(|e| {
            let span = e.span().map(|s| (text, s));
            CaseError::new(file, span, "", e.message().to_owned())
        })?;
        Validator { file, text }.case(raw)
    }

    /// The case's name (its scene's).
    pub fn name(&self) -> &str {
        &self.scene.name
    }

    /// Every solver the case needs: its own list, then those its checks refer to.
    pub fn required_solvers(&self) -> Vec<String> {
        let mut names = self.solvers.clone();
        for check in &self.checks {
            for name in std::iter::once(&check.solver).chain(match &check.reference {
                Reference::Solver(name) => Some(name),
                Reference::Value { .. } => None,
            }) {
                if !names.contains(name) {
                    names.push(name.clone());
                }
            }
        }
        names
    }
}

/// Validation of one file's raw case, turning each broken rule into a located [`CaseError`].
struct Validator<'a> {
    file: &'a Path,
    text: &'a str,
}

impl Validator<'_> {
    fn error<T>(
        &self,
        spanned: &Spanned<T>,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> CaseError {
        CaseError::new(self.file, Some((self.text, spanned.span())), field, message)
    }

    /// A finite number in the open or closed range the predicate describes.
    fn number(
        &self,
        value: &Spanned<f64>,
        field: &str,
        ok: impl Fn(f64) -> bool,
        allowed: &str,
    ) -> Result<f64, CaseError> {
        let v = *value.get_ref();
        if ok(v) {
            Ok(v)
        } else {
            Err(self.error(value, field, format!("{v} is out of range (allowed: {allowed})")))
        }
    }

    fn case(&self, raw: RawCase) -> Result<Case, CaseError> {
        let friction = self.number(
            &raw.friction,
            "friction",
            |m| m.is_finite() && m >= 0.0,
            "finite μ ≥ 0",
        )?;
        let body1 = self.body(&raw.body1, "body1")?;
        let body2 = match &raw.body2 {
            Some(b) => self.body(b, "body2")?,
            None => body1,
        };
        if body1.radius.is_infinite() && body2.radius.is_infinite() {
            let at = raw.body2.as_ref().map_or(&raw.body1.radius, |b| &b.radius);
            return Err(self.error(
                at,
                "body2.radius",
                "two flats make no Hertz contact (allowed: at least one finite radius)",
            ));
        }
        let path = self.path(&raw.path)?;
        let solvers = self.solvers(&raw.solvers)?;
        let name = raw.name.unwrap_or_else(|| {
            self.file
                .file_stem()
                .map_or_else(String::new, |s| s.to_string_lossy().into_owned())
        });
        let checks = raw
            .checks
            .iter()
            .enumerate()
            .map(|(i, c)| self.check(c, &format!("checks[{i}]"), path.positions().len()))
            .collect::<Result<_, _>>()?;
        let focus = self.focus(raw.focus.as_ref(), &path)?;
        let mut scene = Scene {
            name,
            pair: ContactPair { body1, body2 },
            friction,
            path,
            domain: Domain::default(),
        };
        if let Some(domain) = &raw.domain {
            scene.domain = self.domain(domain, &scene)?;
        }
        Ok(Case {
            file: self.file.to_path_buf(),
            focus,
            description: raw.description.unwrap_or_default(),
            scene,
            solvers,
            checks,
        })
    }

    fn focus(&self, raw: Option<&Spanned<i64>>, path: &LoadingPath) -> Result<usize, CaseError> {
        let positions = path.positions();
        let Some(raw) = raw else {
            // The first position of largest δn.
            let largest = path.max_approach();
            return Ok(positions.iter().position(|p| p.delta_n == largest).unwrap_or(0));
        };
        match usize::try_from(*raw.get_ref()) {
            Ok(k) if k < positions.len() => Ok(k),
            _ => Err(self.error(
                raw,
                "focus",
                format!(
                    "{} is not a path position (allowed: 0 to {})",
                    raw.get_ref(),
                    positions.len() - 1
                ),
            )),
        }
    }

    fn body(&self, raw: &RawBody, field: &str) -> Result<Body, CaseError> {
        let radius = self.number(
            &raw.radius,
            &format!("{field}.radius"),
            |r| r > 0.0,
            "R > 0 in m, or inf for a flat",
        )?;
        let young = self.number(
            &raw.young,
            &format!("{field}.young"),
            |e| e.is_finite() && e > 0.0,
            "finite E > 0 in Pa",
        )?;
        let poisson = self.number(
            &raw.poisson,
            &format!("{field}.poisson"),
            |v| v > -1.0 && v < 0.5,
            "−1 < ν < 0.5",
        )?;
        Ok(Body {
            radius,
            material: Material { young, poisson },
        })
    }

    fn path(&self, raw: &RawPath) -> Result<LoadingPath, CaseError> {
        let scale = match raw.unit.get_ref().as_str() {
            "m" => 1.0,
            "mm" => 1e-3,
            "um" | "µm" => 1e-6,
            other => {
                return Err(self.error(
                    &raw.unit,
                    "path.unit",
                    format!("unknown unit `{other}` (allowed: m, mm, um, µm)"),
                ))
            }
        };
        let values = |list: &Spanned<Vec<Spanned<f64>>>, field: &str| -> Result<Vec<f64>, CaseError> {
            list.get_ref()
                .iter()
                .enumerate()
                .map(|(i, v)| {
                    self.number(
                        v,
                        &format!("path.{field}[{i}]"),
                        f64::is_finite,
                        "a finite number",
                    )
                    .map(|v| v * scale)
                })
                .collect()
        };
        let (delta_n, delta_t) = (values(&raw.delta_n, "delta_n")?, values(&raw.delta_t, "delta_t")?);
        if delta_n.is_empty() {
            return Err(self.error(
                &raw.delta_n,
                "path.delta_n",
                "no positions (allowed: at least one)",
            ));
        }
        if delta_t.len() != delta_n.len() {
            return Err(self.error(
                &raw.delta_t,
                "path.delta_t",
                format!(
                    "{} values for {} positions of delta_n (allowed: one per position)",
                    delta_t.len(),
                    delta_n.len()
                ),
            ));
        }
        let segments = delta_n.len() - 1;
        let substeps = self.substeps(&raw.substeps, segments)?;
        let positions = delta_n
            .into_iter()
            .zip(delta_t)
            .map(|(delta_n, delta_t)| Position { delta_n, delta_t })
            .collect();
        Ok(LoadingPath::try_new(positions, substeps).expect("positions and substeps validated above"))
    }

    fn substeps(&self, raw: &Spanned<toml::Value>, segments: usize) -> Result<Vec<usize>, CaseError> {
        let count = |v: &toml::Value| match v {
            toml::Value::Integer(n) if *n >= 1 && *n <= MAX_INCREMENTS as i64 => Ok(*n as usize),
            other => Err(self.error(
                raw,
                "path.substeps",
                format!("{other} is not a whole number from 1 to {MAX_INCREMENTS}"),
            )),
        };
        let counts: Vec<usize> = match raw.get_ref() {
            toml::Value::Array(list) if list.len() == segments => {
                list.iter().map(count).collect::<Result<_, _>>()?
            }
            toml::Value::Array(list) => {
                return Err(self.error(
                    raw,
                    "path.substeps",
                    format!(
                        "{} counts for {segments} segments (allowed: one count, or one per segment)",
                        list.len()
                    ),
                ))
            }
            single => vec![count(single)?; segments],
        };
        let total: usize = counts.iter().sum();
        if total > MAX_INCREMENTS {
            return Err(self.error(
                raw,
                "path.substeps",
                format!("{total} increments in all (allowed: at most {MAX_INCREMENTS})"),
            ));
        }
        Ok(counts)
    }

    fn solvers(&self, raw: &Spanned<Vec<Spanned<String>>>) -> Result<Vec<String>, CaseError> {
        if raw.get_ref().is_empty() {
            return Err(self.error(raw, "solvers", "no solvers (allowed: at least one)"));
        }
        let mut seen = BTreeSet::new();
        raw.get_ref()
            .iter()
            .map(|name| {
                let name_str = self.solver_name(name, "solvers")?;
                if !seen.insert(name_str.clone()) {
                    return Err(self.error(name, "solvers", format!("`{name_str}` is listed twice")));
                }
                Ok(name_str)
            })
            .collect()
    }

    fn solver_name(&self, name: &Spanned<String>, field: &str) -> Result<String, CaseError> {
        if registry::by_name(name.get_ref()).is_some() {
            return Ok(name.get_ref().clone());
        }
        let known = registry::names();
        Err(self.error(
            name,
            field,
            format!(
                "unknown solver `{}` (allowed: {})",
                name.get_ref(),
                known.join(", ")
            ),
        ))
    }

    fn check(&self, raw: &RawCheck, field: &str, positions: usize) -> Result<CheckSpec, CaseError> {
        let solver = self.solver_name(&raw.solver, &format!("{field}.solver"))?;
        let quantity = Quantity::from_name(raw.quantity.get_ref()).ok_or_else(|| {
            let names: Vec<_> = Quantity::ALL.iter().map(|q| q.name()).collect();
            self.error(
                &raw.quantity,
                format!("{field}.quantity"),
                format!(
                    "unknown quantity `{}` (allowed: {})",
                    raw.quantity.get_ref(),
                    names.join(", ")
                ),
            )
        })?;
        let at = self.at(&raw.at, &format!("{field}.at"), positions)?;
        let reference = self.reference(&raw.reference, &format!("{field}.reference"), quantity)?;
        let measure = match &raw.error {
            None => ErrorMeasure::Relative,
            Some(name) => ErrorMeasure::from_name(name.get_ref()).ok_or_else(|| {
                self.error(
                    name,
                    format!("{field}.error"),
                    format!(
                        "unknown error measure `{}` (allowed: relative, relative-to-peak, absolute)",
                        name.get_ref()
                    ),
                )
            })?,
        };
        let tolerance = match (&raw.tolerance, raw.informational) {
            (Some(t), _) => Some(self.number(
                t,
                &format!("{field}.tolerance"),
                |t| t.is_finite() && t > 0.0,
                "finite tolerance > 0",
            )?),
            (None, true) => None,
            (None, false) => {
                return Err(self.error(
                    &raw.solver,
                    format!("{field}.tolerance"),
                    "missing (required unless informational = true)",
                ))
            }
        };
        let tolerance = if raw.informational { None } else { tolerance };
        let reason = raw.reason.clone().unwrap_or_default();
        if tolerance.is_some() && reason.trim().is_empty() {
            return Err(self.error(
                &raw.solver,
                format!("{field}.reason"),
                "missing: every tolerance needs its reason (discretisation, domain, model …)",
            ));
        }
        Ok(CheckSpec {
            solver,
            quantity,
            at,
            reference,
            measure,
            tolerance,
            reason,
        })
    }

    fn at(&self, raw: &Spanned<toml::Value>, field: &str, positions: usize) -> Result<Where, CaseError> {
        let allowed = "\"every-step\", \"every-position\", { position = K } or { positions = [FIRST, LAST] }";
        let bad = |what: String| {
            self.error(
                raw,
                field,
                format!(
                    "{what} (allowed: {allowed}, with positions 0 to {})",
                    positions - 1
                ),
            )
        };
        let index = |v: &toml::Value| match v {
            toml::Value::Integer(k) if *k >= 0 && (*k as usize) < positions => Ok(*k as usize),
            other => Err(bad(format!("position {other} is not on the path"))),
        };
        match raw.get_ref() {
            toml::Value::String(s) if s == "every-step" => Ok(Where::EveryStep),
            toml::Value::String(s) if s == "every-position" => Ok(Where::EveryPosition),
            toml::Value::Table(t) if t.len() == 1 => match (t.get("position"), t.get("positions")) {
                (Some(k), None) => Ok(Where::Position(index(k)?)),
                (None, Some(toml::Value::Array(range))) if range.len() == 2 => {
                    let (a, b) = (index(&range[0])?, index(&range[1])?);
                    if a > b {
                        return Err(bad(format!("range {a}–{b} runs backwards")));
                    }
                    Ok(Where::Positions(a, b))
                }
                _ => Err(bad(format!("`{}` is not understood", raw.get_ref()))),
            },
            other => Err(bad(format!("`{other}` is not understood"))),
        }
    }

    fn reference(
        &self,
        raw: &Spanned<toml::Value>,
        field: &str,
        quantity: Quantity,
    ) -> Result<Reference, CaseError> {
        let allowed = "{ solver = \"NAME\" } or { file = \"PATH\", key = \"KEY\" }";
        let table = match raw.get_ref() {
            toml::Value::Table(t) => t,
            other => {
                return Err(self.error(
                    raw,
                    field,
                    format!("`{other}` is not understood (allowed: {allowed})"),
                ))
            }
        };
        let get = |key: &str| table.get(key).and_then(toml::Value::as_str);
        match (get("solver"), get("file"), get("key"), table.len()) {
            (Some(name), None, None, 1) => {
                let name = Spanned::new(raw.span(), name.to_owned());
                Ok(Reference::Solver(
                    self.solver_name(&name, &format!("{field}.solver"))?,
                ))
            }
            (None, Some(file), Some(key), 2) => self.stored_value(raw, field, file, key, quantity),
            _ => Err(self.error(
                raw,
                field,
                format!("`{}` is not understood (allowed: {allowed})", raw.get_ref()),
            )),
        }
    }

    /// A value from a reference file, which is resolved against the case file's folder.
    fn stored_value(
        &self,
        raw: &Spanned<toml::Value>,
        field: &str,
        file: &str,
        key: &str,
        quantity: Quantity,
    ) -> Result<Reference, CaseError> {
        let path = self.file.parent().unwrap_or(Path::new(".")).join(file);
        let stored = reference::load(&path, key).map_err(|e| match e {
            LoadError::Unreadable(e) => self.error(
                raw,
                format!("{field}.file"),
                format!("cannot read reference file {}: {e}", path.display()),
            ),
            LoadError::NoKey => self.error(
                raw,
                format!("{field}.key"),
                format!("no key `{key}` in {}", path.display()),
            ),
            LoadError::Invalid(e) => e,
        })?;
        if stored.quantity != quantity {
            let message = format!("holds {} but the check judges {quantity}", stored.quantity);
            return Err(CaseError::new(&path, None, key, message));
        }
        Ok(Reference::Value {
            value: stored.value,
            key: format!("{file}#{key}"),
            source: stored.source,
        })
    }
}
