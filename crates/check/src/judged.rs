//! A judged case as the verification job lists it, whatever its kind: a path case's checks
//! (`CaseRun` (spherecontact-verify)) and an impact case's (`ImpactRun` (spherecontact-impact)) become the
//! same rows, so that the printed table, the counts, `summary.txt` and the JUnit document are
//! made once for both (`conclusion (spherecontact-report)`, `junit (spherecontact-report)`).

use crate::Verdict;

/// One judged check: a JUnit test case and a printed row.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The JUnit test case's name: the check's index in its case and the check in words.
    pub title: String,
    /// The judgement.
    pub verdict: Verdict,
    /// The printed row (one line): value, reference, error, tolerance, drift, reason.
    pub text: String,
}

/// One judged case: a JUnit test suite and a printed block.
#[derive(Clone, Debug, PartialEq)]
pub struct Suite {
    /// The case's name.
    pub name: String,
    /// The block printed for it: a header line, warnings and failed solvers, then the rows.
    pub block: String,
    /// Its checks, in the case's order.
    pub rows: Vec<Row>,
    /// True when no check fails the run and every solver it needs ran or is not installed.
    pub passed: bool,
    /// The baseline file the case has none at (one line of text), when its values were compared
    /// with none (set by `verify` and `merge` after the comparison): said in the summary and the
    /// JUnit, a failure with `--require-baselines`.
    pub no_baseline: Option<String>,
}

impl Suite {
    /// The line that says the case has no baseline, if it has none (printed after its block, and
    /// its JUnit test case `baseline`).
    pub fn no_baseline_line(&self) -> Option<String> {
        self.no_baseline.as_ref().map(|file| {
            format!(
                "NOBASE {}: no baseline ({file}): its values are not compared with accepted ones \
                 (`spherecontact baseline update` writes it)",
                self.name
            )
        })
    }
}

/// How many rows of `suites` have `verdict`.
pub fn count(suites: &[Suite], verdict: Verdict) -> usize {
    suites
        .iter()
        .flat_map(|s| &s.rows)
        .filter(|r| r.verdict == verdict)
        .count()
}
