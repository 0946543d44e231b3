//! ccx-3d's maps on the paper path (`cases-heavy/ccx-3d-maps.toml`, docs/external-decks.md,
//! "ccx-3d's maps at c_max/5"): the case compares ccx-3d and fem-3d on one mesh, with the q_y
//! ratio and the stick semi-axes at the paper's position 5 and P and Q at every position, each
//! check reasoned and any known-failure mark carrying its evidence; and (heavy) the case verified
//! with ccx.
//!
//! Run: `cargo test --test suite calculix_3d_maps::` (the heavy run: `-- --ignored`).

use std::path::Path;

use spherecontact::case::Case;
use spherecontact::check::{Reference, Where};
use spherecontact::history::Quantity;

use crate::common::decks::ccx_present;

const CASE: &str = "cases-heavy/ccx-3d-maps.toml";

fn case() -> Case {
    Case::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join(CASE)).unwrap()
}

#[test]
fn the_maps_case_compares_ccx_3d_with_fem_3d_on_one_mesh_at_the_papers_position_5() {
    let case = case();
    assert!(case.labels.iter().any(|l| l == "heavy"), "{:?}", case.labels);
    assert_eq!(case.focus, 5);
    assert_eq!(
        case.resolution.get("ccx-3d"),
        case.resolution.get("fem-3d"),
        "the same mesh"
    );
    let against = |quantity: Quantity, solver: &str| {
        case.checks
            .iter()
            .filter(|c| c.solver == "ccx-3d" && c.quantity == quantity)
            .filter(|c| matches!(&c.reference, Reference::Solver(s) if s == solver))
            .collect::<Vec<_>>()
    };
    for quantity in [
        Quantity::TransverseRatio,
        Quantity::StickSemiAxisX,
        Quantity::StickSemiAxisY,
    ] {
        let checks = against(quantity, "fem-3d");
        assert!(
            checks
                .iter()
                .any(|c| c.at == Where::Position(5) && c.tolerance.is_some()),
            "{quantity:?} at position 5 against fem-3d"
        );
    }
    for quantity in [Quantity::NormalForce, Quantity::TangentialForce] {
        for reference in ["fem-3d", "mdr-domain"] {
            assert!(
                !against(quantity, reference).is_empty(),
                "{quantity:?} against {reference}"
            );
        }
    }
    for check in &case.checks {
        assert!(
            check.reason.contains("measured"),
            "{:?}: {}",
            check.quantity,
            check.reason
        );
        if let Some(evidence) = &check.known_failure {
            // The evidence the issue asks for: the same mesh, the formulation changed, the
            // in-crate solver right.
            let other = ["node-to-face", "mortar"].iter().any(|f| evidence.contains(f));
            assert!(other && evidence.contains("fem-3d"), "{evidence}");
        }
    }
}

#[test]
#[ignore] // heavy: ccx on 61 k equations, six steps, about 10–20 minutes on one thread; `-- --ignored`
fn the_maps_case_verifies_p_q_and_the_stick_zone_with_ccx() {
    if !ccx_present("the_maps_case_verifies_p_q_and_the_stick_zone_with_ccx") {
        return;
    }
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .args(["verify", CASE])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("OMP_NUM_THREADS", "1")
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    // Everything passes but the known failure (Q at position 3: KNOWN); the maps are read from
    // the contact's recovered nodal forces (docs/external-decks.md, "ccx-3d's maps at c_max/5"),
    // and every value is at its baseline (no DRIFT).
    let judged: Vec<&str> = stdout.lines().filter(|l| l.contains("| ccx-3d ")).collect();
    assert_eq!(judged.len(), 9, "{stdout}");
    assert!(output.status.success(), "{stdout}");
    for line in judged {
        let expected = if line.contains("tangential_force at position 3 ") {
            "KNOWN"
        } else {
            "OK"
        };
        assert!(line.starts_with(expected), "{expected}: {line}");
    }
}
