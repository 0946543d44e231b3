//! JUnit XML for CI: one test suite per case, one test case per check. NOOK is a failure,
//! N/A a skip, INFO a pass that carries its measurement.

use std::fmt::Write;

use super::table::outcome_row;
use crate::check::Verdict;
use crate::verify::CaseRun;

/// Escapes text for an XML attribute or element, control characters first ([`crate::text`]:
/// XML 1.0 cannot hold most of them, and a CI log shows the rest raw).
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in crate::text::lines(text).chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

/// How every document opens: what tells a file `verify --junit` wrote from any other.
const OPENING: &str = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"spherecontact verify\"";

/// Whether `head`, the first bytes of a file, opens a document of [`document`]'s: `verify
/// --junit` replaces such a file, and no other without `--force`.
pub fn is_ours(head: &[u8]) -> bool {
    head.starts_with(OPENING.as_bytes())
}

/// The JUnit XML document of a verification run.
pub fn document(runs: &[CaseRun]) -> String {
    let count = |v: Verdict| {
        runs.iter()
            .flat_map(|r| &r.outcomes)
            .filter(|o| o.verdict == v)
            .count()
    };
    let total: usize = runs.iter().map(|r| r.outcomes.len()).sum();
    let mut xml = String::from(OPENING);
    let _ = writeln!(
        xml,
        " tests=\"{total}\" failures=\"{}\" skipped=\"{}\">",
        count(Verdict::Nook) + count(Verdict::Fixed) + count(Verdict::Drift),
        count(Verdict::Unavailable)
    );
    for run in runs {
        let name = run.case.name();
        let failures = run.outcomes.iter().filter(|o| o.verdict.fails_run()).count();
        let _ = writeln!(
            xml,
            "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{failures}\">",
            escape(name),
            run.outcomes.len()
        );
        for (i, outcome) in run.outcomes.iter().enumerate() {
            let spec = &outcome.spec;
            let title = format!(
                "{i:02} {} {} at {} vs {}",
                spec.solver, spec.quantity, spec.at, spec.reference
            );
            let _ = write!(
                xml,
                "    <testcase classname=\"{}\" name=\"{}\">",
                escape(name),
                escape(&title)
            );
            let row = escape(&outcome_row(name, outcome));
            match outcome.verdict {
                Verdict::Nook | Verdict::Drift => {
                    let label = outcome.verdict.label();
                    let _ = write!(xml, "<failure message=\"{label}\">{row}</failure>");
                }
                Verdict::Unavailable => {
                    let _ = write!(xml, "<skipped message=\"{row}\"/>");
                }
                Verdict::Fixed => {
                    let _ = write!(
                        xml,
                        "<failure message=\"FIXED? a known failure passes: remove its mark\">{row}</failure>"
                    );
                }
                Verdict::Ok | Verdict::Info | Verdict::Known => {
                    let _ = write!(xml, "<system-out>{row}</system-out>");
                }
            }
            xml.push_str("</testcase>\n");
        }
        xml.push_str("  </testsuite>\n");
    }
    xml.push_str("</testsuites>\n");
    xml
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_markup() {
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
