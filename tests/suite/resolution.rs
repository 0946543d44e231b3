//! The resolution a user chooses: a case's `[resolution]` table and `--resolution SOLVER=VALUE`,
//! judged by each solver (hostile values are bad input naming the file, the field and the
//! allowed range), carried into the history's metadata, the command line over the case file.
//!
//! Run: `cargo test --test suite resolution::`.

use std::path::Path;

use spherecontact::case::Case;
use spherecontact::solver;

use crate::common;

/// The small case with a `[resolution]` table of `entries` (TOML lines).
fn case_with(entries: &str) -> String {
    format!(
        "{}\n[resolution]\n{entries}\n",
        common::SMALL_CASE.replace("[\"hertz\", \"mdr\"]", "[\"hertz\", \"mdr\", \"bem\"]")
    )
}

#[test]
fn a_chosen_resolution_reaches_the_solver_and_its_metadata() {
    let case = Case::parse(Path::new("r.toml"), &case_with("bem = 16\nmdr = 500")).unwrap();
    let bem = solver::run(case.solver("bem").unwrap().as_ref(), &case.scene).unwrap();
    assert_eq!(bem.metadata.chosen_resolution.as_deref(), Some("16"));
    assert!(
        bem.metadata.resolution.starts_with("16×16 panels"),
        "{}",
        bem.metadata.resolution
    );
    assert!(bem.metadata.resolution_shown().ends_with("(chosen: 16)"));
    let mdr = solver::run(case.solver("mdr").unwrap().as_ref(), &case.scene).unwrap();
    assert!(
        mdr.metadata.resolution.starts_with("500 springs"),
        "{}",
        mdr.metadata.resolution
    );
    // A solver the table does not name runs at its default and says so.
    let hertz = solver::run(case.solver("hertz").unwrap().as_ref(), &case.scene).unwrap();
    assert_eq!(hertz.metadata.chosen_resolution, None);
}

#[test]
fn pole_sizes_are_read_as_fractions_of_the_contact_or_as_lengths() {
    let case = Case::parse(Path::new("r.toml"), &case_with("fem-axisym = \"c/8\"")).unwrap();
    let c = case.scene.max_contact_radius();
    let history = solver::run(case.solver("fem-axisym").unwrap().as_ref(), &case.scene).unwrap();
    let h: f64 = history.metadata.extra["pole_size_m"].as_f64().unwrap();
    assert!((h - c / 8.0).abs() < 1e-12 * c, "{h} against {}", c / 8.0);
    let mut case = case;
    case.set_resolution("fem-axisym", "20um").unwrap();
    assert_eq!(case.resolution["fem-axisym"], "20um");
}

#[test]
fn hostile_values_name_the_file_the_field_and_the_allowed_range() {
    let cases: &[(&str, &[&str])] = &[
        (
            "nosuch = 3",
            &["resolution.nosuch", "unknown solver", "allowed: hertz"],
        ),
        (
            "hertz = 3",
            &[
                "resolution.hertz",
                "no resolution",
                "allowed: a solver with a resolution",
                "bem",
            ],
        ),
        ("bem = 7", &["resolution.bem", "even number 4 ≤ n ≤ 512"]),
        ("bem = 1024", &["resolution.bem", "out of range", "512"]),
        ("bem = -2", &["resolution.bem", "out of range"]),
        ("bem = 99999999999999", &["resolution.bem", "out of range"]),
        ("bem = \"many\"", &["resolution.bem", "not a whole number"]),
        ("bem = 64.5", &["resolution.bem", "not a whole number"]),
        ("bem = true", &["resolution.bem", "not a resolution"]),
        ("bem = [64]", &["resolution.bem", "not a resolution"]),
        ("mdr = 0", &["resolution.mdr", "1 ≤ n ≤ 1000000"]),
        ("mdr = 2000000", &["resolution.mdr", "out of range"]),
        (
            "fem-axisym = \"c/1000\"",
            &[
                "resolution.fem-axisym",
                "finer than allowed",
                "c/N with 2 ≤ N ≤ 320",
            ],
        ),
        (
            "fem-axisym = \"c/1\"",
            &["resolution.fem-axisym", "coarser than allowed"],
        ),
        (
            "fem-axisym = \"c/0\"",
            &["resolution.fem-axisym", "not a positive number"],
        ),
        (
            "fem-axisym = \"c/nan\"",
            &["resolution.fem-axisym", "not a positive number"],
        ),
        ("fem-axisym = \"1nm\"", &["resolution.fem-axisym", "not a length"]),
        (
            "fem-axisym = \"inf\"",
            &["resolution.fem-axisym", "finite and positive"],
        ),
        (
            "fem-axisym = 1e-12",
            &["resolution.fem-axisym", "finer than allowed"],
        ),
        (
            "fem-3d = \"c/40\"",
            &["resolution.fem-3d", "finer than allowed", "2 ≤ N ≤ 14"],
        ),
        (
            "fenicsx-3d = \"c/40\"",
            &["resolution.fenicsx-3d", "finer than allowed"],
        ),
        (
            "freefem-axisym = \"c/1000\"",
            &["resolution.freefem-axisym", "finer than allowed"],
        ),
    ];
    let failures: Vec<String> = cases
        .iter()
        .filter_map(|(entry, fragments)| {
            let error = match Case::parse(Path::new("dir/r.toml"), &case_with(entry)) {
                Ok(_) => return Some(format!("{entry}: accepted")),
                Err(e) => e.to_string(),
            };
            std::iter::once(&"dir/r.toml")
                .chain(fragments.iter())
                .find(|f| !error.contains(*f))
                .map(|f| format!("{entry}: no `{f}` in: {error}"))
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The history JSON that `run` wrote for `solver` in `out`.
fn written_metadata(out: &Path, solver: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(out.join(format!("{solver}.json"))).unwrap();
    serde_json::from_str::<serde_json::Value>(&text).unwrap()["metadata"].clone()
}

#[test]
fn the_command_line_overrides_the_case_table_and_refuses_bad_values() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), case_with("bem = 32")).unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec!["run", "case.toml", "--solver", "bem", "--out", "out"];
        args.extend_from_slice(extra);
        common::spherecontact(&args, dir.path())
    };
    assert!(run(&[]).status.success());
    assert_eq!(
        written_metadata(&dir.path().join("out"), "bem")["chosen_resolution"],
        "32"
    );
    assert!(run(&["--resolution", "bem=16"]).status.success());
    let metadata = written_metadata(&dir.path().join("out"), "bem");
    assert_eq!(metadata["chosen_resolution"], "16");
    assert!(metadata["resolution"].as_str().unwrap().starts_with("16×16"));
    for (bad, fragment) in [
        ("bem=15", "even number 4 ≤ n ≤ 512"),
        ("bem", "not SOLVER=VALUE"),
        ("nosuch=3", "unknown solver"),
        ("bme=16", "unknown solver `bme`; did you mean `bem`?"),
        ("hertz=3", "no resolution"),
    ] {
        let output = run(&["--resolution", bad]);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{bad}: {stderr}");
        assert!(
            stderr.contains("--resolution") && stderr.contains(fragment),
            "{bad}: {stderr}"
        );
    }
    let twice = run(&["--resolution", "bem=16", "--resolution", "bem=32"]);
    assert_eq!(twice.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&twice.stderr).contains("given twice"));
}
