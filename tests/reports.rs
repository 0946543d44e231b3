//! Requirements of the reports (`compare`, `reproduce-paper`):
//! - they regenerate identically from the same inputs, apart from timings;
//! - every SVG is well-formed XML, and the HTML page is self-contained;
//! - a solver missing from a run is shown as missing, never as a line or a zero;
//! - the HTML loads in headless Chromium at a laptop's width without console messages, fits that
//!   width, and its first screen can be shot (skipped, with the reason printed, where Chromium is
//!   not installed).

mod common;

use std::path::Path;
use std::process::Command;

use common::root;
use spherecontact::report::claims::Study;
use spherecontact::report::{compare, paper};
use spherecontact::solver::SolveError;
use spherecontact::verify::{self, CaseRun};

/// The paper's case with the in-crate solvers.
fn paper_run() -> CaseRun {
    verify::run_case(common::paper_case_in_crate())
}

/// Text with the timing cells masked: HTML cells of class "timing", and the last Markdown cell of
/// a row that holds a wall time ("N ms", "N s", or "N ms (assembly … s, …)").
fn without_timings(text: &str) -> String {
    text.lines()
        .map(|line| {
            if let Some(start) = line.find("<td class=\"timing\">") {
                let end = line[start..].find("</td>").map_or(line.len(), |e| start + e);
                format!("{}TIMING{}", &line[..start], &line[end..])
            } else if line.starts_with("| ")
                && (line.ends_with(" ms |") || line.ends_with(" s |") || line.contains(" ms ("))
            {
                let cut = line[..line.len() - 2].rfind("| ").unwrap_or(0);
                format!("{}| TIMING |", &line[..cut])
            } else {
                line.to_owned()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn reports_regenerate_identically_apart_from_timings() {
    let dirs = [tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap()];
    for dir in &dirs {
        let run = paper_run();
        paper::document(&run, &Study::none(), &root().join("reference"))
            .unwrap()
            .write(dir.path())
            .unwrap();
    }
    let read = |dir: &Path, file: &str| without_timings(&std::fs::read_to_string(dir.join(file)).unwrap());
    for file in [
        "report.html",
        "report.md",
        "figures/tangential-force.svg",
        "data/tangential-force.csv",
    ] {
        assert_eq!(
            read(dirs[0].path(), file),
            read(dirs[1].path(), file),
            "{file} differs"
        );
    }
}

#[test]
fn every_svg_is_well_formed_and_the_page_is_self_contained() {
    let dir = tempfile::tempdir().unwrap();
    let run = paper_run();
    compare::document(&run).unwrap().write(dir.path()).unwrap();
    let svgs: Vec<_> = std::fs::read_dir(dir.path().join("figures"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert!(svgs.len() >= 6, "figures: {svgs:?}");
    for svg in &svgs {
        let text = std::fs::read_to_string(svg).unwrap();
        roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", svg.display()));
        assert!(!text.contains("NaN"), "{}", svg.display());
    }
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    assert!(html.contains("<svg") && !html.contains("<script") && !html.contains("src=\"http"));
    // Every inline SVG of the page parses too.
    let mut rest = html.as_str();
    while let Some(start) = rest.find("<svg") {
        let end = rest[start..].find("</svg>").expect("closed svg") + start + "</svg>".len();
        roxmltree::Document::parse(&rest[start..end]).expect("inline svg parses");
        rest = &rest[end..];
    }
}

#[test]
fn a_missing_solver_is_shown_as_missing_not_as_a_line() {
    let mut run = paper_run();
    run.histories.insert(
        "thornton".into(),
        Err(SolveError::Unavailable("thornton is not installed".into())),
    );
    let document = compare::document(&run).unwrap();
    let figures: Vec<_> = document.sections.iter().flat_map(|s| &s.figures).collect();
    let tangential = figures.iter().find(|f| f.id == "tangential-force").unwrap();
    assert!(
        tangential
            .caption
            .contains("Missing: thornton (not available: thornton is not installed)"),
        "{}",
        tangential.caption
    );
    assert!(
        tangential.data.rows.iter().all(|row| row[0].text != "thornton"),
        "no series for a missing solver"
    );
    let svg = roxmltree::Document::parse(&tangential.svg).unwrap();
    let texts: Vec<&str> = svg
        .descendants()
        .filter_map(|n| n.text())
        .map(str::trim)
        .collect();
    assert!(
        texts.contains(&"mdr"),
        "control: the legend names the solvers that ran: {texts:?}"
    );
    assert!(
        !texts.contains(&"thornton"),
        "no legend entry for a missing solver"
    );
    let solver_table = &document.sections[0].tables[0];
    let row = solver_table
        .rows
        .iter()
        .find(|r| r[0].text == "thornton")
        .unwrap();
    assert_eq!(row[1].text, "missing: not available");
    assert!(
        row[2..].iter().all(|c| !c.text.starts_with('0')),
        "no zeros stand in for a missing solver"
    );
}

/// A laptop's viewport [px]: the width a reader is most likely to open the report at.
const LAPTOP: (u32, u32) = (1366, 768);

/// Headless Chromium with a throw-away profile and nothing on the network; `None` (and a line
/// saying why the test is skipped) where Chromium is not installed.
fn chromium(profile: &Path) -> Option<Command> {
    let Some(binary) = ["chromium", "chromium-browser"]
        .into_iter()
        .find(|c| Command::new(c).arg("--version").output().is_ok())
    else {
        println!("skipped: Chromium is not installed (apt-get install chromium)");
        return None;
    };
    let mut command = Command::new(binary);
    command
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
        ])
        .args([
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--window-size={},{}", LAPTOP.0, LAPTOP.1))
        .args(["--hide-scrollbars", "--virtual-time-budget=3000"]);
    Some(command)
}

/// The width and height of a PNG, from its header.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "a PNG");
    let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
    (word(16), word(20))
}

#[test]
fn the_page_loads_at_laptop_width_in_headless_chromium_without_console_messages() {
    let profile = tempfile::tempdir().unwrap();
    let Some(mut load) = chromium(profile.path()) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    paper::document(&paper_run(), &Study::none(), &root().join("reference"))
        .unwrap()
        .write(dir.path())
        .unwrap();
    let page = dir.path().join("report.html");
    let output = load
        .args(["--enable-logging=stderr", "--v=0", "--dump-dom"])
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap();
    let (dom, log) = (
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr),
    );
    assert!(
        dom.contains("Figure 9: tangential force"),
        "the page did not load: {log}"
    );
    // Any console message — error, warning or log — is something a reader's browser complains of.
    let console: Vec<_> = log.lines().filter(|l| l.contains("CONSOLE")).collect();
    assert!(console.is_empty(), "console messages: {console:?}");

    // At laptop width nothing runs off the side: a measuring page loads the report in a frame
    // of that width and prints the width it needs.
    let measure = dir.path().join("measure.html");
    std::fs::write(
        &measure,
        format!(
            "<!DOCTYPE html><html><body style=\"margin:0\"><iframe id=\"page\" src=\"file://{}\" \
             style=\"width:{}px;height:600px;border:0\"></iframe><pre id=\"size\"></pre><script>\
             document.getElementById('page').onload = () => {{ const d = document.getElementById('page').contentDocument; \
             document.getElementById('size').textContent = 'NEEDS=' + d.documentElement.scrollWidth + 'x' + \
             d.documentElement.scrollHeight; }};</script></body></html>",
            page.display(),
            LAPTOP.0
        ),
    )
    .unwrap();
    let output = chromium(profile.path())
        .unwrap()
        .args(["--allow-file-access-from-files", "--dump-dom"])
        .arg(format!("file://{}", measure.display()))
        .output()
        .unwrap();
    let dom = String::from_utf8_lossy(&output.stdout);
    let needs = dom
        .split("NEEDS=")
        .nth(1)
        .and_then(|rest| rest.split('<').next())
        .unwrap_or_else(|| panic!("the measuring page printed no size: {dom}"));
    let (width, height) = needs.split_once('x').unwrap();
    let (width, height): (u32, u32) = (width.parse().unwrap(), height.parse().unwrap());
    assert!(
        width <= LAPTOP.0,
        "the page needs {width} px: it scrolls sideways at {} px",
        LAPTOP.0
    );
    assert!(
        height > 5 * LAPTOP.1,
        "control: the whole report was measured ({height} px)"
    );

    // The first screen, as a reader sees it on opening the report.
    let shot = dir.path().join("laptop.png");
    let output = chromium(profile.path())
        .unwrap()
        .arg(format!("--screenshot={}", shot.display()))
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap();
    let png = std::fs::read(&shot)
        .unwrap_or_else(|e| panic!("no screenshot ({e}): {}", String::from_utf8_lossy(&output.stderr)));
    assert_eq!(png_size(&png), LAPTOP);
}
