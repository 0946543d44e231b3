//! Deck folders are foreign input (issue 42): what `deck read` reads from a folder that came back
//! from a cluster or a colleague goes through the one reader of files from elsewhere
//! (`input::foreign`): a regular file, a symbolic link followed only inside its own folder, a size
//! limit per file (`crates/model/src/limits.rs`), and messages that name the file, the line and the column and
//! never quote the file. One test per finding, each failing before its fix; the rules:
//! docs/security.md, "Files from elsewhere", "Deck folders".
//!
//! No solver runs: each folder is written by `deck write` (gmsh only), its result files written
//! by hand from its `path.txt`. A refused result file is the run's failure (exit 1, as a truncated
//! or garbage file is, docs/external-decks.md "On a cluster"); a refused manifest is bad input
//! (exit 2). Every command runs under a guard that kills it after two minutes (a FIFO read would
//! otherwise block the test for ever); nothing about speed is asserted.
//!
//! Run: `cargo test --release --test suite hostile_decks::`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use spherecontact::toolchain::Tool;

use crate::common::decks::these_tools_present as present;
use crate::common::peak::output_and_peak;
use crate::common::reads::{raw_controls, spherecontact_guarded, symlink, text, SECRET};
use crate::common::SMALL_CASE;

/// A deck folder `deck/` that `deck write` wrote into a temporary folder holding the case
/// (`case.toml`) and, beside the folder, a secret (`secret.txt`) and a FIFO (`outside.fifo`).
struct Folder {
    dir: tempfile::TempDir,
    /// The case file, the solver and its resolution, as `deck write` and `deck read` take them.
    args: Vec<String>,
}

impl Folder {
    /// `solver`'s folder for `case` at `resolution`, or `None` (the test skips, saying why) when
    /// one of `tools` is missing.
    fn written(solver: &str, resolution: &str, case: &str, tools: &[Tool]) -> Option<Self> {
        if !present(solver, tools) {
            return None;
        }
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("case.toml"), case).unwrap();
        std::fs::write(
            dir.path().join("secret.txt"),
            format!("AWS_SECRET_ACCESS_KEY={SECRET}\n"),
        )
        .unwrap();
        make_fifo(&dir.path().join("outside.fifo"));
        let args = ["case.toml", "--solver", solver, "--resolution"]
            .map(String::from)
            .into_iter()
            .chain([format!("{solver}={resolution}")])
            .collect();
        let folder = Self { dir, args };
        let written = folder.run(&["deck", "write"], &["deck"]);
        assert!(written.status.success(), "{}", text(&written));
        Some(folder)
    }

    /// The fenicsx-3d folder of [`SMALL_CASE`] at its coarsest pole size, with its result files
    /// ([`Folder::fake_3d_outputs`]).
    fn fenicsx_3d() -> Option<Self> {
        let folder = Self::written("fenicsx-3d", "c/2", SMALL_CASE, &[Tool::Gmsh])?;
        folder.fake_3d_outputs();
        Some(folder)
    }

    /// The ccx-axisym folder of the normal half of [`SMALL_CASE`] (ccx-axisym solves normal
    /// contact), with a `deck.stdout` that reports no error.
    fn ccx_axisym() -> Option<Self> {
        let frictional = "delta_n = [0, 10, 10]\ndelta_t = [0, 0, 1]";
        assert!(SMALL_CASE.contains(frictional));
        let case = SMALL_CASE.replace(frictional, "delta_n = [0, 10]\ndelta_t = [0, 0]");
        let folder = Self::written("ccx-axisym", "c/10", &case, &[Tool::Gmsh])?;
        folder.write("deck.stdout", "CalculiX Version 2.20\nJob finished\n");
        Some(folder)
    }

    /// The freefem-axisym folder of [`SMALL_CASE`] at c/10, with its `steps.csv` (the field file
    /// of position P named `field_P.vtu`) and `surface.csv`; reading it needs meshio.
    fn freefem_axisym() -> Option<Self> {
        let tools = [Tool::Gmsh, Tool::Meshio];
        let folder = Self::written("freefem-axisym", "c/10", SMALL_CASE, &tools)?;
        folder.fake_axisym_outputs();
        Some(folder)
    }

    /// The deck folder.
    fn deck(&self) -> PathBuf {
        self.dir.path().join("deck")
    }

    /// The command line `action`, the case, solver and resolution, then `tail`, in the temporary
    /// folder (guarded against hangs).
    fn run(&self, action: &[&str], tail: &[&str]) -> Output {
        let args: Vec<&str> = action
            .iter()
            .copied()
            .chain(self.args.iter().map(String::as_str))
            .chain(tail.iter().copied())
            .collect();
        spherecontact_guarded(&args, self.dir.path())
    }

    /// `deck read` of the folder into `out/`.
    fn read(&self) -> Output {
        self.run(&["deck", "read"], &["deck", "--out", "out"])
    }

    /// Writes `text` as the folder's file `name` (replacing a link or FIFO there).
    fn write(&self, name: &str, text: &str) {
        let _ = std::fs::remove_file(self.deck().join(name));
        std::fs::write(self.deck().join(name), text).unwrap();
    }

    /// The text of the folder's file `name`.
    fn text(&self, name: &str) -> String {
        std::fs::read_to_string(self.deck().join(name)).unwrap()
    }

    /// Makes the folder's file `name` a symbolic link to `target`.
    fn link(&self, name: &str, target: &Path) {
        let _ = std::fs::remove_file(self.deck().join(name));
        symlink(target, &self.deck().join(name));
    }

    /// Makes the folder's file `name` a FIFO.
    fn fifo(&self, name: &str) {
        let _ = std::fs::remove_file(self.deck().join(name));
        make_fifo(&self.deck().join(name));
    }

    /// The computed steps of `path.txt`: step index, d and t [mm] as written, position or −1.
    fn steps(&self) -> Vec<[String; 4]> {
        self.text("path.txt")
            .lines()
            .skip(1)
            .map(|l| {
                let cells: Vec<String> = l.split(' ').map(String::from).collect();
                [0, 1, 2, 3].map(|i| cells[i].clone())
            })
            .collect()
    }

    /// `steps.csv` for the folder's steps: no force, converged, the field files `name(P)` at
    /// the positions P.
    fn steps_csv(&self, field: impl Fn(&str) -> String) -> String {
        let mut text = String::from(
            "step,d_mm,t_mm,P_contact_N,P_top_N,Q_N,iterations_normal,iterations_tangential,outcome,field_file\n",
        );
        for [step, d, t, position] in self.steps() {
            let file = if position == "-1" {
                "-".to_owned()
            } else {
                field(&position)
            };
            text.push_str(&format!("{step},{d},{t},0,,0,1,1,1,{file}\n"));
        }
        text
    }

    /// `surface.csv` for the folder's steps: one unloaded node per step, `zeros` zero cells after
    /// the step.
    fn surface_csv(&self, header: &str, zeros: usize) -> String {
        let mut text = format!("{header}\n");
        for [step, ..] in self.steps() {
            text.push_str(&format!("{step}{}\n", ",0".repeat(zeros)));
        }
        text
    }

    /// The 3D deck's result files for the folder's steps: unloaded (P = 0 = 2 Σ ω p), which
    /// `deck read` accepts.
    fn fake_3d_outputs(&self) {
        self.write("steps.csv", &self.steps_csv(|_| "-".into()));
        let header = "step,x_mm,y_mm,weight_mm2,gap_mm,p_MPa,qx_MPa,qy_MPa,stick,slip_x_mm,slip_y_mm";
        self.write("surface.csv", &self.surface_csv(header, 10));
        self.write("triangles.csv", "a,b,c\n0,0,0\n");
        self.write("timing.csv", "phase,seconds\nsetup,1\npath,1\n");
    }

    /// The axisymmetric deck's `steps.csv` and `surface.csv` for the folder's steps (no field
    /// file yet).
    fn fake_axisym_outputs(&self) {
        self.write("steps.csv", &self.steps_csv(|p| format!("field_{p}.vtu")));
        let header = "step,r_mm,weight_mm2,gap_mm,p_MPa,qx_MPa,stick,slip_mm";
        self.write("surface.csv", &self.surface_csv(header, 7));
    }

    /// The secret beside the folder.
    fn secret(&self) -> PathBuf {
        self.dir.path().join("secret.txt")
    }

    /// The FIFO beside the folder.
    fn outside_fifo(&self) -> PathBuf {
        self.dir.path().join("outside.fifo")
    }
}

/// A FIFO at `path`.
fn make_fifo(path: &Path) {
    let made = Command::new("mkfifo").arg(path).status().unwrap();
    assert!(made.success());
}

/// A refusal: exit `code`, every fragment in the message, no secret, no raw control character,
/// and nothing written into `out/`.
fn assert_refused(folder: &Folder, output: &Output, code: i32, fragments: &[&str]) {
    let all = text(output);
    assert_eq!(output.status.code(), Some(code), "{all}");
    for fragment in fragments {
        assert!(all.contains(fragment), "`{fragment}` not in: {all}");
    }
    assert!(!all.contains(SECRET), "a secret leaked: {all}");
    assert!(!all.contains("panicked"), "{all}");
    assert!(raw_controls(&all).is_empty(), "raw control characters: {all:?}");
    assert!(!folder.dir.path().join("out").exists(), "{all}");
}

/// The control: a folder whose result files are well formed is read back, also where one of
/// them is a symbolic link to a file inside the folder (a link is followed inside its folder).
/// The deck's clock is reported, never judged: a rank count out of range in `timing.csv` is
/// passed over (the deck's own count is recorded), not copied into the metadata.
#[test]
fn a_well_formed_folder_is_read_back_and_a_link_inside_it_is_followed() {
    let Some(folder) = Folder::fenicsx_3d() else {
        return;
    };
    std::fs::rename(folder.deck().join("steps.csv"), folder.deck().join("steps-1.csv")).unwrap();
    folder.link("steps.csv", Path::new("steps-1.csv"));
    folder.write("timing.csv", "phase,seconds\nsetup,1\npath,1\nranks,1e30\n");
    let output = folder.read();
    assert!(output.status.success(), "{}", text(&output));
    let json = std::fs::read_to_string(folder.dir.path().join("out/fenicsx-3d.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(json["metadata"]["extra"]["ranks"], 1, "{json}");
}

/// Finding: `steps.csv` or `surface.csv` linked to any file had its first line echoed in the
/// header error. Every result file linked out of its folder (to a secret, to `/dev/zero`) is
/// refused before it is opened, naming the file; the secret is in no output.
#[test]
fn result_files_linked_out_of_the_folder_are_refused_without_echo() {
    let Some(folder) = Folder::fenicsx_3d() else {
        return;
    };
    for name in [
        "steps.csv",
        "surface.csv",
        "triangles.csv",
        "timing.csv",
        "path.txt",
    ] {
        let good = folder.text(name);
        for target in [folder.secret(), PathBuf::from("/dev/zero")] {
            folder.link(name, &target);
            let output = folder.read();
            assert_refused(&folder, &output, 1, &[name, "leads out of its folder"]);
        }
        folder.write(name, &good);
    }
}

/// Finding: a FIFO as `steps.csv`, `timing.csv` or ccx's `deck.stdout` blocked `deck read` for
/// ever. Each (and every other result file) fails at once, saying it is a FIFO.
#[test]
#[ignore = "heavy: a 3D FEniCSx and a ccx-axisym deck folder written (gmsh), 5 s (two test threads); .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn a_fifo_as_a_result_file_fails_at_once_naming_it() {
    let Some(folder) = Folder::fenicsx_3d() else {
        return;
    };
    for name in ["steps.csv", "surface.csv", "triangles.csv", "timing.csv"] {
        let good = folder.text(name);
        folder.fifo(name);
        let output = folder.read();
        assert_refused(&folder, &output, 1, &[name, "a FIFO"]);
        folder.write(name, &good);
    }
    let Some(ccx) = Folder::ccx_axisym() else {
        return;
    };
    ccx.fifo("deck.stdout");
    assert_refused(&ccx, &ccx.read(), 1, &["deck.stdout", "a FIFO"]);
}

/// Finding: a 3 GiB `steps.csv` aborted `deck read` (exit 134). A sparse one is refused by its
/// size before a byte is read: the process stays far below the file's size.
#[test]
fn a_sparse_3_gib_steps_csv_is_refused_by_its_size_without_reading_it() {
    let Some(folder) = Folder::fenicsx_3d() else {
        return;
    };
    let file = std::fs::File::create(folder.deck().join("steps.csv")).unwrap();
    file.set_len(3 << 30).unwrap();
    let mut command = Command::new(env!("CARGO_BIN_EXE_spherecontact"));
    command.current_dir(folder.dir.path()).args(["deck", "read"]);
    command.args(&folder.args).args(["deck", "--out", "out"]);
    let (output, peak) = output_and_peak(&command);
    assert_refused(&folder, &output, 1, &["steps.csv", "at most 256 MiB"]);
    assert!(peak < 256 << 20, "peak {peak} bytes: the file was read");
}

/// Finding: a bad header was quoted whole. A header with a secret-looking column name is named
/// by the column's position, with the header expected, never its text.
#[test]
fn a_bad_header_is_named_by_the_column_position_and_the_expected_header() {
    let Some(folder) = Folder::fenicsx_3d() else {
        return;
    };
    let good = folder.text("steps.csv");
    let bad = good.replacen(",t_mm,", &format!(",ghp_{SECRET},"), 1);
    folder.write("steps.csv", &bad);
    let expected =
        "step,d_mm,t_mm,P_contact_N,P_top_N,Q_N,iterations_normal,iterations_tangential,outcome,field_file";
    let output = folder.read();
    assert_refused(&folder, &output, 1, &["steps.csv:1: header: column 3", expected]);
    folder.write("steps.csv", &good);
    let surface = folder.text("surface.csv");
    folder.write(
        "surface.csv",
        &surface.replacen("step,", &format!("{SECRET},"), 1),
    );
    let output = folder.read();
    assert_refused(&folder, &output, 1, &["surface.csv:1: header: column 1"]);
}

/// Finding: cell values were quoted (`outcome = `…` is not 0, 1 or 2`, "`…` is not a finite
/// number"). A bad cell of any result file is named by its file, line and column, with the form
/// allowed, never its value.
#[test]
fn a_bad_cell_is_named_by_file_line_and_column_never_by_its_value() {
    let Some(folder) = Folder::fenicsx_3d() else {
        return;
    };
    // (file, line, cell index, column name): line 3 is the row of the second step.
    let cells = [
        ("steps.csv", 3, 0, "step"),
        ("steps.csv", 3, 1, "d_mm"),
        ("steps.csv", 3, 3, "P_contact_N"),
        ("steps.csv", 3, 6, "iterations_normal"),
        ("steps.csv", 3, 8, "outcome"),
        ("steps.csv", 3, 9, "field_file"),
        ("surface.csv", 3, 0, "step"),
        ("surface.csv", 3, 5, "p_MPa"),
        ("surface.csv", 3, 8, "stick"),
        ("triangles.csv", 2, 2, "c"),
    ];
    for (name, line, index, column) in cells {
        let good = folder.text(name);
        let mut lines: Vec<String> = good.lines().map(String::from).collect();
        let mut row: Vec<String> = lines[line - 1].split(',').map(String::from).collect();
        row[index] = format!("{SECRET}/x");
        lines[line - 1] = row.join(",");
        folder.write(name, &(lines.join("\n") + "\n"));
        let location = format!("{name}:{line}: column `{column}`");
        let output = folder.read();
        assert_refused(&folder, &output, 1, &[&location, "allowed"]);
        folder.write(name, &good);
    }
}

/// Finding: a `field_file` in steps.csv that is a link out of the folder was handed to meshio.
/// A field file linked out, or an XDMF whose HDF5 data lies outside the folder (by its name, or
/// through a link), is refused before meshio opens it: the targets are FIFOs, which meshio would
/// block on.
#[test]
#[ignore = "heavy: a freefem-axisym deck folder written (gmsh), its field files read by meshio under python3, 11 s (two test threads); .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn a_field_file_leading_out_of_the_folder_is_refused_before_meshio_opens_it() {
    let Some(folder) = Folder::freefem_axisym() else {
        return;
    };
    for position in ["0", "2"] {
        folder.write(&format!("field_{position}.vtu"), "<VTKFile/>\n");
    }
    folder.link("field_1.vtu", &folder.outside_fifo());
    let output = folder.read();
    assert_refused(&folder, &output, 1, &["field_1.vtu", "leads out of its folder"]);
    folder.write("steps.csv", &folder.steps_csv(|p| format!("field_{p}.xdmf")));
    let outside = folder.outside_fifo().display().to_string();
    for (reference, fragment) in [
        (format!("{outside}:/u"), "field_0.xdmf:"),
        ("../outside.fifo:/u".to_owned(), "field_0.xdmf:"),
        ("linked.h5:/u".to_owned(), "linked.h5"),
    ] {
        let xdmf = format!(
            "<?xml version=\"1.0\"?>\n<Xdmf Version=\"3.0\"><Domain><Grid Name=\"mesh\">\n\
             <Geometry GeometryType=\"XY\"><DataItem Dimensions=\"1 2\" Format=\"HDF\">{reference}</DataItem></Geometry>\n\
             </Grid></Domain></Xdmf>\n"
        );
        for position in ["0", "1", "2"] {
            folder.write(&format!("field_{position}.xdmf"), &xdmf);
        }
        folder.link("linked.h5", &folder.outside_fifo());
        let output = folder.read();
        assert_refused(&folder, &output, 1, &[fragment, "DataItem"]);
    }
}

/// Finding: meshio's output went into the message, and meshio quotes what it cannot read
/// ("Unknown XDMF version …", "Expected type UnstructuredGrid, found …"). A field file meshio
/// refuses is named, with what was expected, and nothing meshio said about its content.
#[test]
#[ignore = "heavy: a freefem-axisym deck folder written (gmsh), a field file read by meshio under python3, 8 s (two test threads); .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn meshio_s_words_about_a_field_file_are_not_shown() {
    let Some(folder) = Folder::freefem_axisym() else {
        return;
    };
    let vtu = format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"{SECRET}\" version=\"0.1\" byte_order=\"LittleEndian\"></VTKFile>\n"
    );
    let xdmf = format!("<?xml version=\"1.0\"?>\n<Xdmf Version=\"{SECRET}\"><Domain/></Xdmf>\n");
    for (extension, garbage) in [("vtu", vtu), ("xdmf", xdmf)] {
        folder.write(
            "steps.csv",
            &folder.steps_csv(|p| format!("field_{p}.{extension}")),
        );
        for position in ["0", "1", "2"] {
            folder.write(&format!("field_{position}.{extension}"), &garbage);
        }
        let output = folder.read();
        let file = format!("field_0.{extension}");
        assert_refused(&folder, &output, 1, &[&file, "meshio"]);
    }
}

/// Findings: the meshes of a folder were read with no limit (a FIFO blocked), and mshio's error
/// printed a hex dump of the file from the fault on. A mesh file that is a FIFO fails at once; a
/// garbage one is named with the line of the fault, no byte of it shown.
#[test]
#[ignore = "heavy: a ccx-axisym deck folder written (gmsh), 7 s (two test threads); .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn a_mesh_file_is_read_as_foreign_input() {
    let Some(folder) = Folder::ccx_axisym() else {
        return;
    };
    folder.fifo("mesh.msh");
    assert_refused(&folder, &folder.read(), 1, &["mesh.msh", "a FIFO"]);
    folder.write(
        "mesh.msh",
        &format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n{SECRET} {SECRET}\n$EndNodes\n"),
    );
    let output = folder.read();
    assert_refused(&folder, &output, 1, &["mesh.msh", "line 5"]);
    assert!(!text(&output).contains("Hex dump"), "{}", text(&output));
    let Some(freefem) = Folder::freefem_axisym() else {
        return;
    };
    freefem.fifo("mesh_p1_mm.msh");
    assert_refused(&freefem, &freefem.read(), 1, &["mesh_p1_mm.msh", "a FIFO"]);
}

/// Finding: ccx's `*ERROR` lines in `deck.stdout` were quoted in `deck read`'s message. The
/// error is reported by the file and its line, the lines themselves not shown.
#[test]
fn a_ccx_error_in_deck_stdout_is_named_by_its_line_not_quoted() {
    let Some(folder) = Folder::ccx_axisym() else {
        return;
    };
    folder.write(
        "deck.stdout",
        &format!("CalculiX Version 2.20\n\n *ERROR reading {SECRET}\n"),
    );
    let output = folder.read();
    assert_refused(&folder, &output, 1, &["deck.stdout:3", "*ERROR"]);
}

/// The manifest is read as foreign input too: linked out of its folder it is refused (exit 2,
/// bad input: the folder is not one `deck write` wrote), and a format it does not know is not
/// quoted.
#[test]
fn a_manifest_linked_out_or_of_another_format_is_refused_without_echo() {
    let Some(folder) = Folder::fenicsx_3d() else {
        return;
    };
    let manifest = folder.text("manifest.json");
    folder.link("manifest.json", &folder.secret());
    let output = folder.read();
    assert_refused(&folder, &output, 2, &["manifest.json", "leads out of its folder"]);
    let format = "\"format\": \"spherecontact deck folder 1\"";
    assert!(manifest.contains(format), "{manifest}");
    folder.write(
        "manifest.json",
        &manifest.replace(format, &format!("\"format\": \"{SECRET}\"")),
    );
    let output = folder.read();
    assert_refused(
        &folder,
        &output,
        2,
        &["manifest.json", "spherecontact deck folder 1"],
    );
}
