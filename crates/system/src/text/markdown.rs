//! Text from outside the harness written into Markdown (`report.md`) as text: shown as
//! `report.html` shows it, never read as markup. A case's description, a check's reason, a
//! solver's description, a run file's version or model could otherwise carry raw HTML (a
//! `<script>`, an `<img onerror=…>` that a renderer allowing HTML runs), a link (`[x](javascript:…)`),
//! a `|` that adds a table cell, or a `#` that starts a heading.
//!
//! The rule, in one pass over the text:
//! - control characters are escaped as everywhere ([`super::one_line`]), and a newline is a
//!   space: the text stays one paragraph, one cell or one heading (Markdown shows a line break
//!   inside a paragraph as a space anyway);
//! - HTML's characters are entities: `<` `&lt;`, `>` `&gt;`, and `&` `&amp;` where it could begin
//!   one (before a letter, a digit or `#`), so that no tag, comment or entity is read;
//! - `\`, `[`, `]` and `|` are backslash-escaped: no link, image, link definition or footnote
//!   can open, no cell can break, no escape of ours can be undone;
//! - a colon after a letter or a digit and before a non-space (a URL scheme's: `javascript:`,
//!   `data:`, `https://`) is backslash-escaped, so that no renderer links it and the text holds
//!   no `javascript:`;
//! - at the start, where Markdown reads a block (`# ` a heading, `- ` `+ ` `* ` a list, `---` a
//!   rule, three backticks or `~` a fence, `1. ` a numbered list, four spaces a code block), the
//!   spaces are dropped and the marker is backslash-escaped (`-1.8e-2` or `0.5 ms` is no block:
//!   left as it is).
//!
//! A backslash-escaped character and an entity show as the character itself. Backticks and
//! emphasis (`*`, `_`) inside the text are left: a code span shows its text literally, and
//! emphasis changes only how text looks.

/// `text` as Markdown that shows it as it is, on one line ([the module](self)).
pub fn markdown(text: &str) -> String {
    let flat = text.replace('\n', " ");
    let text = super::one_line(flat.trim_start());
    let marker = block_marker(&text);
    let mut out = String::with_capacity(text.len() + 16);
    let mut previous: Option<char> = None;
    let mut chars = text.char_indices().peekable();
    while let Some((at, c)) = chars.next() {
        let next = chars.peek().map(|&(_, n)| n);
        if Some(at) == marker {
            out.push('\\');
        }
        match c {
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '&' if next.is_some_and(|n| n.is_ascii_alphanumeric() || n == '#') => out.push_str("&amp;"),
            '\\' | '[' | ']' | '|' => {
                out.push('\\');
                out.push(c);
            }
            ':' if previous.is_some_and(|p| p.is_ascii_alphanumeric())
                && next.is_some_and(|n| !n.is_whitespace()) =>
            {
                out.push_str("\\:")
            }
            c => out.push(c),
        }
        previous = Some(c);
    }
    out
}

/// Where `text` starts a Markdown block, the byte index of the character to escape: the first
/// of a heading (`#` to `######` and a space), a list item (`-`, `+`, `*` and a space), a rule
/// (three `-`, `*` or `_`, spaces between) or a fence (three backticks or `~`); the `.` or `)`
/// of a numbered list item (up to nine digits, the mark and a space).
fn block_marker(text: &str) -> Option<usize> {
    // Tabs and newlines are escapes or spaces by now ([`markdown`]).
    let spaced = |rest: &str| rest.is_empty() || rest.starts_with(' ');
    let first = text.chars().next()?;
    let hashes = text.bytes().take_while(|&b| b == b'#').count();
    let rule = matches!(first, '-' | '*' | '_')
        && text.chars().all(|c| c == first || c == ' ')
        && text.matches(first).count() >= 3;
    if ((1..=6).contains(&hashes) && spaced(&text[hashes..]))
        || (matches!(first, '-' | '+' | '*') && spaced(&text[1..]))
        || rule
        || text.starts_with("```")
        || text.starts_with("~~~")
    {
        return Some(0);
    }
    let digits = text.bytes().take_while(u8::is_ascii_digit).count();
    let mark = text[digits..].chars().next();
    ((1..=9).contains(&digits) && matches!(mark, Some('.' | ')')) && spaced(&text[digits + 1..]))
        .then_some(digits)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_text_is_unchanged() {
        let text = "OK: P within 1e-3 of hertz (c_max/2 · ν = 0.3), see docs/paper.md: `--from`";
        assert_eq!(markdown(text), text);
    }

    #[test]
    fn html_is_written_as_entities() {
        assert_eq!(
            markdown("<script>alert(1)</script> <img src=x onerror=alert(2)> <!-- x -->"),
            "&lt;script&gt;alert(1)&lt;/script&gt; &lt;img src=x onerror=alert(2)&gt; &lt;!-- x --&gt;"
        );
        assert_eq!(
            markdown("R&D &amp; &#60; & so on"),
            "R&amp;D &amp;amp; &amp;#60; & so on"
        );
    }

    #[test]
    fn no_link_opens_and_no_cell_breaks() {
        assert_eq!(
            markdown("[x](javascript:alert(1)) ![i](data:x) [r]: https://e.org a | b"),
            "\\[x\\](javascript\\:alert(1)) !\\[i\\](data\\:x) \\[r\\]: https\\://e.org a \\| b"
        );
        // A backslash of the text cannot undo an escape of ours.
        assert_eq!(markdown("a \\| b \\[c"), "a \\\\\\| b \\\\\\[c");
    }

    #[test]
    fn no_block_starts() {
        for (text, shown) in [
            ("# forged heading", "\\# forged heading"),
            ("###### six", "\\###### six"),
            ("#", "\\#"),
            ("    - item", "\\- item"),
            ("* item", "\\* item"),
            ("- - -", "\\- - -"),
            ("___", "\\___"),
            ("2024. a year", "2024\\. a year"),
            ("1) one", "1\\) one"),
            ("```", "\\```"),
            ("~~~ fence", "\\~~~ fence"),
            ("> quote", "&gt; quote"),
            // Not blocks: left as they are.
            ("####### seven", "####### seven"),
            ("#1 first", "#1 first"),
            ("`code` first", "`code` first"),
            ("-1.8e-2", "-1.8e-2"),
            ("0.5 ms", "0.5 ms"),
            ("*emphasis*", "*emphasis*"),
            ("===", "==="),
        ] {
            assert_eq!(markdown(text), shown, "{text}");
        }
    }

    #[test]
    fn control_characters_are_escaped_and_newlines_are_spaces() {
        assert_eq!(markdown("a\nb\x1b[2K\r# c"), "a b\\\\u{1b}\\[2K\\\\u{d}# c");
        assert_eq!(markdown("line one\n# not a heading"), "line one # not a heading");
    }
}
