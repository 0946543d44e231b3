//! # spherecontact-case: case files
//!
//! **Job.** Reading and validating case files into cases: path cases into a `Case`, impact cases into an `ImpactCase`; the files a case may read, the limits on every field, and the solvers by name ([`registry`]).
//!
//! **May depend on.** `spherecontact-model`, `spherecontact-system`, `spherecontact-reference`, `spherecontact-solvers`, `spherecontact-external` (to name every solver) and `spherecontact-check` (the checks a case states).
//!
//! **Offers.** `load`, `load_impact`, `case_files`, and typed errors that name the file, the field and the allowed range.
//!
//! Case files (`cases/*.toml`): the bodies, friction, loading path, solvers and checks of one
//! verification case, read and validated into a [`Case`].
//!
//! ```toml
//! name = "hertz-normal"                 # optional, defaults to the file stem; a plain name:
//!                                       # 1–64 of A–Z a–z 0–9 . _ -, starting with a letter or digit
//! description = "…"
//! friction = 0.2                        # Coulomb 0 ≤ μ ≤ 10
//! solvers = ["hertz", "mdr"]
//! focus = 2                             # optional: the position whose surface fields reports
//!                                       # show (default: the first of largest δn)
//! fields = "every-position"             # optional: where solvers keep surface fields:
//!                                       # "every-position", "focus", or [1, 5, 7] (the focus is
//!                                       # always added); at most 16 positions. Default: every
//!                                       # position for a path of at most 16, else the focus only
//! ranks = 2                             # optional: MPI ranks of fenicsx-3d, 1 ≤ ranks ≤ 1024
//! labels = ["fast", "dem"]              # optional: what kind of work (`verify --label`);
//!                                       # fast, heavy, external, dem, paper, hard, fem, bem
//!                                       # (see [`labels`])
//!
//! [body1]                               # SI: m, Pa
//! radius = 0.1                          # 1e-9 ≤ R ≤ 1e3; `inf` for a flat
//! young = 70e9                          # 1e3 ≤ E ≤ 1e13
//! poisson = 0.3                         # −1 < ν < 0.5
//! # [body2] is optional: absent means two identical spheres
//!
//! [path]
//! unit = "um"                           # "m", "mm", "um", "µm" or "μm" (micro sign or Greek mu)
//! delta_n = [0, 10, 17]                 # total approach of the far points, |δn| ≤ R_min
//! delta_t = [0, 0, 2]                   # relative tangential displacement, |δt| ≤ R_min
//! substeps = 20                         # per segment: one count, or one per segment
//!
//! [domain]                              # optional: the finite body FEM solvers and decks mesh
//! kind = "hemisphere"                   # "hemisphere" (default) or "cap"
//! height = 0.02                         # cap only: cut this far from the pole [m],
//!                                       # 10 c_max ≤ height ≤ the smallest finite radius
//! grip = "rigid"                        # "rigid" (default) or "axial" (frictionless scenes only)
//!
//! [calculix]                            # optional: the CalculiX solvers' settings
//! contact = "face-to-face"              # node-to-face, face-to-face, mortar, linmortar, pglinmortar
//! penalty = 1e3                         # K = penalty · E / h, 1 ≤ penalty ≤ 1e6
//! element = "tet10"                     # the 3D decks' element: tet10, hex20, hex20r
//!
//! [kratos]                              # optional: the kratos-3d deck's settings
//! contact = "alm-frictional"            # alm-frictional, alm-frictionless, penalty
//! element = "tet4"                      # tet4
//! alm_factor = 1.0                      # ALM penalty and scale factor · E / h, 1e-2 to 1e4
//! penalty = 1e3                         # penalty: K = penalty · E / h, 1 ≤ penalty ≤ 1e6
//!
//! [resolution]                          # optional: per solver, over its default (see
//! bem = 128                             # `resolution`); `--resolution SOLVER=VALUE` overrides
//! fem-axisym = "c/80"                   # c/N or a length ("10um")
//!
//! [[checks]]
//! solver = "mdr"
//! quantity = "normal_force"             # normal_force, tangential_force, contact_radius,
//!                                       # peak_pressure, stick_radius; or a profile at one
//!                                       # position against another solver's: pressure_profile,
//!                                       # traction_profile (RMS over 0.1c < r < 0.9c,
//!                                       # error = "relative-to-peak", crates/solvers/src/profile.rs);
//!                                       # or a map's measure at positions (not every-step):
//!                                       # transverse_ratio, stick_semi_axis_x,
//!                                       # stick_semi_axis_y (crates/solvers/src/map_measure.rs)
//! at = "every-step"                     # "every-position", { position = 2 }, { positions = [1, 2] }
//! reference = { solver = "hertz" }      # or { file = "../reference/x.toml", key = "…" }
//! error = "relative"                    # "relative-to-peak", "absolute"
//! tolerance = 1e-6
//! reason = "why this tolerance"         # required unless informational = true
//! known_failure = "evidence …"          # optional: a code's shown defect (KNOWN, FIXED?)
//! abs_zero = 1e-10                      # optional, SI: below it a value is zero (crates/check/src/lib.rs)
//! ```
//!
//! A case may also define solvers of its own: a program run as a solver (`[[command_solvers]]`)
//! and results computed elsewhere (`[[stored_results]]`); see [`case_solvers`].
//!
//! Every rule broken gives a [`CaseError`] naming the file, the field, its line and column where
//! known, and the allowed range.
//!
//! **Physical ranges.** R_min is the smaller finite radius: Hertz, Mindlin and every solver here
//! are small-displacement theories, and a displacement beyond the radius has no meaning for them.
//! The derived quantities must be normal positive floating-point numbers: E*, R*, G*, and at the
//! largest approach (when the path closes the gap) the Hertz contact radius, force and peak
//! pressure, the stiffnesses 2E*c and 8G*c, and the sliding force μP when μ > 0.
//!
//! **Limits** ([`limits`]): what a valid case may ask for, so that it cannot exhaust the machine.
//!
//! | what | limit |
//! |---|---|
//! | case or reference file | a regular file (no FIFO, device or folder), at most 4 MiB |
//! | stored results | a regular file, at most 256 MiB |
//! | any file a case names | inside the case's folder, the nearest `reference/` folder or an `--allow-read` folder ([`reads`]) |
//! | increments of the path, in all | at most 1 000 000 (a history and its JSON: 0.43 GB a solver) |
//! | positions with surface fields | at most 16 (see `fields`) |
//! | BEM grid | at most 512² panels |
//! | MDR bed | at most 1 000 000 springs |
//! | mesh (`mesh --resolution`), fem-axisym, mdr-domain, axisymmetric decks | pole element c_max/320 to c_max/2 (R1/32 000 to R1/200 without contact): under a million triangles |
//! | fem-3d, fenicsx-3d | pole element c_max/14 to c_max/2 |

pub mod registry;

mod calculix;
pub mod case_solvers;
mod check_rules;
mod domain;
mod error;
mod fem3d;
mod impact_own;
mod impact_raw;
mod impact_rules;
mod impact_solvers;
mod kratos;
pub mod labels;
mod listing;
mod raw;
pub mod reads;
pub mod reference;
mod resolution;
mod scene_rules;
#[cfg(test)]
mod test_case;

pub use case_solvers::CaseSolver;
pub use error::CaseError;
pub use impact_rules::{is_impact, is_impact_file, load_impact, parse_impact};
pub use impact_solvers::{impact_kind_in_words, solver_names};
pub use listing::{case_files, ListError};
pub use reads::{CaseTree, ReadRoots};
pub use spherecontact_model::limits::{self, MAX_FIELD_POSITIONS, MAX_INCREMENTS};

use std::collections::{BTreeMap, BTreeSet};

use spherecontact_system::input;
use std::path::{Path, PathBuf};
use toml::Spanned;

use raw::RawCase;
use spherecontact_check::CheckSpec;
use spherecontact_model::domain::Domain;
use spherecontact_model::number::Short;
use spherecontact_model::pair::ContactPair;
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::Solver;
use spherecontact_model::stick_slope::StickSlope;

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
    /// The solvers the case defines itself (commands, stored results).
    pub own_solvers: Vec<CaseSolver>,
    /// MPI ranks of the solvers that run under MPI (`fenicsx-3d`); 1 by default.
    pub ranks: u32,
    /// The folders whose files the case may read ([`reads`]).
    pub tree: CaseTree,
    /// The CalculiX solvers' settings (`[calculix]`; the defaults when absent).
    pub calculix: spherecontact_model::calculix_settings::Settings,
    /// The Kratos FEM deck's settings (`[kratos]`; the defaults when absent).
    pub kratos: spherecontact_model::kratos_settings::Settings,
    /// fem-3d's regularised stick (`[fem-3d] stick_slope`); `None`: exact Coulomb friction.
    pub stick_slope: Option<StickSlope>,
    /// What kind of work the case is ([`labels::LABELS`]), in its order.
    pub labels: Vec<String>,
    /// The resolution chosen per solver (`[resolution]`, then `--resolution`), each value
    /// accepted by its solver for this scene; solvers not named run at their default.
    pub resolution: BTreeMap<String, String>,
}

/// The text of the case file `file` (path or impact case): a regular file of at most 4 MiB,
/// UTF-8 ([`input::read_text`]).
pub fn read_case_file(file: &Path) -> Result<String, CaseError> {
    input::read_text(file)
        .map_err(|e| CaseError::new(file, None, "", format!("cannot read the case file: {e}")))
}

impl Case {
    /// Reads and validates the case file at `file` (a regular file of at most 4 MiB); the files
    /// it names must lie in its own tree ([`reads`]).
    pub fn load(file: &Path) -> Result<Self, CaseError> {
        Self::load_with(file, &ReadRoots::default())
    }

    /// [`Case::load`], the files it names also read from the folders `roots` allows.
    pub fn load_with(file: &Path, roots: &ReadRoots) -> Result<Self, CaseError> {
        Self::parse_with(file, &read_case_file(file)?, roots)
    }

    /// Validates the text of a case file; `file` names it in errors and anchors the files it
    /// names, which must lie in its own tree.
    pub fn parse(file: &Path, text: &str) -> Result<Self, CaseError> {
        Self::parse_with(file, text, &ReadRoots::default())
    }

    /// [`Case::parse`], the files it names also read from the folders `roots` allows.
    pub fn parse_with(file: &Path, text: &str, roots: &ReadRoots) -> Result<Self, CaseError> {
        let raw: RawCase = toml::from_str(text).map_err(|e| {
            // The parser locates its errors but does not name the field: read it at the span.
            let field = e.span().and_then(|s| error::field_at(text, s.start));
            let message = error::parser_message(&e);
            CaseError::new(
                file,
                e.span().map(|s| (text, s)),
                field.unwrap_or_default(),
                message,
            )
        })?;
        Validator {
            file,
            text,
            tree: roots.tree(file),
            own: Vec::new(),
        }
        .case(raw)
    }

    /// The case's name (its scene's).
    pub fn name(&self) -> &str {
        &self.scene.name
    }

    /// The solver called `name` (one the case defines, else one of this build) on the case's
    /// ranks and at the resolution chosen for it.
    pub fn solver(&self, name: &str) -> Option<Box<dyn Solver>> {
        self.unresolved_solver(name).map(|s| self.resolved(s))
    }

    /// The names of the solvers a case may name: this build's and the case's own.
    pub fn solver_names(&self) -> Vec<String> {
        let mut names = registry::names();
        names.extend(self.own_solvers.iter().map(|s| s.name().to_owned()));
        names
    }

    /// The solver called `name` on the case's ranks, at its default resolution.
    fn unresolved_solver(&self, name: &str) -> Option<Box<dyn Solver>> {
        let solver = self
            .own_solvers
            .iter()
            .find(|s| s.name() == name)
            .map(CaseSolver::solver)
            .or_else(|| registry::by_name(name))?;
        let solver = solver.with_ranks(self.ranks).unwrap_or(solver);
        let solver = solver.with_calculix(&self.calculix).unwrap_or(solver);
        let solver = solver.with_kratos(&self.kratos).unwrap_or(solver);
        match self.stick_slope {
            Some(slope) => Some(solver.with_stick_slope(slope).unwrap_or(solver)),
            None => Some(solver),
        }
    }

    /// Every solver the case needs: its own list, then those its checks refer to.
    pub fn required_solvers(&self) -> Vec<String> {
        let mut names = self.solvers.clone();
        for check in &self.checks {
            for name in check.solvers() {
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
    /// What the case may read.
    tree: CaseTree,
    /// The names of the solvers the case defines itself.
    own: Vec<String>,
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

    /// A deck table's setting (`[calculix]`, `[kratos]`, …): `default` if the case leaves it out,
    /// else `parse` of its value, whose error is located at the value under `field`.
    fn setting<T, V, E: std::fmt::Display>(
        &self,
        raw: Option<&Spanned<T>>,
        field: &str,
        default: V,
        parse: impl FnOnce(&T) -> Result<V, E>,
    ) -> Result<V, CaseError> {
        match raw {
            None => Ok(default),
            Some(value) => parse(value.get_ref()).map_err(|e| self.error(value, field, e.to_string())),
        }
    }

    /// A number in the range the predicate describes (`allowed`, in words).
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
            Err(self.error(
                value,
                field,
                format!("{} is out of range (allowed: {allowed})", Short(v)),
            ))
        }
    }

    /// The Coulomb coefficient `friction`, 0 ≤ μ ≤ 10.
    fn friction(&self, value: &Spanned<f64>) -> Result<f64, CaseError> {
        self.number(
            value,
            "friction",
            |m| (0.0..=limits::MAX_FRICTION).contains(&m),
            "0 ≤ μ ≤ 10",
        )
    }

    /// An unknown quantity at `field`, listing `names`.
    fn unknown_quantity(&self, raw: &Spanned<String>, field: &str, names: &[&str]) -> CaseError {
        self.error(
            raw,
            format!("{field}.quantity"),
            format!(
                "unknown quantity `{}` (allowed: {})",
                raw.get_ref(),
                names.join(", ")
            ),
        )
    }

    fn case(mut self, raw: RawCase) -> Result<Case, CaseError> {
        let name = self.name(raw.name.as_ref())?;
        let friction = self.friction(&raw.friction)?;
        let pair = self.pair(&raw)?;
        let path = self.path(&raw.path, &pair)?;
        self.derived(&raw, &pair, friction, &path)?;
        let own_solvers = self.case_solvers(&raw.command_solvers, &raw.stored_results, &path)?;
        self.own = own_solvers.iter().map(|s| s.name().to_owned()).collect();
        let solvers = self.solvers(&raw.solvers)?;
        let checks = raw
            .checks
            .iter()
            .enumerate()
            .map(|(i, c)| self.check(c, &format!("checks[{i}]"), path.positions().len()))
            .collect::<Result<_, _>>()?;
        let focus = self.focus(raw.focus.as_ref(), &path)?;
        let labels = self.labels(raw.labels.as_ref())?;
        let fields = self.fields(raw.fields.as_ref(), path.positions().len(), focus)?;
        let mut scene = Scene {
            name,
            pair,
            friction,
            path,
            domain: Domain::default(),
            fields,
        };
        if let Some(domain) = &raw.domain {
            scene.domain = self.domain(domain, &scene)?;
        }
        let ranks = match &raw.ranks {
            None => 1,
            Some(value) => {
                let max = i64::from(limits::MAX_RANKS);
                let n = *value.get_ref();
                u32::try_from(n)
                    .ok()
                    .filter(|_| (1..=max).contains(&n))
                    .ok_or_else(|| {
                        self.error(
                            value,
                            "ranks",
                            format!("{n} is out of range (allowed: 1 ≤ ranks ≤ {max})"),
                        )
                    })?
            }
        };
        let mut case = Case {
            file: self.file.to_path_buf(),
            focus,
            description: raw.description.unwrap_or_default(),
            scene,
            solvers,
            checks,
            own_solvers,
            ranks,
            tree: self.tree.clone(),
            calculix: match &raw.calculix {
                Some(table) => self.calculix(table)?,
                None => Default::default(),
            },
            kratos: match &raw.kratos {
                Some(table) => self.kratos(table)?,
                None => Default::default(),
            },
            stick_slope: match &raw.fem3d {
                Some(table) => self.fem3d(table)?,
                None => None,
            },
            labels,
            resolution: BTreeMap::new(),
        };
        if let Some(table) = &raw.resolution {
            self.resolution(table, &mut case)?;
        }
        Ok(case)
    }

    /// The two bodies: each in range, and not two flats.
    fn pair(&self, raw: &RawCase) -> Result<ContactPair, CaseError> {
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
        Ok(ContactPair { body1, body2 })
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
        if self.own.contains(name.get_ref()) || registry::by_name(name.get_ref()).is_some() {
            return Ok(name.get_ref().clone());
        }
        let mut known = registry::names();
        known.extend(self.own.iter().cloned());
        let unknown = registry::unknown(name.get_ref(), &known);
        Err(self.error(name, field, format!("{unknown} (allowed: {})", known.join(", "))))
    }
}
