//! Formulations as a case axis (`[calculix]`: contact formulation, penalty factor, 3D element):
//! a bad value stops the case with exit code 2 naming the file, the field and the allowed set;
//! the case's settings reach the solver through its resolution and are recorded in the
//! metadata; the mortars, which CalculiX 2.20 refuses on the axisymmetric model, are N/A with
//! the reason. The sweep itself is `examples/ccx_formulations.rs` on
//! `cases-heavy/ccx-formulations.toml` (docs/external-decks.md, "CalculiX: formulations").
//! Tests that need gmsh and ccx skip, saying why, where those are absent.
//! Run: `cargo test --test suite calculix_formulations::`.

use std::path::Path;

use spherecontact::calculix_settings::{Element, Formulation, MeshKind, Settings};
use spherecontact::case::Case;
use spherecontact::solver::{self, SolveError};

use crate::common::decks::{ccx_present, force_error_against_mdr_domain, scene_17um};
use crate::common::refused::{assert_refused, Left};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn a_bad_setting_exits_2_naming_the_file_the_field_and_the_allowed_set() {
    for (file, field, allowed) in [
        (
            "bad-element.toml",
            "calculix.element",
            "allowed: tet10, hex20, hex20r",
        ),
        (
            "bad-contact.toml",
            "calculix.contact",
            "allowed: face-to-face, node-to-face, mortar, linmortar, pglinmortar",
        ),
    ] {
        let path = root().join("tests/hostile/calculix").join(file);
        assert_refused(&["run"], &path, &[file, ":15:", field, allowed], Left::Nothing);
    }
}

#[test]
fn the_element_axis_names_the_keyword_and_mesh_of_the_3d_decks() {
    let case = Case::parse(
        Path::new("c.toml"),
        "friction = 0.2\nsolvers = [\"hertz\"]\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
         [path]\nunit = \"um\"\ndelta_n = [0, 10]\ndelta_t = [0, 0]\nsubsteps = 1\n\
         [calculix]\ncontact = \"mortar\"\npenalty = 1e4\nelement = \"hex20r\"\n",
    )
    .unwrap();
    assert_eq!(case.calculix.formulation, Formulation::Mortar);
    assert_eq!(case.calculix.element.spec(), ("C3D20R", MeshKind::Hex20));
    let recorded = case.calculix.describe();
    assert_eq!(recorded["contact_keyword"], "MORTAR");
    assert_eq!(recorded["penalty_factor"], 1e4);
    assert_eq!(recorded["element_keyword"], "C3D20R");
    assert_eq!(Settings::default().element, Element::Tet10);
}

#[test]
fn a_mortar_on_the_axisymmetric_deck_is_not_applicable_with_calculixs_reason() {
    // Through the case's resolved solver (the sweep's path): the resolution is kept and the
    // setting reaches the deck. CalculiX's refusal was measured with ccx 2.20 (the message
    // quotes it); the deck says so before running it.
    let case = Case::load(&root().join("cases/ccx-axisym.toml")).unwrap();
    let resolved = case.solver("ccx-axisym").unwrap();
    for formulation in [
        Formulation::Mortar,
        Formulation::LinMortar,
        Formulation::PgLinMortar,
    ] {
        let settings = Settings {
            formulation,
            ..case.calculix
        };
        let solver = resolved
            .with_calculix(&settings)
            .expect("the resolved solver takes settings");
        let error = solver::run(solver.as_ref(), &case.scene).unwrap_err();
        assert!(matches!(error, SolveError::NotApplicable(_)), "{error}");
        let message = error.to_string();
        assert!(
            message.contains(formulation.name()) && message.contains("catsmpcslavno"),
            "{message}"
        );
    }
}

#[test]
#[ignore = "heavy: ccx-axisym under node-to-face contact; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn node_to_face_is_run_and_recorded() {
    if !ccx_present("node_to_face_is_run_and_recorded") {
        return;
    }
    let scene = scene_17um();
    let settings = Settings {
        formulation: Formulation::NodeToFace,
        penalty: 1e4,
        ..Settings::default()
    };
    let solver = spherecontact::registry::by_name("ccx-axisym")
        .unwrap()
        .with_calculix(&settings)
        .unwrap()
        .at_resolution(&scene, "c/10")
        .unwrap();
    let history = solver::run(solver.as_ref(), &scene).unwrap();
    let extra = &history.metadata.extra;
    assert_eq!(extra["calculix"]["contact"], "node-to-face");
    assert_eq!(extra["calculix"]["contact_keyword"], "NODE TO SURFACE");
    assert_eq!(extra["calculix"]["penalty_factor"], 1e4);
    assert_eq!(extra["element_axisymmetric"], "CAX6");
    assert!(
        history.metadata.model.contains("node-to-face"),
        "{}",
        history.metadata.model
    );
    let error = force_error_against_mdr_domain("ccx-axisym node-to-face c/10", &history, &scene);
    // As the face-to-face run of tests/suite/external_calculix.rs: the coarse mesh (c_max/10) and
    // the penalty leave a few 1e-3; a wrong segment factor or a contact that does nothing would
    // be off by orders of magnitude.
    assert!(error.abs() < 5e-3, "P error {error:+.3e}");
}
