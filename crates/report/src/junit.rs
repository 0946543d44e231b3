//! JUnit XML for CI: one test suite per case, one test case per check. NOOK is a failure,
//! N/A a skip, INFO a pass that carries its measurement.

use std::fmt::Write;

use spherecontact_check::judged::{count, Suite};
use spherecontact_check::Verdict;

/// Escapes text for an XML attribute or element, control characters first ([`spherecontact_system::text`]:
/// XML 1.0 cannot hold most of them, and a CI log shows the rest raw).
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in spherecontact_system::text::lines(text).chars() {
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

/// The JUnit XML document of a verification run: a test suite per case, a test case per check
/// (path and impact cases alike, [`spherecontact_check::judged`]), and a test case `baseline`
/// in the suite of a case compared with no baseline: skipped, or a failure when
/// `require_baselines` (`--require-baselines`).
pub fn document(suites: &[Suite], require_baselines: bool) -> String {
    let unbaselined = suites.iter().filter(|s| s.no_baseline.is_some()).count();
    let total: usize = suites.iter().map(|s| s.rows.len()).sum::<usize>() + unbaselined;
    let (failed, skipped) = if require_baselines {
        (unbaselined, 0)
    } else {
        (0, unbaselined)
    };
    let mut xml = String::from(OPENING);
    let _ = writeln!(
        xml,
        " tests=\"{total}\" failures=\"{}\" skipped=\"{}\">",
        count(suites, Verdict::Nook) + count(suites, Verdict::Fixed) + count(suites, Verdict::Drift) + failed,
        count(suites, Verdict::Unavailable) + skipped
    );
    for suite in suites {
        let name = escape(&suite.name);
        let missing = suite.no_baseline_line();
        let failures = suite.rows.iter().filter(|r| r.verdict.fails_run()).count()
            + usize::from(require_baselines && missing.is_some());
        let _ = writeln!(
            xml,
            "  <testsuite name=\"{name}\" tests=\"{}\" failures=\"{failures}\">",
            suite.rows.len() + usize::from(missing.is_some())
        );
        if let Some(line) = missing {
            let text = escape(&line);
            let _ = if require_baselines {
                writeln!(
                    xml,
                    "    <testcase classname=\"{name}\" name=\"baseline\"><failure message=\"NO BASELINE \
                     (--require-baselines)\">{text}</failure></testcase>"
                )
            } else {
                writeln!(
                    xml,
                    "    <testcase classname=\"{name}\" name=\"baseline\"><skipped message=\"{text}\"/></testcase>"
                )
            };
        }
        for row in &suite.rows {
            let _ = write!(
                xml,
                "    <testcase classname=\"{name}\" name=\"{}\">",
                escape(&row.title)
            );
            let text = escape(&row.text);
            match row.verdict {
                Verdict::Nook | Verdict::Drift => {
                    let label = row.verdict.label();
                    let _ = write!(xml, "<failure message=\"{label}\">{text}</failure>");
                }
                Verdict::Unavailable => {
                    let _ = write!(xml, "<skipped message=\"{text}\"/>");
                }
                Verdict::Fixed => {
                    let _ = write!(
                        xml,
                        "<failure message=\"FIXED? a known failure passes: remove its mark\">{text}</failure>"
                    );
                }
                Verdict::Ok | Verdict::Info | Verdict::Known => {
                    let _ = write!(xml, "<system-out>{text}</system-out>");
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
