//! Verification at scale, end to end through the command line: labels select cases, concurrent
//! runs (`--jobs`) and sharded runs merged (`--shard`, `merge`) give what a serial run gives,
//! and a value that moves from its non-regression baseline is a DRIFT until `baseline update`.

use crate::common;

use std::path::Path;

use common::{arg as path, root, run_in_root as run, text};

/// The cases of a verification's printed blocks (`== name (file)`).
fn cases_run(stdout: &str) -> Vec<&str> {
    stdout
        .lines()
        .filter_map(|l| l.strip_prefix("== ")?.split(' ').next())
        .collect()
}

#[test]
fn labels_select_and_skip_cases() {
    let empty = tempfile::tempdir().unwrap();
    let none = path(empty.path());
    let (code, stdout, stderr) = run(&[
        "verify",
        "--label",
        "hard",
        "--skip-label",
        "dem",
        "--baselines",
        none,
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    // Of cases/hard/, only the case without a DEM law.
    assert_eq!(cases_run(&stdout), ["hard-nearly-incompressible"], "{stdout}");
    let (code, _, stderr) = run(&["verify", "--label", "haevy"]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("--label haevy: unknown label (allowed: fast, heavy"),
        "{stderr}"
    );
    let (code, _, stderr) = run(&["verify", "--label", "heavy"]);
    assert_eq!(code, 2, "cases/ has no heavy case: {stderr}");
    assert!(stderr.contains("none selected by label"), "{stderr}");
    // A folder given expands to its cases: the heavy one is there, and not run here.
    let (code, stdout, stderr) = run(&["verify", "cases-heavy", "--skip-label", "heavy"]);
    assert_eq!((code, stdout.as_str()), (2, ""), "{stderr}");
}

/// The fast cases without python (command-solver needs it): the hard cases.
const FAST: [&str; 2] = ["--label", "hard"];

#[test]
fn concurrent_runs_print_and_write_what_a_serial_run_does() {
    let dir = tempfile::tempdir().unwrap();
    let none = dir.path().join("no-baselines");
    // An empty baselines folder: a missing one is an error (a typo would hide the check).
    std::fs::create_dir(&none).unwrap();
    let mut outputs = Vec::new();
    for jobs in ["1", "2", "3"] {
        let junit = dir.path().join(format!("junit-{jobs}.xml"));
        let (code, stdout, stderr) = run(&[
            &[
                "verify",
                "cases/hard",
                "cases/sphere-on-flat.toml",
                "--jobs",
                jobs,
            ],
            &FAST[..],
            &["--junit", path(&junit), "--baselines", path(&none)],
        ]
        .concat());
        assert_eq!(code, 0, "{stdout}{stderr}");
        outputs.push((stdout, text(&junit)));
    }
    // sphere-on-flat has no label `hard`: it is left out, whatever the folder given.
    assert!(!outputs[0].0.contains("sphere-on-flat"), "{}", outputs[0].0);
    assert_eq!(cases_run(&outputs[0].0).len(), 8, "{}", outputs[0].0);
    assert_eq!(outputs[0], outputs[1]);
    assert_eq!(outputs[0], outputs[2]);
}

/// Two impact cases (a normal impact and a restitution sweep: fast), verified beside the hard
/// path cases when their label is selected too (docs/impact.md).
const IMPACT: [&str; 4] = [
    "cases/impact/chung-ooi-2.toml",
    "cases/impact/chung-ooi-3.toml",
    "--label",
    "impact",
];

#[test]
#[ignore = "heavy: verify four times (whole and three shards) on the hard cases and two impact cases with LAMMPS and YADE, 14 s on an idle core; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn three_shards_merged_equal_the_unsharded_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = |name: &str| dir.path().join(name);
    let none = d("no-baselines");
    // An empty baselines folder: a missing one is an error (a typo would hide the check).
    std::fs::create_dir(&none).unwrap();
    let common = [
        &["verify", "cases/hard", "--baselines", path(&none)][..],
        &FAST[..],
        &IMPACT[..],
    ]
    .concat();
    let (code, whole, stderr) = run(&[
        &common[..],
        &["--out", path(&d("whole")), "--junit", path(&d("whole.xml"))],
    ]
    .concat());
    assert_eq!(code, 0, "{whole}{stderr}");
    assert!(
        whole.contains("== chung-ooi-3") && whole.contains("== hard-"),
        "{whole}"
    );
    let (mut runs_in_shards, mut impact_runs) = (0, 0);
    for k in 1..=3 {
        let shard = format!("{k}/3");
        let out = d(&format!("shard-{k}"));
        let (code, stdout, stderr) = run(&[&common[..], &["--shard", &shard, "--out", path(&out)]].concat());
        assert_eq!(code, 0, "{stdout}{stderr}");
        let file: serde_json::Value = serde_json::from_str(&text(&out.join("run.json"))).unwrap();
        assert_eq!(file["shard"], shard);
        let runs = file["runs"].as_array().unwrap();
        assert!(!runs.is_empty(), "shard {shard} has no run");
        runs_in_shards += runs.len();
        impact_runs += runs
            .iter()
            .filter(|r| r["result"].get("impact").is_some())
            .count();
    }
    let whole_file: serde_json::Value = serde_json::from_str(&text(&d("whole").join("run.json"))).unwrap();
    assert_eq!(runs_in_shards, whole_file["runs"].as_array().unwrap().len());
    // Every impact run in exactly one shard: the whole run's, which are each case's five laws and
    // the DEM-code solvers its checks name (chung-ooi-2: 4 LAMMPS models, YADE, LIGGGHTS and
    // Kratos DEM; chung-ooi-3, damped: those and the references under LAMMPS's, YADE's and
    // LIGGGHTS' rules — Kratos damps by YADE's rule, so mdr-yade serves both), 12 + 15.
    let whole_impact_runs = whole_file["runs"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["result"].get("impact").is_some())
        .count();
    assert_eq!(impact_runs, whole_impact_runs);
    assert_eq!(impact_runs, 27);
    let shards: Vec<String> = (1..=3)
        .map(|k| d(&format!("shard-{k}")).to_str().unwrap().to_owned())
        .collect();
    let (code, merged, stderr) = run(&[
        &["merge"][..],
        &shards.iter().map(String::as_str).collect::<Vec<_>>(),
        &[
            "--junit",
            path(&d("merged.xml")),
            "--out",
            path(&d("merged")),
            "--baselines",
            path(&none),
        ],
    ]
    .concat());
    assert_eq!(code, 0, "{merged}{stderr}");
    assert!(stderr.contains("(shard 2/3): runs"), "{stderr}");
    assert_eq!(merged, whole);
    assert_eq!(text(&d("merged.xml")), text(&d("whole.xml")));
    assert_eq!(
        text(&d("merged").join("summary.txt")),
        text(&d("whole").join("summary.txt"))
    );
    assert!(text(&d("whole.xml")).contains("classname=\"chung-ooi-3\""));
    // The impact report beside the summary, the same from the merge.
    let report = text(&d("whole").join("impact/report.html"));
    assert!(report.contains("How far is your DEM code from exact Mindlin–Deresiewicz in impact?"));
    assert_eq!(text(&d("merged").join("impact/report.html")), report);
    // A shard missing is refused, naming a run it lacks; nothing is written.
    let (code, _, stderr) = run(&[
        "merge",
        &shards[0],
        &shards[2],
        "--junit",
        path(&d("partial.xml")),
    ]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("is a shard missing?"), "{stderr}");
    assert!(!d("partial.xml").exists());
}

/// A case with a command solver (Hertz in Python) whose force is scaled by the number in the
/// file `factor` beside it.
fn perturbable_case(dir: &Path) {
    let script = text(&root().join("examples/hertz_command_solver.py")).replace(
        "p = 4 / 3 * e_star * math.sqrt(r_star) * d**1.5  # normal force",
        "p = 4 / 3 * e_star * math.sqrt(r_star) * d**1.5 * float(open(sys.argv[2]).read())",
    );
    assert!(script.contains("sys.argv[2]"), "the example's force line moved");
    std::fs::write(dir.join("solver.py"), script).unwrap();
    std::fs::write(dir.join("factor"), "1.0").unwrap();
    let case = format!(
        "{}{}",
        common::SMALL_CASE.replace("solvers = [\"hertz\", \"mdr\"]", "solvers = [\"hertz\", \"py\"]"),
        r#"
[[command_solvers]]
name = "py"
kind = "analytic"
command = ["python3", "{case_dir}/solver.py", "{scene}", "{case_dir}/factor"]

[[checks]]
solver = "py"
quantity = "normal_force"
at = "every-step"
reference = { solver = "hertz" }
tolerance = 1e-6
reason = "the same closed form; loose enough that a 1e-9 change passes the check and only the baseline sees it"
"#
    );
    std::fs::write(dir.join("case.toml"), case).unwrap();
}

#[test]
fn a_drift_of_1e_9_fails_verify_until_the_baseline_is_updated() {
    let dir = tempfile::tempdir().unwrap();
    perturbable_case(dir.path());
    let (case, baselines) = (dir.path().join("case.toml"), dir.path().join("baselines"));
    let verify = || {
        run(&[
            "verify",
            path(&case),
            "--baselines",
            path(&baselines),
            "--allow-commands",
        ])
    };
    let update = || {
        let (code, stdout, stderr) = run(&[
            "baseline",
            "update",
            path(&case),
            "--baselines",
            path(&baselines),
            "--allow-commands",
        ]);
        assert_eq!(code, 0, "{stdout}{stderr}");
    };
    update();
    let stored = text(&baselines.join("cli-test.toml"));
    assert!(
        stored.contains("[solvers.\"py\"]") && stored.contains("check = \"py normal_force"),
        "{stored}"
    );
    let (code, stdout, _) = verify();
    assert_eq!(code, 0, "{stdout}");
    assert!(
        stdout.contains("OK    cli-test | py normal_force") && stdout.contains("| drift 0 at all 9 values"),
        "{stdout}"
    );
    std::fs::write(dir.path().join("factor"), "1.000000001").unwrap();
    let (code, stdout, _) = verify();
    assert_eq!(code, 1, "{stdout}");
    let row = stdout.lines().find(|l| l.contains("py normal_force")).unwrap();
    // Within the check's own tolerance, beyond the command solver's round-off: DRIFT alone,
    // naming the first step that moved (step 0 is unloaded, P = 0 times any factor) and how many.
    assert!(
        row.starts_with("DRIFT cli-test")
            && row.contains("| drift: first beyond tol at step 1: ")
            && row.contains("(change 1.0000e-9)")
            && row.contains("8 of 9 values moved"),
        "{row}"
    );
    assert!(
        stdout.contains("1 checks drifted from their baselines"),
        "{stdout}"
    );
    update();
    let (code, stdout, _) = verify();
    assert_eq!(code, 0, "{stdout}");
}

#[test]
fn every_shipped_case_is_labelled_and_the_heavy_one_is_heavy() {
    let mut files = common::all_case_files();
    files.push(root().join("cases-heavy/paper-fig7-3d.toml"));
    for file in &files {
        let case = spherecontact::case::Case::load(file).unwrap();
        assert!(!case.labels.is_empty(), "{} has no labels", file.display());
        let heavy = case.labels.iter().any(|l| l == "heavy");
        assert_eq!(
            heavy,
            file.starts_with(root().join("cases-heavy")),
            "{}",
            file.display()
        );
    }
}

#[test]
fn slurm_writes_a_job_array_of_shards_and_a_merge_after_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("slurm");
    let (code, stdout, stderr) = run(&[
        "slurm",
        "--label",
        "hard",
        "--shards",
        "3",
        "--cores",
        "2",
        "--out",
        path(&out),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let shards = text(&out.join("shards.sbatch"));
    assert!(
        shards.contains("#SBATCH --array=1-3\n") && shards.contains("#SBATCH --cpus-per-task=2\n"),
        "{shards}"
    );
    assert!(
        shards.contains(" verify '--label' 'hard' '--baselines' "),
        "{shards}"
    );
    assert!(shards.contains("--jobs 2 --shard \"$k/3\""), "{shards}");
    let merge = text(&out.join("merge.sbatch"));
    assert!(
        merge.contains(&format!(
            "merge '{}/shard-1' '{0}/shard-2' '{0}/shard-3'",
            out.display()
        )),
        "{merge}"
    );
    assert!(text(&out.join("submit.sh")).contains("sbatch --parsable --dependency=afterok:\"$array\""));
    assert!(!shards.contains("--require-baselines") && !merge.contains("--require-baselines"));
    // --require-baselines (CI's) goes into the shards' and the merge's command lines.
    let strict = dir.path().join("strict");
    let (code, stdout, stderr) = run(&[
        "slurm",
        "--label",
        "hard",
        "--shards",
        "3",
        "--require-baselines",
        "--out",
        path(&strict),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    for script in ["shards.sbatch", "merge.sbatch"] {
        let script = text(&strict.join(script));
        assert!(script.contains(" '--require-baselines'"), "{script}");
    }
    // Bad input writes nothing.
    let (code, _, stderr) = run(&[
        "slurm",
        "--label",
        "nope",
        "--shards",
        "3",
        "--out",
        path(&dir.path().join("x")),
    ]);
    assert_eq!(code, 2, "{stderr}");
    assert!(!dir.path().join("x").exists());
    let (code, _, stderr) = run(&["verify", "--shard", "4/3"]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("--shard 4/3: not a shard (allowed: K/N with 1 ≤ K ≤ N ≤ 1000"),
        "{stderr}"
    );
}
