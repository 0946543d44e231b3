//! What a deck is: a template kept beside the Rust code, filled from the scene, run by one
//! external program whose exit codes it knows.

use std::path::{Path, PathBuf};
use std::time::Duration;

use spherecontact_model::domain::Grip;
use spherecontact_model::limits::MAX_SHOWN_LINES;
use spherecontact_model::solver::SolveError;
use spherecontact_system::process::{Ending, Job, Run};
use spherecontact_system::toolchain::{Tool, Toolchain};

/// The numbers a deck template is filled with: mm, N, MPa (the decks' units). The computed
/// steps go into a separate file ([`PATH_FILE`]): a path has more steps than FreeFEM accepts in
/// an array literal (1024).
#[derive(Clone, Debug, PartialEq)]
pub struct DeckInput {
    /// The scene's name (a comment in the deck).
    pub scene: String,
    /// The mesh file name, relative to the run directory.
    pub mesh: String,
    /// Sphere radius [mm].
    pub radius_mm: f64,
    /// Young's modulus [MPa].
    pub young_mpa: f64,
    /// Poisson ratio.
    pub poisson: f64,
    /// Pole element size [mm].
    pub h_mm: f64,
    /// Penalty factor: k = kfac E / h, normal and tangential.
    pub kfac: f64,
    /// Coulomb friction coefficient μ.
    pub friction: f64,
    /// How the far face is held: the scene's `[domain]` grip, as its mesh is tagged.
    pub grip: Grip,
    /// Contact-line nodes with r below this are contact candidates [mm].
    pub candidate_radius_mm: f64,
    /// Whether the tangential (Fourier n = 1) mode is solved.
    pub tangential: bool,
    /// Cap on contact iterations per step and mode.
    pub max_iterations: u32,
}

/// The Python block both dolfinx decks share (imports, the template's numbers, the list of steps,
/// the normal contact's Newton), inserted where a template says `@FENICSX_COMMON@`.
pub const FENICSX_COMMON: &str = include_str!("templates/fenicsx_common.py");

/// The file that lists a deck's computed steps: a count, then one line per step with its path
/// index, d = δn/2 [mm], t = δt/2 [mm], and the path position it reaches or −1.
pub const PATH_FILE: &str = "path.txt";

/// The stem of a deck's logs (`deck.stdout`, `deck.stderr`), in its own run ([`run_written`])
/// and in a deck folder's run script ([`super::split::RUN_SCRIPT`]).
pub const LOG_STEM: &str = "deck";

/// One step a deck computes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ComputedStep {
    /// The path step index.
    pub step: usize,
    /// The modelled sphere's approach d = δn/2 [m].
    pub d: f64,
    /// The modelled sphere's far-face shift t = δt/2 [m].
    pub t: f64,
    /// The path position this step reaches, if any (the deck writes a field file there).
    pub position: Option<usize>,
}

/// The text of [`PATH_FILE`] for `steps` (lengths in mm, full precision).
pub fn path_file(steps: &[ComputedStep]) -> String {
    let mut text = format!("{}\n", steps.len());
    for s in steps {
        let position = s.position.map_or(-1, |p| i64::try_from(p).unwrap_or(-1));
        text.push_str(&format!(
            "{} {:e} {:e} {position}\n",
            s.step,
            s.d * 1e3,
            s.t * 1e3
        ));
    }
    text
}

impl DeckInput {
    /// The `@KEY@` substitutions of the templates.
    fn substitutions(&self) -> Vec<(&'static str, String)> {
        vec![
            // First, so that the keys of the inserted block are filled by the ones below.
            ("@FENICSX_COMMON@", FENICSX_COMMON.to_owned()),
            ("@SCENE@", self.scene.replace(['"', '\n'], " ")),
            ("@MESH@", self.mesh.clone()),
            ("@R_MM@", format!("{:e}", self.radius_mm)),
            ("@E_MPA@", format!("{:e}", self.young_mpa)),
            ("@NU@", format!("{:e}", self.poisson)),
            ("@H_MM@", format!("{:e}", self.h_mm)),
            ("@KFAC@", format!("{:e}", self.kfac)),
            ("@MU@", format!("{:e}", self.friction)),
            ("@GRIP_RADIAL@", u8::from(self.grip == Grip::Rigid).to_string()),
            (
                "@FAR_TAG@",
                spherecontact_solvers::fem::mesh::geo::far_face_tag(self.grip).to_string(),
            ),
            ("@CANDIDATE_RADIUS_MM@", format!("{:e}", self.candidate_radius_mm)),
            ("@TANGENTIAL@", u8::from(self.tangential).to_string()),
            ("@PATH_FILE@", PATH_FILE.to_owned()),
            ("@MAX_ITERATIONS@", self.max_iterations.to_string()),
        ]
    }
}

/// Fills every `@KEY@` of `template` from `input`.
pub fn fill(template: &str, input: &DeckInput) -> String {
    input
        .substitutions()
        .into_iter()
        .fold(template.to_owned(), |text, (key, value)| {
            text.replace(key, &value)
        })
}

/// The environment every deck runs in: one BLAS/OpenMP thread per process. Reason: OpenBLAS
/// (pthreads) and OpenMP split their reductions by thread count, so a deck's last bits would
/// depend on the machine's cores (measured: the FEniCSx deck's steps.csv is bit-identical run to
/// run at a fixed thread count, and differs between one thread and the default); the condensed
/// problems are small enough that threads gain little on a shared machine, and MPI decks get
/// their parallelism from ranks. FreeFEM's MUMPS_seq stays nondeterministic in the last bits
/// even on one thread (P and Q differ by ≈ 1e-14 relative between two runs on the same files;
/// with UMFPACK the runs are bit-identical): far below every tolerance, and MUMPS's solves are
/// 4 × faster (docs/external-decks.md).
pub fn single_threaded() -> Vec<(String, String)> {
    ["OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS"]
        .map(|k| (k.to_owned(), "1".to_owned()))
        .to_vec()
}

/// `python3 deck` (the toolchain's Python, one BLAS thread): how a dolfinx deck runs serially.
pub fn python_job(toolchain: &Toolchain, deck: &Path, timeout: Duration) -> Job {
    Job {
        program: toolchain.python.clone(),
        args: vec![deck.display().to_string()],
        env: single_threaded(),
        timeout,
    }
}

/// What names a deck: a table row, the same fields for every deck.
#[derive(Clone, Copy, Debug)]
pub struct DeckKind {
    /// The solver name (`freefem-axisym`, …).
    pub name: &'static str,
    /// One line: model and method.
    pub description: &'static str,
    /// The tool that runs it.
    pub tool: Tool,
    /// The deck template (kept beside the code, `templates/`).
    pub template: &'static str,
    /// The deck's file name in the run directory.
    pub file_name: &'static str,
}

/// One external deck: what names it, its mesh, its program, and the meaning of its exit codes.
pub trait Deck: Send + Sync + Clone {
    /// What names it.
    const KIND: DeckKind;
    /// The solver name.
    fn name(&self) -> &'static str {
        Self::KIND.name
    }
    /// One line: model and method.
    fn description(&self) -> &'static str {
        Self::KIND.description
    }
    /// The tool that runs it.
    fn tool(&self) -> Tool {
        Self::KIND.tool
    }
    /// The deck template.
    fn template(&self) -> &'static str {
        Self::KIND.template
    }
    /// The deck's file name in the run directory.
    fn file_name(&self) -> &'static str {
        Self::KIND.file_name
    }
    /// The meshes gmsh writes for it (the meridian's [`MeshFiles`], the solid's
    /// [`spherecontact_solvers::fem::mesh::solid_geo::SolidMeshFiles`]).
    type Mesh;
    /// The mesh file it reads, of those.
    fn mesh_file<'a>(&self, mesh: &'a Self::Mesh) -> &'a Path;
    /// The job that runs the deck file `deck` in the run directory.
    fn job(&self, toolchain: &Toolchain, deck: &Path, timeout: Duration) -> Job;
    /// What an exit code of this program means.
    fn exit_code_meaning(&self, code: i32) -> &'static str;
}

/// The reason a finished run failed, in words, or `None` if it succeeded.
pub fn failure(deck: &impl Deck, ending: &Ending, timeout: Duration) -> Option<String> {
    ending.failure(deck.tool().name(), timeout, |code| deck.exit_code_meaning(code))
}

/// How long a deck may run when its options set no time limit: start-up (imports, form
/// compilation), set-up (assembly, factorisation, condensation), and a time per computed step.
#[derive(Clone, Copy, Debug)]
pub struct TimeBudget {
    /// Start-up.
    pub start: Duration,
    /// Set-up.
    pub setup: Duration,
    /// Per computed step.
    pub per_step: Duration,
}

impl TimeBudget {
    /// The limit for `steps` computed steps.
    pub fn limit(&self, steps: usize) -> Duration {
        self.start + self.setup + self.per_step * u32::try_from(steps).unwrap_or(u32::MAX)
    }
}

/// Writes the filled deck `text` (as the deck's file name) and the list of `steps`
/// ([`PATH_FILE`]) into `dir`.
pub fn write_deck(
    deck: &impl Deck,
    dir: &Path,
    text: &str,
    steps: &[ComputedStep],
) -> Result<(), SolveError> {
    let write = |name: &str, text: &str| {
        std::fs::write(dir.join(name), text).map_err(|e| SolveError::Failed(format!("writing {name}: {e}")))
    };
    write(deck.file_name(), text)?;
    write(PATH_FILE, &path_file(steps))
}

/// Writes the filled deck `text` and the list of `steps` into `dir`, runs the deck there within
/// `timeout`, and returns the finished run; a run that failed (exit code, signal, timeout) is an
/// error with the reason and the last lines of its log.
pub fn launch(
    deck: &impl Deck,
    toolchain: &Toolchain,
    dir: &Path,
    text: &str,
    steps: &[ComputedStep],
    timeout: Duration,
) -> Result<Run, SolveError> {
    write_deck(deck, dir, text, steps)?;
    run_written(deck, toolchain, dir, timeout)
}

/// Runs the deck already written into `dir` ([`write_deck`]) there within `timeout`, and returns
/// the finished run; a run that failed (exit code, signal, timeout) is an error with the reason
/// and the last lines of its log.
pub fn run_written(
    deck: &impl Deck,
    toolchain: &Toolchain,
    dir: &Path,
    timeout: Duration,
) -> Result<Run, SolveError> {
    let job = deck.job(toolchain, &dir.join(deck.file_name()), timeout);
    let run = spherecontact_system::process::run(&job, dir, LOG_STEM)
        .map_err(|e| SolveError::Failed(format!("{} could not start: {e}", job.program.display())))?;
    match failure(deck, &run.ending, timeout) {
        Some(why) => Err(SolveError::Failed(format!(
            "{why}; last output:\n{}",
            run.tail(MAX_SHOWN_LINES)
        ))),
        None => Ok(run),
    }
}

/// Runs `work` in a fresh run directory named after `prefix`: removed when `work` succeeds,
/// kept when it fails (its path appended to the error) for the deck, mesh and logs.
pub fn in_run_dir<T>(
    prefix: &str,
    work: impl FnOnce(&RunDir) -> Result<T, SolveError>,
) -> Result<T, SolveError> {
    let mut dir =
        RunDir::new(prefix).map_err(|e| SolveError::Failed(format!("no temporary directory: {e}")))?;
    match work(&dir) {
        Err(SolveError::Failed(message)) => Err(SolveError::Failed(format!(
            "{message} (deck, mesh, stdout and stderr kept in {})",
            dir.keep().display()
        ))),
        other => other,
    }
}

/// A run directory whose files are removed on success and kept on failure.
pub struct RunDir {
    dir: Option<tempfile::TempDir>,
}

impl RunDir {
    /// A fresh temporary directory.
    pub fn new(prefix: &str) -> std::io::Result<Self> {
        Ok(Self {
            dir: Some(tempfile::Builder::new().prefix(prefix).tempdir()?),
        })
    }

    /// Its path.
    pub fn path(&self) -> &Path {
        self.dir.as_ref().map_or(Path::new("."), |d| d.path())
    }

    /// Keeps the directory (deck, mesh, stdout, stderr) for inspection and returns its path.
    pub fn keep(&mut self) -> PathBuf {
        self.dir.take().map_or_else(PathBuf::new, tempfile::TempDir::keep)
    }
}

/// Whether a filled deck still holds a key: @ + capitals and underscores + @ (Python's matrix
/// product `a @ b` is not one).
#[cfg(test)]
pub(crate) fn has_unfilled_key(deck: &str) -> bool {
    deck.match_indices('@').any(|(i, _)| {
        let key: String = deck[i + 1..]
            .chars()
            .take_while(|c| c.is_ascii_uppercase() || *c == '_')
            .collect();
        !key.is_empty() && deck[i + 1 + key.len()..].starts_with('@')
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_of_both_templates_is_filled() {
        let input = DeckInput {
            scene: "s".into(),
            mesh: "m.msh".into(),
            radius_mm: 100.0,
            young_mpa: 7e4,
            poisson: 0.3,
            h_mm: 0.02,
            kfac: 1e3,
            friction: 0.2,
            grip: Grip::Rigid,
            candidate_radius_mm: 1.25,
            tangential: true,
            max_iterations: 30,
        };
        for template in [super::super::freefem::TEMPLATE, super::super::fenicsx::TEMPLATE] {
            let deck = fill(template, &input);
            assert!(!has_unfilled_key(&deck), "unfilled key in {deck}");
            assert!(deck.contains("1.25e0") && deck.contains(PATH_FILE));
        }
    }

    #[test]
    fn the_path_file_lists_steps_in_mm_with_positions() {
        let steps = [
            ComputedStep {
                step: 0,
                d: 0.0,
                t: 0.0,
                position: Some(0),
            },
            ComputedStep {
                step: 1,
                d: 8.5e-6,
                t: -5e-7,
                position: None,
            },
        ];
        let text = path_file(&steps);
        let lines: Vec<Vec<&str>> = text.lines().map(|l| l.split(' ').collect()).collect();
        assert_eq!(lines[0], ["2"]);
        assert_eq!(lines[1], ["0", "0e0", "0e0", "0"]);
        assert_eq!((lines[2][0], lines[2][3]), ("1", "-1"));
        let mm = |s: &str| s.parse::<f64>().unwrap();
        assert!((mm(lines[2][1]) - 8.5e-3).abs() < 1e-18 && (mm(lines[2][2]) + 5e-4).abs() < 1e-18);
    }
}
