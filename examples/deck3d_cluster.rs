//! The `fenicsx-3d` deck run elsewhere (a cluster: docs/external-decks.md, "On a cluster"):
//!
//! - `write CASE DIR [POLE]` meshes the case's body and writes everything the deck needs into the
//!   folder DIR (created if missing), without running it: `body.geo`, `body.msh`, `deck3d.py`,
//!   `path.txt` — then `mpirun -np N python3 deck3d.py` in DIR, wherever dolfinx runs;
//! - `read CASE DIR OUT [POLE]` reads the finished run directory back (`steps.csv`,
//!   `surface.csv`, `triangles.csv`, `timing.csv`, checked against `path.txt` and each other) into
//!   the files `spherecontact run` writes: `OUT/fenicsx-3d.csv` (the History CSV), `.json` and
//!   `.fields.csv`; a case names the CSV as stored results (`[[stored_results]]`) to check and
//!   report it beside the other solvers.
//!
//! POLE is the pole element size (`c/8`, `25um`, …; default the deck's c_max/5), the same for
//! both commands.
//!
//! Run: `cargo run --release --example deck3d_cluster -- write CASE DIR [POLE]` (needs gmsh), and
//! `cargo run --release --example deck3d_cluster -- read CASE DIR OUT [POLE]`.

use std::path::Path;
use std::process::ExitCode;

use spherecontact::case::Case;
use spherecontact::external::fenicsx3d::{Solid3dDeck, NAME};
use spherecontact::io::OutputFolder;
use spherecontact::limits::SOLID_POLE;
use spherecontact::report::history_files;
use spherecontact::resolution;

const USAGE: &str = "usage: deck3d_cluster write CASE DIR [POLE] | read CASE DIR OUT [POLE]";

/// The deck for `case` at pole size `pole` (or its default).
fn deck_for(case: &str, pole: Option<&String>) -> Result<(Solid3dDeck, spherecontact::scene::Scene), String> {
    let scene = Case::load(Path::new(case)).map_err(|e| e.to_string())?.scene;
    let mut deck = Solid3dDeck::new(1);
    if let Some(value) = pole {
        let h = resolution::pole_size(NAME, &scene, value, SOLID_POLE).map_err(|e| e.to_string())?;
        deck.options.resolution = Some(h);
    }
    Ok((deck, scene))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let outcome = match args.as_slice() {
        [command, case, dir, rest @ ..] if command == "write" && rest.len() <= 1 => {
            deck_for(case, rest.first()).and_then(|(deck, scene)| {
                std::fs::create_dir_all(dir).map_err(|e| format!("{dir}: {e}"))?;
                deck.write_run(&scene, Path::new(dir))
                    .map_err(|e| e.to_string())?;
                Ok(format!(
                    "deck, mesh and path written to {dir}: run `mpirun -np N python3 deck3d.py` there"
                ))
            })
        }
        [command, case, dir, out, rest @ ..] if command == "read" && rest.len() <= 1 => {
            deck_for(case, rest.first()).and_then(|(deck, scene)| {
                let history = deck.read_run(&scene, Path::new(dir)).map_err(|e| e.to_string())?;
                OutputFolder::claim(Path::new(out), false)
                    .map_err(anyhow::Error::from)
                    .and_then(|folder| history_files::write(folder.path(), &history))
                    .map_err(|e| format!("{out}: {e}"))?;
                Ok(format!(
                    "{} steps read back from {dir} into {out}/{NAME}.csv",
                    history.steps.len()
                ))
            })
        }
        _ => {
            eprintln!("{USAGE}");
            return ExitCode::from(2);
        }
    };
    match outcome {
        Ok(message) => {
            println!("{message}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(1)
        }
    }
}
