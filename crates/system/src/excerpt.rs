//! What of a program's text a message shows: its last lines, each at most
//! [`MAX_SHOWN_LINE_CHARS`], together at most [`MAX_SHOWN_OUTPUT_BYTES`] (docs/security.md,
//! "Programs a case may run"). The text is masked before ([`super::mask`]), so that a cut never
//! leaves part of a secret; it is escaped where it is shown (`crate::text`).

use spherecontact_model::limits::{MAX_SHOWN_LINES, MAX_SHOWN_LINE_CHARS, MAX_SHOWN_OUTPUT_BYTES};

/// The last `lines` lines of `text` (at most [`MAX_SHOWN_LINES`]), each cut to
/// [`MAX_SHOWN_LINE_CHARS`], the first of them dropped until the rest fits
/// [`MAX_SHOWN_OUTPUT_BYTES`].
pub fn last_lines(text: &str, lines: usize) -> String {
    let all: Vec<&str> = text.lines().collect();
    let shown: Vec<String> = all[all.len().saturating_sub(lines.min(MAX_SHOWN_LINES))..]
        .iter()
        .map(|line| cut(line))
        .collect();
    // Joined by newlines: each line costs its bytes and a separator, the last line none.
    let mut bytes = 0;
    let fitting = shown
        .iter()
        .rev()
        .take_while(|line| {
            bytes += line.len() + 1;
            bytes <= MAX_SHOWN_OUTPUT_BYTES + 1
        })
        .count();
    shown[shown.len() - fitting..].join("\n")
}

/// `line` cut to [`MAX_SHOWN_LINE_CHARS`] characters, saying how many more it had.
fn cut(line: &str) -> String {
    match line.char_indices().nth(MAX_SHOWN_LINE_CHARS) {
        None => line.to_owned(),
        Some((end, _)) => {
            let more = line[end..].chars().count();
            format!("{} [… {more} more characters]", &line[..end])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Short output is shown as it is, its last lines only.
    #[test]
    fn short_output_shows_its_last_lines_unchanged() {
        assert_eq!(last_lines("a\nb\nc\n", 2), "b\nc");
        assert_eq!(last_lines("", 5), "");
    }

    /// A line longer than the bound is cut (on a character, never inside one) and says how
    /// much it had; the lines shown never pass the byte bound nor the line count.
    #[test]
    fn long_lines_are_cut_and_the_whole_is_bounded_in_lines_and_bytes() {
        let long = "é".repeat(MAX_SHOWN_LINE_CHARS + 5);
        let shown = last_lines(&format!("first\n{long}"), 2);
        let (kept, said) = shown.lines().nth(1).unwrap().split_once(" [… ").unwrap();
        assert_eq!(kept.chars().count(), MAX_SHOWN_LINE_CHARS);
        assert_eq!(said, "5 more characters]");
        let flood = format!("{long}\n").repeat(100);
        let shown = last_lines(&flood, 100);
        assert!(shown.len() <= MAX_SHOWN_OUTPUT_BYTES && !shown.is_empty());
        assert!(shown.lines().count() <= MAX_SHOWN_LINES);
        assert!(shown.lines().all(|l| l.ends_with("5 more characters]")));
    }
}
