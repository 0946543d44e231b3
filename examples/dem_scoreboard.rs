//! The DEM scoreboard: every DEM tangential law, built into the crate or a real DEM code
//! (LAMMPS, YADE: `scripts/setup.sh`), against exact Mindlin–Deresiewicz (MDR) along the paper's
//! path and along `cattaneo`; printed as the reports show it ("How far is your DEM code from
//! Mindlin–Deresiewicz?").
//!
//! Run with `cargo run --release --example dem_scoreboard`.

use std::path::Path;

use spherecontact::case::Case;
use spherecontact::check::Reference;
use spherecontact::report::dem_scoreboard;
use spherecontact::verify;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let laws: Vec<String> = [
        "hertz-mindlin-spring",
        "thornton",
        "md-incremental",
        "walton-braun",
    ]
    .into_iter()
    .map(String::from)
    .chain(spherecontact::dem::solvers().iter().map(|s| s.name().to_owned()))
    .collect();
    for file in ["cases/paper-fig7.toml", "cases/cattaneo.toml"] {
        let mut case = Case::load(&root.join(file))?;
        // Only MDR and the laws: the scoreboard needs nothing else.
        let wanted = |name: &str| name == "mdr" || laws.iter().any(|l| l == name);
        case.solvers.retain(|s| wanted(s));
        case.checks
            .retain(|c| wanted(&c.solver) && matches!(&c.reference, Reference::Solver(r) if wanted(r)));
        let run = verify::run_case(case);
        println!("{}", dem_scoreboard::text(&run));
        print!("{}", spherecontact::verify::table::case_block(&run));
        println!();
    }
    Ok(())
}
