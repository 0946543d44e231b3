//! What a deck is: a template kept beside the Rust code, filled from the scene, run by one
//! external program whose exit codes it knows.

use std::path::{Path, PathBuf};
use std::time::Duration;

use super::geo::MeshFiles;
use super::process::{Ending, Job};
use super::toolchain::{Tool, Toolchain};

/// The numbers a deck template is filled with: mm, N, MPa (the decks' units).
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
    /// Penalty factor: k = kfac E / h.
    pub kfac: f64,
    /// Approaches of the modelled sphere d = δn/2 [mm], ascending.
    pub d_mm: Vec<f64>,
    /// Cap on contact iterations per approach.
    pub max_iterations: u32,
}

impl DeckInput {
    /// The `@KEY@` substitutions of the templates.
    fn substitutions(&self) -> Vec<(&'static str, String)> {
        let list = self
            .d_mm
            .iter()
            .map(|d| format!("{d:e}"))
            .collect::<Vec<_>>()
            .join(", ");
        vec![
            ("@SCENE@", self.scene.replace(['"', '\n'], " ")),
            ("@MESH@", self.mesh.clone()),
            ("@R_MM@", format!("{:e}", self.radius_mm)),
            ("@E_MPA@", format!("{:e}", self.young_mpa)),
            ("@NU@", format!("{:e}", self.poisson)),
            ("@H_MM@", format!("{:e}", self.h_mm)),
            ("@KFAC@", format!("{:e}", self.kfac)),
            ("@D_LIST_MM@", list),
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

/// One external deck: its template, its program, and the meaning of its exit codes.
pub trait Deck: Send + Sync + Clone {
    /// The solver name (`freefem-axisym`, …).
    fn name(&self) -> &'static str;
    /// One line: model and method.
    fn description(&self) -> &'static str;
    /// The tool that runs it.
    fn tool(&self) -> Tool;
    /// The deck template (kept beside the code, `templates/`).
    fn template(&self) -> &'static str;
    /// The deck's file name in the run directory.
    fn file_name(&self) -> &'static str;
    /// The mesh file it reads.
    fn mesh_file<'a>(&self, mesh: &'a MeshFiles) -> &'a Path;
    /// How `p0` is obtained (for the metadata).
    fn p0_method(&self) -> &'static str;
    /// The job that runs the deck file `deck` in the run directory.
    fn job(&self, toolchain: &Toolchain, deck: &Path, timeout: Duration) -> Job;
    /// What an exit code of this program means.
    fn exit_code_meaning(&self, code: i32) -> &'static str;
}

/// The reason a finished run failed, in words, or `None` if it succeeded.
pub fn failure(deck: &impl Deck, ending: &Ending, timeout: Duration) -> Option<String> {
    ending.failure(deck.tool().name(), timeout, |code| deck.exit_code_meaning(code))
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
            d_mm: vec![0.0085, 0.0125],
            max_iterations: 30,
        };
        for template in [super::super::freefem::TEMPLATE, super::super::fenicsx::TEMPLATE] {
            let deck = fill(template, &input);
            assert!(!deck.contains('@'), "unfilled key in {deck}");
            assert!(deck.contains("8.5e-3, 1.25e-2"));
        }
    }
}
