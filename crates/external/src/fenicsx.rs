//! The FEniCSx deck `fenicsx-axisym`: the axisymmetric Fourier modes n = 0 (normal) and n = 1
//! (tangential, Coulomb with history) with dolfinx 0.5.2 (Debian), P2 on the quadratic mesh
//! (MUMPS), penalty contact with Gauss–Lobatto nodal quadrature condensed onto the contact line
//! (template `templates/fenicsx_axisym.py`; the model: [`super::axisym`]).

use std::path::Path;
use std::time::Duration;

use super::deck::{Deck, DeckKind};
use spherecontact_solvers::fem::mesh::geo::MeshFiles;
use spherecontact_system::process::Job;
use spherecontact_system::toolchain::{Tool, Toolchain};

/// The deck template.
pub const TEMPLATE: &str = include_str!("templates/fenicsx_axisym.py");

/// dolfinx's axisymmetric deck.
#[derive(Clone, Copy, Debug)]
pub struct Fenicsx;

impl Deck for Fenicsx {
    const KIND: DeckKind = DeckKind {
        name: "fenicsx-axisym",
        description: "FEniCSx (dolfinx) axisymmetric FEM, one sphere on its symmetry plane, Fourier n = 0 and n = 1, P2, penalty, Coulomb with history",
        tool: Tool::Dolfinx,
        template: TEMPLATE,
        file_name: "deck.py",
    };

    type Mesh = MeshFiles;

    fn mesh_file<'a>(&self, mesh: &'a MeshFiles) -> &'a Path {
        &mesh.msh41
    }

    /// Serial, no `mpirun` (faster than 2 ranks on 2 cores; mpirun as root needs extra flags).
    fn job(&self, toolchain: &Toolchain, deck: &Path, timeout: Duration) -> Job {
        super::deck::python_job(toolchain, deck, timeout)
    }

    fn exit_code_meaning(&self, code: i32) -> &'static str {
        match code {
            1 => "uncaught Python exception (traceback in stderr)",
            2 => "Python could not open the deck or its arguments were wrong",
            _ => "unexpected exit code",
        }
    }
}
