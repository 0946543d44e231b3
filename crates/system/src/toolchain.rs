//! Finding the external tools, their versions and how to install them (`spherecontact doctor`).
//!
//! Debian 12's packages are the dependable set (docs/toolchain.md): gmsh 4.8.4,
//! FreeFem++ 4.11 with its plugins in `/usr/lib/freefem++`, and dolfinx 0.5.2, meshio and h5py
//! for Debian's own `/usr/bin/python3` (not whichever `python3` is first on PATH).
//! Kratos (DEMApplication) is not a Debian package: `scripts/setup.sh` installs its PyPI wheels
//! into the project's own virtual environment, [`KRATOS_PYTHON`]'s, with Debian's Python 3.11
//! (the DEMApplication, and the structural and contact applications of the `kratos-3d` deck).
//! `scripts/setup.sh` installs them all.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Duration;

use super::process::{self, Job};

/// Where Debian's libfreefem++ puts the FreeFEM plugins (`gmsh`, `iovtk`); Debian's
/// `/etc/freefem++.pref` points elsewhere, so every FreeFem++ run gets `FF_LOADPATH` set to this.
pub const FF_LOADPATH: &str = "/usr/lib/freefem++";

/// The Python of the project's Kratos environment (`scripts/setup.sh` makes it: a virtual
/// environment of Debian's `/usr/bin/python3` with the `KratosMultiphysics` wheels).
pub const KRATOS_PYTHON: &str = "/opt/spherecontact/venv/bin/python";

/// How long a version probe may take (a dolfinx import takes 1–2 s).
const PROBE_TIMEOUT: Duration = Duration::from_secs(60);

/// One external tool the decks need.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tool {
    /// The gmsh mesher (command line).
    Gmsh,
    /// FreeFem++ with its `gmsh` and `iovtk` plugins.
    FreeFem,
    /// dolfinx (FEniCSx) and the gmsh Python module, for `/usr/bin/python3`.
    Dolfinx,
    /// meshio and h5py, for `/usr/bin/python3`: reads field files back.
    Meshio,
    /// LAMMPS (`lmp`) with its GRANULAR package: the `lammps-*` DEM solvers.
    Lammps,
    /// YADE (`yade`): the `yade-mindlin` DEM solver.
    Yade,
    /// LIGGGHTS-PUBLIC (`liggghts`) with `pair gran` Hertz and tangential history: the
    /// `liggghts-*` DEM solvers.
    Liggghts,
    /// CalculiX (`ccx`): the `ccx-axisym` deck.
    Ccx,
    /// Kratos' DEMApplication, for [`KRATOS_PYTHON`]: the `kratos-*` DEM solvers.
    KratosDem,
    /// Kratos' StructuralMechanics, ContactStructuralMechanics and LinearSolvers applications,
    /// for [`KRATOS_PYTHON`]: the `kratos-3d` FEM deck (mortar augmented-Lagrangian contact).
    KratosContact,
}

impl Tool {
    /// Every tool, in the order `doctor` lists them.
    pub const ALL: [Tool; 10] = [
        Tool::Gmsh,
        Tool::FreeFem,
        Tool::Dolfinx,
        Tool::Meshio,
        Tool::Lammps,
        Tool::Yade,
        Tool::Liggghts,
        Tool::Ccx,
        Tool::KratosDem,
        Tool::KratosContact,
    ];

    /// The tool's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Tool::Gmsh => "gmsh",
            Tool::FreeFem => "FreeFem++",
            Tool::Dolfinx => "dolfinx",
            Tool::Meshio => "meshio",
            Tool::Lammps => "LAMMPS",
            Tool::Yade => "YADE",
            Tool::Liggghts => "LIGGGHTS",
            Tool::Ccx => "CalculiX",
            Tool::KratosDem => "Kratos DEM",
            Tool::KratosContact => "Kratos contact",
        }
    }

    /// The command that installs it (all of them: `scripts/setup.sh`).
    pub fn install_command(self) -> &'static str {
        match self {
            Tool::Gmsh => "apt-get install gmsh",
            Tool::FreeFem => "apt-get install freefem++ libfreefem++",
            Tool::Dolfinx => "apt-get install python3-dolfinx-real python3-gmsh",
            Tool::Meshio => "apt-get install python3-meshio python3-h5py",
            Tool::Lammps => "apt-get install lammps",
            Tool::Yade => "apt-get install yade",
            Tool::Liggghts => "apt-get install liggghts",
            Tool::Ccx => "apt-get install --no-install-recommends calculix-ccx",
            Tool::KratosDem => {
                "python3 -m venv /opt/spherecontact/venv && /opt/spherecontact/venv/bin/pip install \
                 KratosMultiphysics==10.4.4 KratosDEMApplication==10.4.4"
            }
            Tool::KratosContact => {
                "python3 -m venv /opt/spherecontact/venv && /opt/spherecontact/venv/bin/pip install \
                 KratosMultiphysics==10.4.4 KratosStructuralMechanicsApplication==10.4.4 \
                 KratosContactStructuralMechanicsApplication==10.4.4 KratosLinearSolversApplication==10.4.4"
            }
        }
    }
}

/// The executables the decks are run with.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Toolchain {
    /// The gmsh executable.
    pub gmsh: PathBuf,
    /// The FreeFem++ executable.
    pub freefem: PathBuf,
    /// The Python interpreter that has dolfinx, gmsh, meshio and h5py.
    pub python: PathBuf,
    /// The LAMMPS executable.
    pub lammps: PathBuf,
    /// The YADE executable.
    pub yade: PathBuf,
    /// The LIGGGHTS executable.
    pub liggghts: PathBuf,
    /// The CalculiX executable.
    pub ccx: PathBuf,
    /// The Python interpreter that has Kratos (its DEMApplication).
    pub kratos_python: PathBuf,
}

impl Default for Toolchain {
    /// Debian's: `gmsh`, `FreeFem++`, `lmp`, `yade`, `liggghts` and `ccx` from PATH,
    /// `/usr/bin/python3`; Kratos' [`KRATOS_PYTHON`].
    fn default() -> Self {
        Self {
            gmsh: "gmsh".into(),
            freefem: "FreeFem++".into(),
            python: "/usr/bin/python3".into(),
            lammps: "lmp".into(),
            yade: "yade".into(),
            liggghts: "liggghts".into(),
            ccx: "ccx".into(),
            kratos_python: KRATOS_PYTHON.into(),
        }
    }
}

/// What a probe of one tool found.
#[derive(Clone, Debug, PartialEq)]
pub struct Probe {
    /// The tool.
    pub tool: Tool,
    /// The executable that runs it, if found.
    pub path: Option<PathBuf>,
    /// Its version, or why it does not work.
    pub version: Result<String, String>,
}

impl Probe {
    /// True when the tool was found and reported a version.
    pub fn available(&self) -> bool {
        self.version.is_ok()
    }

    /// One line for `doctor`: found or not, path, version, install command.
    pub fn line(&self) -> String {
        let path = self
            .path
            .as_ref()
            .map_or_else(|| "-".to_owned(), |p| p.display().to_string());
        match &self.version {
            Ok(version) => format!("{:<10} found      {version:<10} {path}", self.tool.name()),
            Err(why) => format!(
                "{:<10} NOT FOUND  {path}: {why}; install: {} (or scripts/setup.sh)",
                self.tool.name(),
                self.tool.install_command()
            ),
        }
    }
}

impl Toolchain {
    /// The executable that runs `tool`.
    pub fn executable(&self, tool: Tool) -> &Path {
        match tool {
            Tool::Gmsh => &self.gmsh,
            Tool::FreeFem => &self.freefem,
            Tool::Dolfinx | Tool::Meshio => &self.python,
            Tool::Lammps => &self.lammps,
            Tool::Yade => &self.yade,
            Tool::Liggghts => &self.liggghts,
            Tool::Ccx => &self.ccx,
            Tool::KratosDem | Tool::KratosContact => &self.kratos_python,
        }
    }

    /// Finds `tool` and asks it for its version (runs it once, in a temporary directory).
    pub fn probe(&self, tool: Tool) -> Probe {
        let Some(path) = which(self.executable(tool)) else {
            return Probe {
                tool,
                path: None,
                version: Err(format!("{} not on PATH", self.executable(tool).display())),
            };
        };
        let version = version_of(tool, &path);
        Probe {
            tool,
            path: Some(path),
            version,
        }
    }

    /// Every tool's probe, in [`Tool::ALL`] order.
    pub fn doctor(&self) -> Vec<Probe> {
        Tool::ALL.iter().map(|&t| self.probe(t)).collect()
    }

    /// `Ok(version)` if `tool` works, else the "not installed" message a solver reports.
    /// The default toolchain's probes are made once per process.
    pub fn require(&self, tool: Tool) -> Result<String, String> {
        let probe = if *self == Toolchain::default() {
            static SYSTEM: OnceLock<Vec<Probe>> = OnceLock::new();
            SYSTEM.get_or_init(|| self.doctor())[Tool::ALL.iter().position(|&t| t == tool).unwrap_or(0)]
                .clone()
        } else {
            self.probe(tool)
        };
        probe.version.map_err(|why| {
            format!(
                "{} not installed ({why}); run scripts/setup.sh or {}",
                tool.name(),
                tool.install_command()
            )
        })
    }
}

/// The executable `program` resolves to: itself if it is a path, else the first match on PATH.
pub fn which(program: &Path) -> Option<PathBuf> {
    let is_file = |p: &Path| p.is_file();
    if program.components().count() > 1 {
        return is_file(program).then(|| program.to_path_buf());
    }
    std::env::split_paths(&std::env::var_os("PATH")?)
        .map(|dir| dir.join(program))
        .find(|p| is_file(p))
}

/// The version line of `lmp -h` ("… Simulator - 29 Sep 2021 - Update 2"), if the GRANULAR
/// package is built in (the `lammps-*` solvers need `pair_style granular`).
fn lammps_version(help: &str) -> Result<Option<String>, String> {
    if !help
        .lines()
        .any(|l| l.split_whitespace().any(|w| w == "GRANULAR"))
    {
        return Err("lmp is built without the GRANULAR package (pair_style granular)".into());
    }
    Ok(help
        .lines()
        .find_map(|l| l.split_once("Simulator - ").map(|(_, v)| v.trim().to_owned())))
}

/// The version of `liggghts -h` ("LIGGGHTS (Version LIGGGHTS-PUBLIC 3.8.0, compiled …"), if
/// its help lists the models the `liggghts-*` solvers use (normal `hertz`, tangential `history`).
fn liggghts_version(help: &str) -> Result<Option<String>, String> {
    let listed = |word: &str| help.lines().any(|l| l.split_whitespace().any(|w| w == word));
    if !(listed("hertz") && listed("history")) {
        return Err("liggghts lists no normal model hertz or tangential model history (liggghts -h)".into());
    }
    Ok(help.lines().find_map(|l| {
        let rest = l.split_once("(Version ")?.1;
        Some(rest.split([',', ')']).next()?.trim().to_owned())
    }))
}

/// Runs the tool's version query in a temporary directory.
fn version_of(tool: Tool, path: &Path) -> Result<String, String> {
    let dir = tempfile::tempdir().map_err(|e| format!("no temporary directory: {e}"))?;
    let (args, env): (Vec<String>, Vec<(String, String)>) = match tool {
        Tool::Gmsh => (vec!["-version".into()], vec![]),
        Tool::FreeFem => {
            // The plugins the decks load must be there too: a FreeFEM without libfreefem++
            // fails on `load "gmsh"` with exit code 2.
            let script = "load \"gmsh\"\nload \"iovtk\"\nload \"lapack\"\nload \"MUMPS_seq\"\n\
                          cout << \"ffversion \" << version << endl;\n";
            std::fs::write(dir.path().join("version.edp"), script).map_err(|e| e.to_string())?;
            (
                vec![
                    "-nw".into(),
                    "-ns".into(),
                    "-v".into(),
                    "0".into(),
                    "version.edp".into(),
                ],
                vec![("FF_LOADPATH".into(), FF_LOADPATH.into())],
            )
        }
        Tool::Dolfinx => (
            vec![
                "-c".into(),
                "import gmsh, dolfinx; print(dolfinx.__version__)".into(),
            ],
            vec![],
        ),
        Tool::Meshio => (
            vec![
                "-c".into(),
                "import h5py, meshio; print(meshio.__version__)".into(),
            ],
            vec![],
        ),
        Tool::Lammps => (vec!["-h".into()], vec![]),
        Tool::Yade => (vec!["--version".into()], vec![]),
        Tool::Liggghts => (vec!["-h".into()], vec![]),
        Tool::Ccx => (vec!["-v".into()], vec![]),
        // Kratos prints a banner when imported: the version comes on a line of its own.
        Tool::KratosDem => (
            vec![
                "-c".into(),
                "import importlib.metadata as m, KratosMultiphysics.DEMApplication; \
                 print('kratosversion', m.version('KratosDEMApplication'))"
                    .into(),
            ],
            vec![("OMP_NUM_THREADS".into(), "1".into())],
        ),
        // The three applications the kratos-3d deck imports, and the direct solver it names.
        Tool::KratosContact => (
            vec![
                "-c".into(),
                "import importlib.metadata as m, KratosMultiphysics.StructuralMechanicsApplication, \
                 KratosMultiphysics.ContactStructuralMechanicsApplication, \
                 KratosMultiphysics.LinearSolversApplication; \
                 print('kratosversion', m.version('KratosContactStructuralMechanicsApplication'))"
                    .into(),
            ],
            vec![("OMP_NUM_THREADS".into(), "1".into())],
        ),
    };
    let job = Job {
        program: path.to_path_buf(),
        args,
        env,
        timeout: PROBE_TIMEOUT,
    };
    let run = process::run(&job, dir.path(), "version").map_err(|e| e.to_string())?;
    // ccx 2.20 prints its version and exits with code 201; liggghts 3.8.0 its help with code 1.
    let answered =
        matches!(tool, Tool::Ccx | Tool::Liggghts) && matches!(run.ending, process::Ending::Exited(_));
    if let Some(failure) = run
        .ending
        .failure(tool.name(), PROBE_TIMEOUT, |_| "its version probe failed")
        .filter(|_| !answered)
    {
        return Err(format!("{failure}; {}", run.tail(3)));
    }
    let text = format!("{}\n{}", run.stdout, run.stderr);
    let version = match tool {
        Tool::Lammps => lammps_version(&text)?,
        Tool::Liggghts => liggghts_version(&text)?,
        Tool::FreeFem => text
            .lines()
            .find_map(|l| l.trim().strip_prefix("ffversion "))
            .map(str::to_owned),
        Tool::Yade => text
            .lines()
            .find_map(|l| l.trim().strip_prefix("Yade version:"))
            .map(|v| v.trim().to_owned()),
        Tool::Ccx => text
            .lines()
            .find_map(|l| l.trim().strip_prefix("This is Version"))
            .map(|v| v.trim().to_owned()),
        Tool::KratosDem | Tool::KratosContact => text
            .lines()
            .find_map(|l| l.trim().strip_prefix("kratosversion "))
            .map(|v| v.trim().to_owned()),
        _ => text
            .lines()
            .map(str::trim)
            .find(|l| !l.is_empty())
            .map(str::to_owned),
    };
    version.ok_or_else(|| format!("no version in its output: {}", run.tail(3)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_tool_is_reported_with_its_install_command() {
        let chain = Toolchain {
            gmsh: "/nonexistent/gmsh".into(),
            ..Toolchain::default()
        };
        let probe = chain.probe(Tool::Gmsh);
        assert!(!probe.available());
        assert!(probe.line().contains("NOT FOUND"));
        assert!(probe.line().contains("apt-get install gmsh"));
        let message = chain.require(Tool::Gmsh).unwrap_err();
        assert!(
            message.contains("not installed") && message.contains("scripts/setup.sh"),
            "{message}"
        );
    }

    #[test]
    fn liggghts_help_gives_its_version_and_needs_its_models() {
        let help = "LIGGGHTS (Version LIGGGHTS-PUBLIC 3.8.0, compiled 2022-01-26 by buildd)\n\
                    * Normal models for pair gran:\nhertz   hooke\n* Tangential models for pair gran:\nhistory   no_history\n";
        assert_eq!(
            liggghts_version(help),
            Ok(Some("LIGGGHTS-PUBLIC 3.8.0".to_owned()))
        );
        assert!(liggghts_version("LIGGGHTS (Version X)\nhooke\n").is_err());
    }

    #[test]
    fn which_finds_a_shell() {
        assert!(which(Path::new("sh")).is_some());
        assert!(which(Path::new("spherecontact-no-such-tool")).is_none());
    }
}
