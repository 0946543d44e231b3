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
//! attribute); [`lines`] keeps them (a paragraph, a multi-line error message). [`markdown`] adds
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

    #[test]
    fn lines_keeps_newlines_only() {
        assert_eq!(lines("a\nb\r\nc\x1b"), "a\nb\\u{d}\nc\\u{1b}");
    }
}
