//! A report as data — sections of text, tables and figures with the CSV behind each — and its
//! two renderings: a self-contained HTML page (inline SVG and CSS, no network) and a Markdown
//! summary that links the SVG and CSV files written beside it.

use std::fmt::Write;
use std::path::Path;

use spherecontact_system::io::write_atomically;
use spherecontact_system::text::{lines, markdown, one_line};

/// A table cell: text, and a CSS class that marks verdicts and timings.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// The text shown.
    pub text: String,
    /// `ok`, `nook`, `info`, `na`, `timing`, or empty.
    pub class: &'static str,
}

impl Cell {
    /// A plain cell.
    pub fn plain(text: impl Into<String>) -> Self {
        Self {
            text: text.into(),
            class: "",
        }
    }

    /// A cell with a class.
    pub fn with_class(text: impl Into<String>, class: &'static str) -> Self {
        Self {
            text: text.into(),
            class,
        }
    }
}

/// A table with a header row.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// Column titles.
    pub header: Vec<String>,
    /// Rows of cells, as many as the header has columns.
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    /// The table as CSV text.
    pub fn to_csv(&self) -> anyhow::Result<String> {
        let mut writer = csv::Writer::from_writer(Vec::new());
        writer.write_record(self.header.iter().map(|h| one_line(h).into_owned()))?;
        for row in &self.rows {
            writer.write_record(row.iter().map(|c| one_line(&c.text).into_owned()))?;
        }
        Ok(String::from_utf8(writer.into_inner()?)?)
    }
}

/// A plot with its caption and the data behind it.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// File stem of its SVG and CSV (letters, digits, '-').
    pub id: String,
    /// The SVG document.
    pub svg: String,
    /// What it shows, and which solvers are missing from it and why.
    pub caption: String,
    /// The plotted values.
    pub data: Table,
}

/// A titled section.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Section {
    /// The heading.
    pub title: String,
    /// Paragraphs of plain text.
    pub paragraphs: Vec<String>,
    /// Tables, after the paragraphs.
    pub tables: Vec<Table>,
    /// Figures, after the tables.
    pub figures: Vec<Figure>,
    /// Folded in the HTML page (a `<details>` opened by its heading): detail a reader opens when
    /// the first screen sends them there. The Markdown report shows it in the same place.
    pub folded: bool,
}

/// A whole report.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Document {
    /// The page title.
    pub title: String,
    /// The sections, in order.
    pub sections: Vec<Section>,
}

/// Escapes text for HTML, control characters included ([`spherecontact_system::text`]).
pub fn escape_html(text: &str) -> String {
    lines(text)
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The page's style. Tables take the page's width and no more: cells wrap anywhere a long word
/// would otherwise widen the table (a path, a list of metadata), so no table scrolls sideways;
/// headings and verdicts (short) never break, timings only between words.
const STYLE: &str = "body{font-family:sans-serif;max-width:1100px;margin:1em auto;padding:0 1em;color:#222}\
h1{font-size:1.4em;margin:.3em 0}h2{font-size:1.2em;border-bottom:1px solid #ccc;padding-bottom:.2em;margin:1.5em 0 .5em}\
summary{cursor:pointer}summary h2{display:inline-block;border:0;margin:1em 0 .3em}\
table{border-collapse:collapse;margin:.5em 0;font-size:.82em;width:100%;table-layout:auto}\
td,th{border:1px solid #ccc;padding:.15em .4em;line-height:1.25;text-align:left;vertical-align:top;overflow-wrap:anywhere}\
th,td.ok,td.nook,td.info,td.na,td.known{white-space:nowrap}td.timing{overflow-wrap:normal}\
th{background:#f3f3f3}td.ok{color:#176b1e;font-weight:bold}td.nook{color:#b00;font-weight:bold}td.info{color:#555}td.na{color:#a60}td.known{color:#7a4b00;font-weight:bold}\
p{margin:.4em 0}nav{font-size:.85em;margin:.2em 0 .6em}figure{margin:1.5em 0}figcaption{font-size:.85em;color:#444;max-width:820px}\
svg{max-width:100%;height:auto}";

impl Document {
    /// The self-contained HTML page.
    pub fn to_html(&self) -> String {
        let mut html = String::new();
        let title = escape_html(&self.title);
        let _ = write!(
            html,
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{title}</title>\n\
             <style>{STYLE}</style>\n</head>\n<body>\n<h1>{title}</h1>\n"
        );
        // Contents, on a line or two after the first section (the answer comes first): a reader
        // jumps to a figure or a folded section.
        let mut contents = String::new();
        if self.sections.len() > 1 {
            let links: Vec<String> = self
                .sections
                .iter()
                .enumerate()
                .map(|(k, section)| {
                    format!(
                        "<a href=\"#section-{}\">{}</a>",
                        k + 1,
                        escape_html(&section.title)
                    )
                })
                .collect();
            contents = format!("<nav>Contents: {}</nav>\n", links.join(" · "));
        }
        for (k, section) in self.sections.iter().enumerate() {
            let heading = format!("<h2>{}</h2>", escape_html(&section.title));
            let heading = if section.folded {
                format!("<details><summary>{heading}</summary>")
            } else {
                heading
            };
            let _ = writeln!(html, "<section id=\"section-{}\">\n{heading}", k + 1);
            for paragraph in &section.paragraphs {
                let _ = writeln!(html, "<p>{}</p>", escape_html(paragraph));
            }
            for table in &section.tables {
                html.push_str(&table_html(table));
            }
            for figure in &section.figures {
                let _ = writeln!(
                    html,
                    "<figure id=\"{id}\">\n{svg}\n<figcaption>{caption} (data: <a href=\"data/{id}.csv\">{id}.csv</a>)</figcaption>\n</figure>",
                    id = figure.id,
                    svg = figure.svg,
                    caption = escape_html(&figure.caption)
                );
            }
            if section.folded {
                html.push_str("</details>\n");
            }
            html.push_str("</section>\n");
            if k == 0 {
                html.push_str(&contents);
            }
        }
        html.push_str("</body>\n</html>\n");
        html
    }

    /// The Markdown summary (figures linked as files). Every text, the title's to the cells',
    /// goes through [`markdown`]: Markdown shows what the HTML page shows, never markup of a
    /// case's or a file's.
    pub fn to_markdown(&self) -> String {
        let mut md = format!("# {}\n", markdown(&self.title));
        for section in &self.sections {
            let _ = write!(md, "\n## {}\n\n", markdown(&section.title));
            for paragraph in &section.paragraphs {
                let _ = write!(md, "{}\n\n", markdown(paragraph));
            }
            for table in &section.tables {
                let _ = writeln!(
                    md,
                    "| {} |",
                    table
                        .header
                        .iter()
                        .map(|h| markdown(h))
                        .collect::<Vec<_>>()
                        .join(" | ")
                );
                let _ = writeln!(md, "|{}", "---|".repeat(table.header.len()));
                for row in &table.rows {
                    let cells: Vec<_> = row.iter().map(|c| markdown(&c.text)).collect();
                    let _ = writeln!(md, "| {} |", cells.join(" | "));
                }
                md.push('\n');
            }
            for figure in &section.figures {
                let _ = write!(
                    md,
                    "![{caption}](figures/{id}.svg)\n\n*{caption}* (data: [data/{id}.csv](data/{id}.csv))\n\n",
                    id = figure.id,
                    caption = markdown(&figure.caption)
                );
            }
        }
        md
    }

    /// Writes `report.html`, `report.md`, `figures/*.svg` and `data/*.csv` into `dir`, each file
    /// atomically (the HTML last, so that a page never links files not yet written).
    pub fn write(&self, dir: &Path) -> anyhow::Result<()> {
        spherecontact_system::io::create_folder(&dir.join("figures"))?;
        spherecontact_system::io::create_folder(&dir.join("data"))?;
        for figure in self.sections.iter().flat_map(|s| &s.figures) {
            write_atomically(
                &dir.join("figures").join(format!("{}.svg", figure.id)),
                figure.svg.as_bytes(),
            )?;
            write_atomically(
                &dir.join("data").join(format!("{}.csv", figure.id)),
                figure.data.to_csv()?.as_bytes(),
            )?;
        }
        write_atomically(&dir.join("report.md"), self.to_markdown().as_bytes())?;
        write_atomically(&dir.join("report.html"), self.to_html().as_bytes())?;
        Ok(())
    }
}

/// A table as HTML.
fn table_html(table: &Table) -> String {
    let mut html = String::from("<table>\n<tr>");
    for title in &table.header {
        let _ = write!(html, "<th>{}</th>", escape_html(title));
    }
    html.push_str("</tr>\n");
    for row in &table.rows {
        html.push_str("<tr>");
        for cell in row {
            match cell.class {
                "" => {
                    let _ = write!(html, "<td>{}</td>", escape_html(&cell.text));
                }
                class => {
                    let _ = write!(html, "<td class=\"{class}\">{}</td>", escape_html(&cell.text));
                }
            }
        }
        html.push_str("</tr>\n");
    }
    html.push_str("</table>\n");
    html
}

#[cfg(test)]
mod tests {
    use super::*;

    fn document() -> Document {
        Document {
            title: "T <1>".into(),
            sections: vec![Section {
                title: "S".into(),
                paragraphs: vec!["a & b".into()],
                tables: vec![Table {
                    header: vec!["k".into(), "v".into()],
                    rows: vec![vec![Cell::plain("x|y"), Cell::with_class("OK", "ok")]],
                }],
                figures: vec![Figure {
                    id: "f1".into(),
                    svg: "<svg xmlns=\"http://www.w3.org/2000/svg\"></svg>".into(),
                    caption: "cap".into(),
                    data: Table {
                        header: vec!["x".into()],
                        rows: vec![vec![Cell::plain("1")]],
                    },
                }],
                folded: false,
            }],
        }
    }

    #[test]
    fn html_escapes_text_and_inlines_svg() {
        let html = document().to_html();
        assert!(html.contains("<title>T &lt;1&gt;</title>"));
        assert!(html.contains("<p>a &amp; b</p>"));
        assert!(html.contains("<td class=\"ok\">OK</td>"));
        assert!(html.contains("<svg xmlns"));
        assert!(
            !html.contains("http-equiv") && !html.contains("<script"),
            "no network, no script"
        );
    }

    #[test]
    fn pages_of_several_sections_list_them_with_links() {
        let mut doc = document();
        assert!(!doc.to_html().contains("<nav>"), "one section: no contents");
        doc.sections.push(Section {
            title: "Claims & more".into(),
            ..Section::default()
        });
        let html = doc.to_html();
        assert!(html.contains("<a href=\"#section-2\">Claims &amp; more</a></nav>"));
        assert!(html.contains("<section id=\"section-2\">"));
    }

    #[test]
    fn folded_sections_open_by_their_heading() {
        let mut doc = document();
        doc.sections[0].folded = true;
        let html = doc.to_html();
        assert!(html.contains("<details><summary><h2>S</h2></summary>"), "{html}");
        assert_eq!(
            html.matches("<details>").count(),
            html.matches("</details>").count()
        );
        // The Markdown report keeps the section where it is.
        assert!(doc.to_markdown().contains("## S\n\na & b"));
    }

    #[test]
    fn markdown_escapes_table_pipes() {
        let md = document().to_markdown();
        assert!(md.contains("| x\\|y | OK |"));
        assert!(md.contains("![cap](figures/f1.svg)"));
    }

    #[test]
    fn markdown_shows_every_text_as_text() {
        let mut doc = document();
        doc.title = "<b>T</b>".into();
        doc.sections[0].paragraphs = vec!["[x](javascript:alert(1))".into()];
        doc.sections[0].figures[0].caption = "c](javascript:alert(2)) <img src=x>".into();
        let md = doc.to_markdown();
        assert!(md.starts_with("# &lt;b&gt;T&lt;/b&gt;\n"), "{md}");
        assert!(md.contains("\n\\[x\\](javascript\\:alert(1))\n"), "{md}");
        assert!(
            md.contains("![c\\](javascript\\:alert(2)) &lt;img src=x&gt;](figures/f1.svg)"),
            "{md}"
        );
    }

    #[test]
    fn write_produces_every_file() {
        let dir = tempfile::tempdir().unwrap();
        document().write(dir.path()).unwrap();
        for file in ["report.html", "report.md", "figures/f1.svg", "data/f1.csv"] {
            assert!(dir.path().join(file).is_file(), "{file}");
        }
    }
}
