//! What `verify` and `merge` print and write once the checks are judged: the check table case by
//! case, the counts, the JUnit document, and whether the run passed.

use std::fmt::Write;

use crate::junit;
use spherecontact_check::judged::{self, Suite};
use spherecontact_check::Verdict;

/// The verdicts of a verification run.
pub struct Conclusion<'a> {
    /// The cases judged (path and impact cases), in the plan's order.
    pub suites: &'a [Suite],
    /// A check that is N/A (a solver not installed) counts as a failure (`--require-external`).
    pub require_external: bool,
    /// A case without a baseline counts as a failure (`--require-baselines`).
    pub require_baselines: bool,
}

impl Conclusion<'_> {
    fn count(&self, verdict: Verdict) -> usize {
        judged::count(self.suites, verdict)
    }

    /// The text printed: each case's block of checks, then the counts.
    pub fn text(&self) -> String {
        let mut text = String::new();
        for suite in self.suites {
            text.push_str(&suite.block);
            if let Some(line) = suite.no_baseline_line() {
                let _ = writeln!(text, "{line}");
            }
        }
        let na = self.count(Verdict::Unavailable);
        let _ = writeln!(
            text,
            "verify: {} passed, {} failed, {} informational, {na} not available",
            self.count(Verdict::Ok),
            self.count(Verdict::Nook),
            self.count(Verdict::Info),
        );
        let (known, fixed) = (self.count(Verdict::Known), self.count(Verdict::Fixed));
        if known + fixed > 0 {
            let _ = writeln!(
                text,
                "verify: {known} known failures (KNOWN: a defect of an external code, shown with its evidence), {fixed} known failures that pass (FIXED?: the defect may be fixed, remove the mark)"
            );
        }
        let drifted = self.count(Verdict::Drift);
        if drifted > 0 {
            let _ = writeln!(
                text,
                "verify: {drifted} checks drifted from their baselines (DRIFT; `spherecontact baseline update` accepts a deliberate change)"
            );
        }
        let unbaselined = self.unbaselined();
        if unbaselined > 0 {
            let _ = writeln!(
                text,
                "verify: {unbaselined} cases without a baseline (NOBASE: their values are not compared with accepted ones){}",
                if self.require_baselines {
                    "; they count as failures (--require-baselines)"
                } else {
                    ""
                }
            );
        }
        if self.require_external && na > 0 {
            let _ = writeln!(
                text,
                "verify: {na} not-available checks count as failures (--require-external)"
            );
        }
        text
    }

    /// The JUnit XML document.
    pub fn junit(&self) -> String {
        junit::document(self.suites, self.require_baselines)
    }

    /// How many cases were compared with no baseline.
    fn unbaselined(&self) -> usize {
        self.suites.iter().filter(|s| s.no_baseline.is_some()).count()
    }

    /// True when every case passed ([`Suite::passed`]), with `require_external` no check is
    /// N/A, and with `require_baselines` every case has a baseline.
    pub fn passed(&self) -> bool {
        self.suites.iter().all(|s| s.passed)
            && !(self.require_external && self.count(Verdict::Unavailable) > 0)
            && !(self.require_baselines && self.unbaselined() > 0)
    }
}
