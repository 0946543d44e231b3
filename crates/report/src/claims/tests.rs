//! The claims table on small runs: what it says without the solvers a claim needs, how a new
//! finite element solver is judged as it lands, and the surface-field rows from a resolution study.

use std::path::Path;

use super::*;
use spherecontact_case::Case;
use spherecontact_model::solver::Solver;
use spherecontact_solvers::bem::Bem;

/// The paper's spheres and friction along the first five positions of its path (µm), with
/// `solvers`, 4 increments a segment.
fn run(solvers: &[&str]) -> CaseRun {
    run_with(solvers, 0.2)
}

/// The same with friction coefficient `friction`.
fn run_with(solvers: &[&str], friction: f64) -> CaseRun {
    let list: Vec<String> = solvers.iter().map(|s| format!("\"{s}\"")).collect();
    let text = format!(
        "friction = {friction}\nfocus = 5\nsolvers = [{}]\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
         [path]\nunit = \"um\"\ndelta_n = [0, 10, 14, 17, 17, 17]\ndelta_t = [0, 0, 1, 1, 2, 3]\nsubsteps = 4\n",
        list.join(", ")
    );
    let case = Case::parse(Path::new("claims.toml"), &text).unwrap_or_else(|e| panic!("{e}"));
    spherecontact_verify::run_case(case)
}

fn quoted() -> Quoted {
    Quoted::load(&spherecontact_model::fixtures::repository().join("reference"))
        .expect("reference/paper.toml")
}

fn row<'a>(claims: &'a [Claim], start: &str) -> &'a Claim {
    claims
        .iter()
        .find(|c| c.claim.starts_with(start))
        .unwrap_or_else(|| panic!("no claim `{start}`"))
}

#[test]
fn without_the_solvers_a_claim_needs_it_says_what_it_needs() {
    let run = run(&["hertz", "mdr"]);
    let claims = claims(&run, &Study::none(), &quoted());
    assert_eq!(claims.len(), 11);
    for c in claims.iter().filter(|c| c.verdict == Verdict::NotMeasured) {
        assert!(c.measured.starts_with("not measured: needs "), "{c:?}");
        assert!(!c.measured.contains("MPa"), "no value stands in: {c:?}");
    }
    let stick = row(&claims, "The contact status");
    assert_eq!(stick.verdict, Verdict::NotMeasured);
    assert!(stick.measured.contains("bem, fem-3d"), "{}", stick.measured);
    assert_eq!(
        row(&claims, "FEM normal force agrees with Hertz (Figure 8)").verdict,
        Verdict::NotMeasured
    );
    // The caps claim runs its own finite element model of the paper's 20 mm caps: P sits 3-4 %
    // above Hertz at 10-17 µm (the caps' compliance), which mdr-domain explains to < 0.1 %.
    let caps = row(&claims, "FEM normal force agrees with Hertz on");
    assert_eq!(caps.verdict, Verdict::NotConfirmed, "{caps:?}");
    assert!(caps.measured.contains("(+4.0"), "{}", caps.measured);
    assert!(caps.measured.contains("within 0.0"), "{}", caps.measured);
    // Measured from Hertz alone: the paper's 581 MPa is not Hertz's p0 at 17 µm.
    assert_eq!(row(&claims, "Hertz gives p0").verdict, Verdict::NotConfirmed);
}

#[test]
fn a_new_finite_element_solver_is_judged_as_it_lands() {
    let mut run = run(&["hertz", "mdr"]);
    let mdr = run.histories["mdr"].as_ref().unwrap().clone();
    // A finite element solver 0.4 % stiffer than Hertz and 2 % softer than MD in shear: inside
    // the agreement the rows state (1 % for P, 3 % of the peak for Q).
    let fake = |p_scale: f64, q_scale: f64| {
        let mut h = mdr.clone();
        for row in &mut h.steps {
            row.normal_force = row.normal_force.map(|p| p * p_scale);
            row.tangential_force = row.tangential_force.map(|q| q * q_scale);
        }
        h
    };
    run.histories.insert("fem-fake".into(), Ok(fake(1.004, 0.98)));
    run.case.solvers.push("fem-fake".into());
    let claims = claims(&run, &Study::none(), &quoted());
    let normal = row(&claims, "FEM normal force agrees with Hertz (Figure 8)");
    assert_eq!(normal.verdict, Verdict::Confirmed, "{normal:?}");
    assert!(
        normal.measured.contains("fem-fake +0.40 %"),
        "{}",
        normal.measured
    );
    let tangential = row(&claims, "FEM tangential force");
    assert_eq!(tangential.verdict, Verdict::Confirmed, "{tangential:?}");
    assert!(
        tangential.measured.contains("fem-fake 2.00 %"),
        "{}",
        tangential.measured
    );
    // Beyond the agreement: not confirmed, with the number.
    run.histories.insert("fem-fake".into(), Ok(fake(1.02, 0.9)));
    let claims = claims_of(&run);
    assert_eq!(
        row(&claims, "FEM normal force agrees with Hertz (Figure 8)").verdict,
        Verdict::NotConfirmed
    );
    let tangential = row(&claims, "FEM tangential force");
    assert_eq!(tangential.verdict, Verdict::NotConfirmed);
    assert!(
        tangential.reading.contains("up to 10.00 %"),
        "{}",
        tangential.reading
    );
}

fn claims_of(run: &CaseRun) -> Vec<Claim> {
    claims(run, &Study::none(), &quoted())
}

#[test]
fn surface_field_claims_are_measured_on_a_map_solver_with_its_resolution() {
    let run = run(&["hertz", "mdr", "bem"]);
    let ladder: Vec<Box<dyn Solver>> = vec![Box::new(Bem::with_grid(24)), Box::new(Bem::with_grid(32))];
    let study = Study::of(&run, vec![("bem".into(), ladder)], 4, 2);
    assert_eq!(study.solvers[0].rungs.len(), 2, "{:?}", study.solvers[0].problems);
    let claims = claims(&run, &study, &quoted());
    for start in [
        "The contact pressure is axisymmetric",
        "The contact status",
        "The frictional stress",
        "There is a mismatch",
        "The maximum frictional",
    ] {
        let c = row(&claims, start);
        assert_ne!(c.verdict, Verdict::NotMeasured, "{c:?}");
        assert!(c.measured.starts_with("bem: "), "{}", c.measured);
        assert!(
            c.measured.contains("at h = c/") && c.measured.contains("this run"),
            "{}",
            c.measured
        );
        assert!(
            c.measured.contains("needs fem-3d"),
            "the paper's own FE model is named as missing"
        );
    }
    // The section lists the study's rungs, their wall time marked as a timing (masked when
    // reports are compared).
    let section = section(&run, &study, &claims);
    assert_eq!(section.tables.len(), 2);
    assert_eq!(section.tables[1].rows.len(), 2);
    assert!(section.tables[1].rows.iter().all(|r| r[3].class == "timing"));
    // Even on these coarse grids the transverse traction has its pattern and the stick zone is
    // a disc within its change under refinement.
    assert!(row(&claims, "The frictional stress")
        .measured
        .contains("odd in x and in y"));
    assert_eq!(row(&claims, "The contact status").verdict, Verdict::Confirmed);
    // The BEM's grid reads p the same along x and along y (identical bodies: no coupling).
    assert_eq!(
        row(&claims, "The contact pressure is axisymmetric").verdict,
        Verdict::Confirmed
    );
}

#[test]
fn a_finite_element_map_solver_is_judged_and_the_bem_measured_beside_it() {
    let mut run = run(&["hertz", "mdr", "bem"]);
    // A finite element solver with the BEM's own fields: the claims are judged on it, the BEM
    // is measured beside it, and the two compare as equal.
    let bem = run.histories["bem"].as_ref().unwrap().clone();
    run.histories.insert("fem-fake".into(), Ok(bem));
    run.case.solvers.push("fem-fake".into());
    let ladder =
        || -> Vec<Box<dyn Solver>> { vec![Box::new(Bem::with_grid(24)), Box::new(Bem::with_grid(32))] };
    let study = Study::of(
        &run,
        vec![("bem".into(), ladder()), ("fem-fake".into(), ladder())],
        4,
        2,
    );
    let claims = claims(&run, &study, &quoted());
    for start in [
        "The contact pressure is axisymmetric",
        "The contact status",
        "The frictional stress",
    ] {
        let c = row(&claims, start);
        assert!(c.measured.starts_with("fem-fake: "), "{}", c.measured);
        assert!(c.measured.contains(". Beside it, bem: "), "{}", c.measured);
        assert!(!c.measured.contains("needs fem-3d"), "{}", c.measured);
    }
    let transverse = row(&claims, "The frictional stress");
    assert!(
        transverse.reading.contains("Against bem: the same sign pattern")
            && transverse.reading.contains("0.00 % of max|q_x| apart")
            && transverse
                .reading
                .contains("within what the two discretisations explain"),
        "{}",
        transverse.reading
    );
}

#[test]
fn finite_element_solvers_are_recognised_by_name() {
    for name in ["fem-axisym", "fem-3d", "freefem-axisym", "fenicsx-3d"] {
        assert!(is_finite_element(name), "{name}");
    }
    for name in ["bem", "mdr", "hertz", "thornton"] {
        assert!(!is_finite_element(name), "{name}");
    }
}

#[test]
fn without_friction_nothing_prints_as_nan_or_infinity() {
    let run = run_with(&["hertz", "mdr", "bem"], 0.0);
    let ladder: Vec<Box<dyn Solver>> = vec![Box::new(Bem::with_grid(16)), Box::new(Bem::with_grid(24))];
    let study = Study::of(&run, vec![("bem".into(), ladder)], 2, 2);
    for c in claims(&run, &study, &quoted()) {
        let text = format!("{} {} {}", c.measured, c.reading, c.evidence).to_lowercase();
        let words: Vec<&str> = text.split(|ch: char| !ch.is_alphanumeric()).collect();
        assert!(!words.contains(&"nan") && !words.contains(&"inf"), "{c:?}");
    }
}
