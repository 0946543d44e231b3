//! The FreeFEM deck `freefem-axisym`: the axisymmetric Fourier modes n = 0 (normal) and n = 1
//! (tangential, Coulomb with history), P2 displacements on the P1 mesh (MUMPS_seq), penalty contact
//! with Simpson nodal quadrature condensed onto the contact line (template
//! `templates/freefem_axisym.edp`; the model: [`super::axisym`]).

use std::path::Path;
use std::time::Duration;

use super::deck::{self, Deck, DeckKind};
use spherecontact_solvers::fem::mesh::geo::MeshFiles;
use spherecontact_system::process::Job;
use spherecontact_system::toolchain::{Tool, Toolchain, FF_LOADPATH};

/// The deck template.
pub const TEMPLATE: &str = include_str!("templates/freefem_axisym.edp");

/// FreeFEM's axisymmetric deck.
#[derive(Clone, Copy, Debug)]
pub struct FreeFem;

impl Deck for FreeFem {
    const KIND: DeckKind = DeckKind {
        name: "freefem-axisym",
        description: "FreeFEM axisymmetric FEM, one sphere on its symmetry plane, Fourier n = 0 and n = 1, P2, penalty, Coulomb with history",
        tool: Tool::FreeFem,
        template: TEMPLATE,
        file_name: "deck.edp",
    };

    type Mesh = MeshFiles;

    fn mesh_file<'a>(&self, mesh: &'a MeshFiles) -> &'a Path {
        &mesh.msh22_mm
    }

    fn job(&self, toolchain: &Toolchain, deck: &Path, timeout: Duration) -> Job {
        Job {
            program: toolchain.freefem.clone(),
            args: vec![
                "-nw".into(),
                "-ns".into(),
                "-v".into(),
                "0".into(),
                deck.display().to_string(),
            ],
            env: [("FF_LOADPATH".into(), FF_LOADPATH.into())]
                .into_iter()
                .chain(deck::single_threaded())
                .collect(),
            timeout,
        }
    }

    /// FreeFEM's codes, measured with FreeFem++ 4.11 (Debian 12): 1 for a compile error (also a
    /// mesh file that cannot be opened), 2 for a plugin that cannot be loaded, 8 for an error
    /// during execution (failed assert, index out of range, …).
    fn exit_code_meaning(&self, code: i32) -> &'static str {
        match code {
            1 => "compile error in the deck, or an input file (mesh) that cannot be opened",
            2 => {
                "a plugin (gmsh, iovtk, lapack, MUMPS_seq) failed to load: install libfreefem++, FF_LOADPATH=/usr/lib/freefem++"
            }
            8 => "execution error (failed assertion, index out of range, solver error)",
            _ => "unexpected exit code",
        }
    }
}
