//! Text from outside the harness (a case's description, a check's reason, a file's name, a
//! program's message) made safe to show: every control character is written as a visible escape,
//! so that no input can move the cursor, clear a line, recolour the terminal or reorder what is
//! shown, and no `reason` can redraw a NOOK line as OK.
//!
//! One mechanism for every output: the terminal (`verify`'s table, the summary, error messages),
//! the reports (HTML, Markdown, the CSV data) and JUnit. Escaped are the C0 controls (with
//! ESC, CR, backspace), DEL, the C1 controls and the Unicode bidirectional and invisible
//! formatting characters (U+200B–U+200F, U+202A–U+202E, U+2060–U+2069, U+FEFF): each is written
//! `\u{…}` (a newline `\n`, a tab `\t`). [`one_line`] escapes newlines too (a table row, a cell, an
//! attribute); [`lines`] keeps them (a paragraph, a multi-line error message); [`row_lines`] puts a
//! message's further lines under its table row, indented. [`markdown`] adds
//! Markdown's own rule on top (`report.md`: no HTML, link or table cell from the text). [`nearest`]
//! is the "did you mean" of a message that refuses a name.

use std::borrow::Cow;

mod markdown;
mod nearest;
pub use markdown::markdown;
pub use nearest::nearest;

/// `text` with every control character escaped, newlines included: for text that must stay on
/// its line.
pub fn one_line(text: &str) -> Cow<'_, str> {
    escape(text, false)
}

/// `text` with every control character escaped except the newline: for text that may span
/// lines (each line is then shown as it is, none can rewrite another).
pub fn lines(text: &str) -> Cow<'_, str> {
    escape(text, true)
}

/// Where a line of text after the first goes in a table of one line per row ([`row_lines`]).
pub const CONTINUED: &str = "      ";

/// `text` (a message that may span lines: a program's last output) for a table of one line per
/// row: its first line escaped as [`one_line`] escapes it, and each further line escaped the same
/// way on its own line behind [`CONTINUED`] (every one begun by a newline), so that the lines are
/// read as lines and none can pass for a row.
pub fn row_lines(text: &str) -> (Cow<'_, str>, String) {
    let mut all = text.lines();
    let first = one_line(all.next().unwrap_or(""));
    let rest = all
        .map(|line| format!("\n{CONTINUED}{}", one_line(line)))
        .collect();
    (first, rest)
}

/// True for a character that changes how text is shown rather than being shown.
fn is_hidden(c: char) -> bool {
    c.is_control()
        || matches!(c,
            '\u{200B}'..='\u{200F}' | '\u{202A}'..='\u{202E}' | '\u{2060}'..='\u{2069}' | '\u{FEFF}')
}

fn escape(text: &str, keep_newlines: bool) -> Cow<'_, str> {
    let hidden = |c: char| is_hidden(c) && !(keep_newlines && c == '\n');
    if !text.chars().any(hidden) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        match c {
            c if !hidden(c) => out.push(c),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            c => out.push_str(&format!("\\u{{{:x}}}", c as u32)),
        }
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_text_is_borrowed_unchanged() {
        let text = "σ = 5 µm · ok — ü 🦀";
        assert!(matches!(one_line(text), Cow::Borrowed(t) if t == text));
    }

    #[test]
    fn controls_are_written_as_visible_escapes() {
        assert_eq!(
            one_line("a\x1b[1A\rOK\x08\x7f"),
            "a\\u{1b}[1A\\u{d}OK\\u{8}\\u{7f}"
        );
        assert_eq!(one_line("a\nb\tc\u{85}"), "a\\nb\\tc\\u{85}");
        assert_eq!(one_line("\u{202e}txt\u{feff}"), "\\u{202e}txt\\u{feff}");
    }

    /// Requirement: a message over lines is shown as lines in a table, each after the first
    /// behind the indent (never at a row's start), each line's own controls escaped.
    #[test]
    fn row_lines_puts_each_further_line_behind_the_indent() {
        let (first, rest) = row_lines("failed; last output:\nNOOK fake\x1b[2K\n\tend");
        assert_eq!(first, "failed; last output:");
        assert_eq!(
            rest,
            format!("\n{CONTINUED}NOOK fake\\u{{1b}}[2K\n{CONTINUED}\\tend")
        );
        assert_eq!(row_lines("one line"), (Cow::Borrowed("one line"), String::new()));
    }

    #[test]
    fn lines_keeps_newlines_only() {
        assert_eq!(lines("a\nb\r\nc\x1b"), "a\nb\\u{d}\nc\\u{1b}");
    }
}
