//! The reproduce-paper report as a reader sees it, in a real browser (headless Chromium) at a
//! laptop's 1366 × 768:
//! - the first viewport shows the verdict counts and the verdict of every claim of the paper;
//! - no element is wider than the page, and no table (folded ones opened) scrolls sideways, every
//!   section included (the paper's discretisation, which `reproduce-paper` adds where CalculiX is
//!   installed, from the values its case measured);
//! - every legend entry of a figure has its own colour-and-dash pair, read from the drawn SVG
//!   (the sample's colour, how many dashes it is drawn in, its marker's shape), and one pair
//!   never stands for two solvers in one figure;
//! - the page logs no console message.
//!
//! The page is measured by a script added to a copy of it, which writes its findings into the
//! DOM that Chromium dumps. Where Chromium is not installed the test says so loudly and passes,
//! except in CI (`CI=true`), where a missing browser is a failure.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::json;
use spherecontact::history::{History, StepResult};
use spherecontact::report::discretisation::{Discretisation, DEFAULT_CASE, FEM, REFERENCE, SOLVER};
use spherecontact::verify;

/// A laptop's viewport [px].
const LAPTOP: (u32, u32) = (1366, 768);

/// Chromium, or `None` where it is not installed outside CI (a failure in CI).
fn chromium() -> Option<PathBuf> {
    let found = ["/usr/bin/chromium", "/usr/bin/chromium-browser"]
        .into_iter()
        .map(PathBuf::from)
        .find(|p| p.is_file());
    if found.is_none() {
        let ci = std::env::var("CI").is_ok_and(|v| v == "true");
        assert!(
            !ci,
            "CI=true and Chromium is not installed: apt-get install chromium"
        );
        eprintln!(
            "\n*** SKIPPED report_browser: Chromium is not installed (apt-get install -y chromium) ***\n"
        );
    }
    found
}

/// Headless Chromium at laptop size with a fresh profile and nothing on the network.
fn browser(binary: &Path, profile: &Path) -> Command {
    let mut command = Command::new(binary);
    command
        .args(["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic"])
        .args(["--no-first-run", "--disable-background-networking"])
        .args([
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--window-size={},{}", LAPTOP.0, LAPTOP.1))
        .arg("--virtual-time-budget=5000");
    command
}

/// The reproduce-paper report of the paper's case as the README's main job writes it, every
/// section included: in-crate solvers but fem-3d (whose set-up alone would take most of a minute
/// in a debug build), 10 increments a segment (the page's structure does not depend on the
/// increments), and the section "The paper's discretisation" from [`discretisation_run`].
fn write_report(dir: &Path) -> PathBuf {
    let mut case = common::paper_case_coarse(10);
    case.solvers.retain(|s| s != "fem-3d");
    case.checks.retain(|c| c.solver != "fem-3d");
    let run = verify::run_case(case);
    let bricks = discretisation_run();
    spherecontact::report::paper::document(
        &run,
        &spherecontact::report::claims::Study::none(),
        &common::root().join("reference"),
        &Discretisation::Run(&bricks),
    )
    .expect("the paper report")
    .write(dir)
    .expect("written");
    dir.join("report.html")
}

/// The run of the paper's discretisation case (`cases-heavy/ccx-3d-hex20.toml`, which
/// `reproduce-paper` runs where CalculiX is installed) as its section reads it: P and Q of its
/// three solvers at positions 0-5, the values measured and quoted in that case file (ccx 2.20,
/// 140 s of CPU: too long to run here), P of fem-3d and mdr-domain at positions 4 and 5 as at 3
/// (δn unchanged); the bricks' element and fem-3d's stick slope as the solvers record them
/// (λ = 10 E/h, h = c_max/2). A fixture of the page's layout, never judged.
fn discretisation_run() -> verify::CaseRun {
    let case = spherecontact::case::Case::load(&common::root().join(DEFAULT_CASE)).unwrap();
    let history = |forces: [[f64; 2]; 6]| History {
        steps: case
            .scene
            .steps()
            .iter()
            .zip(forces)
            .map(|(step, [p, q])| StepResult {
                normal_force: Some(p),
                tangential_force: Some(q),
                ..StepResult::at(step)
            })
            .collect(),
        ..History::default()
    };
    let mut bricks = history([
        [0.0, 0.0],
        [372.51, -0.02],
        [608.66, 42.83],
        [810.35, 49.38],
        [810.33, 93.60],
        [810.35, 133.35],
    ]);
    bricks.metadata.extra.insert("element".into(), json!("C3D20R"));
    bricks.metadata.resolution = "pole brick c_max/2, graded fast".into();
    let mut fem = history([
        [0.0, 0.0],
        [374.69, 0.0],
        [602.18, 44.52],
        [811.17, 44.52],
        [811.17, 96.06],
        [811.17, 136.51],
    ]);
    fem.metadata
        .extra
        .insert("stick_slope_pa_per_m".into(), json!(1.52e15));
    let reference = history([
        [0.0, 0.0],
        [363.97, 0.0],
        [603.40, 47.64],
        [807.82, 47.66],
        [807.82, 98.87],
        [807.82, 135.53],
    ]);
    let histories = [(SOLVER, bricks), (FEM, fem), (REFERENCE, reference)]
        .into_iter()
        .map(|(name, h)| (name.to_owned(), Ok(h)))
        .collect();
    verify::CaseRun {
        case,
        warnings: Vec::new(),
        histories,
        outcomes: Vec::new(),
    }
}

/// The measuring script: every finding a line "FINDING kind: detail" in `<pre id="findings">`.
const MEASURE: &str = r#"
<script>
window.addEventListener('load', () => {
  const out = [];
  const say = (kind, detail) => out.push('FIND' + 'ING ' + kind + ': ' + detail); // split: the source itself is in the DOM
  // The first screen is the top 768 px, as a screenshot at 1366 × 768 shows it (a dumped page's
  // window is shorter by the browser's own bars: its innerHeight is not the laptop's).
  const H = 768, W = document.documentElement.clientWidth;
  say('width', window.innerWidth);
  // The first viewport: the verdict counts and every claim's verdict.
  const glance = document.getElementById('section-1');
  const counts = [...glance.querySelectorAll('p')].find(p => p.textContent.startsWith('Checks:'));
  if (!counts) say('missing', 'the verdict counts');
  else say(counts.getBoundingClientRect().bottom <= H ? 'in-view' : 'below-view', 'verdict counts');
  const claims = [...glance.querySelectorAll('table')].find(t => t.rows[0].textContent.includes('claim of the paper'));
  if (!claims) say('missing', 'the claims table');
  else {
    say('claims', claims.rows.length - 1);
    for (const row of [...claims.rows].slice(1)) {
      const cell = row.cells[0];
      say(cell.getBoundingClientRect().bottom <= H ? 'in-view' : 'below-view', 'claim verdict ' + cell.textContent);
    }
  }
  // Widths, with every folded section opened.
  document.querySelectorAll('details').forEach(d => d.open = true);
  say('page-width', document.documentElement.scrollWidth + ' of ' + W);
  let measured = 0;
  for (const el of document.body.querySelectorAll('*')) {
    const r = el.getBoundingClientRect();
    if (r.width === 0 && r.height === 0) continue;
    measured++;
    if (r.right > W + 0.5 || r.left < -0.5) say('too-wide', el.tagName + ' ' + (el.id || el.className.baseVal || el.className || '') + ' ' + r.left.toFixed(0) + '..' + r.right.toFixed(0));
  }
  say('elements', measured);
  const tables = document.querySelectorAll('table');
  say('tables', tables.length);
  for (const t of tables) {
    if (t.scrollWidth > t.clientWidth + 1) say('scrolls', 'table "' + t.rows[0].textContent.slice(0, 60) + '" ' + t.scrollWidth + ' > ' + t.clientWidth);
  }
  // Legends: each text a row; each sample shape belongs to the row nearest its centre.
  let entries = 0;
  for (const figure of document.querySelectorAll('figure')) {
    if (figure.id.includes('-map-')) continue; // colour scales and map categories, not series
    const owner = new Map();
    for (const legend of figure.querySelectorAll('g.legend')) {
      const rows = [...legend.querySelectorAll('text')].map(t => {
        const r = t.getBoundingClientRect();
        return { name: t.textContent.trim(), y: (r.top + r.bottom) / 2, shapes: [] };
      });
      for (const s of legend.querySelectorAll('polyline, circle, rect, polygon, path')) {
        const fill = s.getAttribute('fill'), stroke = s.getAttribute('stroke');
        if (s.tagName === 'rect' && (fill === 'none' || !fill)) continue; // the legend's box
        const r = s.getBoundingClientRect(), y = (r.top + r.bottom) / 2;
        let best = null;
        for (const row of rows) if (!best || Math.abs(row.y - y) < Math.abs(best.y - y)) best = row;
        if (best && Math.abs(best.y - y) < 11) best.shapes.push(s.tagName + ':' + (s.tagName === 'polyline' ? stroke : fill));
      }
      const pairs = new Map();
      for (const row of rows) {
        entries++;
        if (row.shapes.length === 0) { say('no-sample', figure.id + ' ' + row.name); continue; }
        const lines = row.shapes.filter(s => s.startsWith('polyline'));
        const marks = row.shapes.filter(s => !s.startsWith('polyline'));
        const colour = (lines[0] || marks[0]).split(':')[1].toLowerCase();
        const pair = colour + ' dashes=' + lines.length + ' marker=' + (marks[0] || '').split(':')[0];
        if (pairs.has(pair)) say('shared-pair', figure.id + ': ' + pairs.get(pair) + ' and ' + row.name + ' (' + pair + ')');
        pairs.set(pair, row.name);
        const solver = row.name.split(' vs ')[0].split(' raw')[0];
        const colourOwner = owner.get(pair);
        if (colourOwner && colourOwner !== solver) say('shared-pair', figure.id + ': ' + colourOwner + ' and ' + solver + ' across its plots (' + pair + ')');
        owner.set(pair, solver);
      }
    }
  }
  say('legend-entries', entries);
  const pre = document.createElement('pre');
  pre.id = 'findings';
  pre.textContent = out.join('\n');
  document.body.appendChild(pre);
});
</script>
"#;

/// The findings of the measuring script, "kind: detail" each.
fn measure(binary: &Path, page: &Path, profile: &Path) -> Vec<(String, String)> {
    let html = std::fs::read_to_string(page).unwrap();
    let copy = page.with_file_name("measured.html");
    std::fs::write(&copy, html.replace("</body>", &format!("{MEASURE}</body>"))).unwrap();
    let output = browser(binary, profile)
        .arg("--dump-dom")
        .arg(format!("file://{}", copy.display()))
        .output()
        .unwrap();
    let dom = String::from_utf8_lossy(&output.stdout);
    let findings: Vec<(String, String)> = dom
        .split("FINDING ")
        .skip(1)
        .filter_map(|l| l.split(['\n', '<']).next()?.split_once(": "))
        .map(|(k, d)| (k.to_owned(), d.replace("&amp;", "&").replace("&quot;", "\"")))
        .collect();
    assert!(
        !findings.is_empty(),
        "the measuring script wrote nothing: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    findings
}

#[test]
#[ignore = "heavy: the paper case and headless Chromium, 5 s on an idle core; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn the_paper_report_reads_at_a_glance_in_chromium_at_laptop_size() {
    let Some(binary) = chromium() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let profile = tempfile::tempdir().unwrap();
    let page = write_report(dir.path());
    // Every section is there, the paper's discretisation with its tables of P and Q.
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(
        html.contains("The paper&#39;s discretisation") || html.contains("The paper's discretisation"),
        "no discretisation section"
    );
    assert!(html.contains("P bricks [N]") && html.contains("Q bricks [N]"));
    let findings = measure(&binary, &page, profile.path());
    let all = |kind: &str| -> Vec<&str> {
        findings
            .iter()
            .filter(|(k, _)| k == kind)
            .map(|(_, d)| d.as_str())
            .collect()
    };
    let one = |kind: &str| {
        all(kind)
            .first()
            .copied()
            .unwrap_or_else(|| panic!("no {kind}: {findings:?}"))
    };
    assert_eq!(one("width"), LAPTOP.0.to_string(), "the window is a laptop's");
    assert!(all("missing").is_empty(), "{:?}", all("missing"));
    // Controls: the script saw the claims, the elements, the tables and the legends.
    let claims: usize = one("claims").parse().unwrap();
    assert!(claims >= 8, "the paper's claims: {claims}");
    assert!(one("elements").parse::<usize>().unwrap() > 1000);
    assert!(one("tables").parse::<usize>().unwrap() >= 5);
    assert!(one("legend-entries").parse::<usize>().unwrap() >= 30);

    let in_view = all("in-view");
    assert!(
        all("below-view").is_empty(),
        "below the first screen: {:?}",
        all("below-view")
    );
    assert_eq!(
        in_view.len(),
        claims + 1,
        "the counts and every claim's verdict in view"
    );
    let (width, page_width) = one("page-width").split_once(" of ").unwrap();
    assert!(
        width.parse::<u32>().unwrap() <= page_width.parse().unwrap(),
        "the page scrolls sideways"
    );
    assert!(
        all("too-wide").is_empty(),
        "wider than the page: {:?}",
        all("too-wide")
    );
    assert!(
        all("scrolls").is_empty(),
        "tables that scroll sideways: {:?}",
        all("scrolls")
    );
    assert!(
        all("no-sample").is_empty(),
        "legend rows without a sample: {:?}",
        all("no-sample")
    );
    assert!(all("shared-pair").is_empty(), "{:?}", all("shared-pair"));

    // The page as it is, without the measuring script: no console message at all.
    let output = browser(&binary, profile.path())
        .args(["--enable-logging=stderr", "--v=0", "--dump-dom"])
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap();
    let (dom, log) = (
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr),
    );
    assert!(dom.contains("At a glance"), "the page did not load: {log}");
    let console: Vec<&str> = log.lines().filter(|l| l.contains("CONSOLE")).collect();
    assert!(console.is_empty(), "console messages: {console:?}");
}
