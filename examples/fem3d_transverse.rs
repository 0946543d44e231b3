//! The transverse traction q_y at the paper's position 5 (δn = 17 µm after the shifts 1, 2,
//! 3 µm), fem-3d against the BEM, under refinement of the mesh (the panels) and of the increments.
//!
//! Run: `cargo run --release --example fem3d_transverse -- [RUN…]`, each RUN `fem-3d:N:S[:T]`
//! (pole size c_max/N, the engine's tangential tolerance T; `fem-3d-sub`: multipliers at every
//! node on sub-triangulated faces) or `bem:N:S` (an N × N grid), S
//! increments a segment; default: the BEM at 64 and 128 panels and fem-3d at c_max/10, each at
//! 10 and 20 increments a segment.
//!
//! For each run, at position 5: the sample spacing h/c; max|q_y|/max|q_x| read pointwise (the
//! measure of the reports, `report::claims::measure`); the same ratio of the RMS over the
//! contact; the same ratio of the largest averages over square boxes of side c/5 on one grid
//! centred on the contact (a measure both discretisations share: each box holds several of
//! either's samples); ∫ q_y dA over the first quadrant; the stick semi-axes along x and y (the
//! reports' edge fit on the half-axes); and where max|q_y| lies (x/c, y/c, stick or slip) with
//! its value against the mean of its neighbours (a node-to-node oscillation or a one-point spike
//! shows as a peak far above its neighbours). Then, a line above it: the ratio on the hat
//! averages of the traction (`fit::recovery`; a grid's values as they are) and where its
//! largest |q̄_y| lies; the stick zone's second-moment semi-axes (`fit::stick::semi_axes`);
//! and at the pointwise maximum: its radius against the stick radius, |q|/μp, and how many of
//! its neighbours stick and slip.
//!
//! Along Cattaneo's shift: `cargo run --release --example fem3d_transverse -- shift [RUN…]`
//! presses the paper's spheres to δn = 17 µm and shifts them at constant δn to δt = 1, 2, 3,
//! 4 µm (S increments a segment, the normal one included), and prints one table: at each δt the
//! transverse share on the hat averages (`map_measure::transverse_ratio`, what the checks read),
//! the sign of ∫ q_y dA over the four quadrants (counter-clockwise from x, y > 0), the stick
//! zone's second-moment semi-axes (`map_measure::stick_semi_axes`), the stick radius and the
//! contact radius. Default runs: the BEM at 64, 128, 256 panels and fem-3d at c_max/8, /10,
//! /14, all at 10 increments a segment, and each at its default (64², c_max/10) at 20.

use spherecontact::fem::solid3d::surface::Rule;
use spherecontact::fem::FemSolid3d;
use spherecontact::fit::recovery::hat_averages;
use spherecontact::history::History;
use spherecontact::map_measure;
use spherecontact::registry;
use spherecontact::report::claims::study;
use spherecontact::report::figures::surface::{FieldView, Layout};
use spherecontact::scene::Scene;
use spherecontact::solver;

/// The paper's scene cut at position 5, `substeps` increments a segment.
fn scene(substeps: usize) -> Scene {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/paper-fig7.toml");
    let mut scene = spherecontact::case::Case::load(&file)
        .expect("the paper case")
        .scene;
    let positions = scene.path.positions()[..6].to_vec();
    scene.path = spherecontact::path::LoadingPath::try_new(positions, vec![substeps; 5]).expect("path");
    scene
}

/// Cattaneo's shift: δn = 17 µm, then δt = 1, 2, 3, 4 µm at constant δn (positions 2–5),
/// `substeps` increments a segment, on the paper's spheres.
fn shift_scene(substeps: usize) -> Scene {
    let mut scene = scene(substeps);
    let um = |n: f64, t: f64| spherecontact::path::Position {
        delta_n: n * 1e-6,
        delta_t: t * 1e-6,
    };
    let mut positions = vec![um(0.0, 0.0), um(17.0, 0.0)];
    positions.extend([1.0, 2.0, 3.0, 4.0].map(|t| um(17.0, t)));
    scene.path = spherecontact::path::LoadingPath::try_new(positions, vec![substeps; 5]).expect("path");
    scene
}

/// The shift's table: one row per run and δt.
fn shift(runs: &[String]) {
    let defaults = [
        "bem:64:10",
        "bem:128:10",
        "bem:256:10",
        "fem-3d:8:10",
        "fem-3d:10:10",
        "fem-3d:14:10",
        "bem:64:20",
        "fem-3d:10:20",
    ];
    let runs: Vec<String> = if runs.is_empty() {
        defaults.map(str::to_owned).to_vec()
    } else {
        runs.to_vec()
    };
    let mut table = Vec::new();
    for run in &runs {
        let (solver, n, substeps, tolerance) = parse(run);
        let scene = shift_scene(substeps);
        let t = std::time::Instant::now();
        let history = solve(solver, n, tolerance, &scene);
        let seconds = t.elapsed().as_secs_f64();
        eprintln!("{run}: {seconds:.0} s");
        for position in 2..=5 {
            table.push(shift_row(run, &history, position, scene.friction));
        }
    }
    println!("| run | δt [µm] | max|q̄_y|/max|q̄_x| | ∫q_y sign by quadrant | stick semi-axes x/y [µm] | stick radius [µm] | c [µm] | h [µm] |");
    println!("|---|---|---|---|---|---|---|---|");
    for row in table {
        println!("{row}");
    }
}

/// One row of the shift's table at `position`.
fn shift_row(run: &str, history: &History, position: usize, friction: f64) -> String {
    let row = history.at_position(position).expect("the position");
    let field = history.field_at(position).expect("a map at the position");
    let ratio = map_measure::transverse_ratio(field);
    let axes = map_measure::stick_semi_axes(field);
    let signs = study::measure(history, position, friction, None).map_or("—".into(), |(m, _)| {
        m.quadrants
            .iter()
            .map(|q| if q.total < 0.0 { "−" } else { "+" })
            .collect::<Vec<_>>()
            .join(",")
    });
    let spacing = FieldView::of(field).spacing();
    let um = |v: Option<f64>| v.map_or("—".into(), |v| format!("{:.1}", 1e6 * v));
    format!(
        "| {run} | {:.0} | {} | {signs} | {} | {} | {} | {:.1} |",
        1e6 * row.delta_t,
        ratio.map_or("—".into(), |r| format!("{r:.4}")),
        axes.map_or("—".into(), |a| format!("{:.1}/{:.1}", 1e6 * a[0], 1e6 * a[1])),
        um(row.stick_radius),
        um(row.contact_radius),
        1e6 * spacing
    )
}

/// A run `SOLVER:N:S[:TOLERANCE]`: solver, resolution, increments a segment, tolerance.
fn parse(run: &str) -> (&str, f64, usize, Option<f64>) {
    let parts: Vec<&str> = run.split(':').collect();
    let (solver, n, substeps, tolerance) = match parts[..] {
        [solver, n, substeps] => (solver, n, substeps, None),
        [solver, n, substeps, t] => (solver, n, substeps, Some(t.parse().expect("a tolerance"))),
        _ => panic!("a run is SOLVER:N:S[:TOLERANCE], not {run}"),
    };
    (
        solver,
        n.parse().expect("a resolution"),
        substeps.parse().expect("increments a segment"),
        tolerance,
    )
}

/// The history of `solver` at `n` (fem-3d: pole size c_max/n, also beyond the case files'
/// finest c_max/14, with the engine's tangential tolerance `tolerance` if given; bem: n × n
/// panels) on `scene`.
fn solve(solver: &str, n: f64, tolerance: Option<f64>, scene: &Scene) -> History {
    let rung: Box<dyn solver::Solver> = if solver.starts_with("fem-3d") {
        let mut fem = FemSolid3d::with_pole_size(scene.max_contact_radius() / n);
        if solver == "fem-3d-sub" {
            fem.rule = Rule::SubTriangles;
        }
        if let Some(t) = tolerance {
            fem.contact.tangential_tolerance = t;
        }
        Box::new(fem)
    } else {
        let base = registry::by_name(solver).expect("registered");
        base.at_resolution(scene, &n.to_string()).expect("resolution")
    };
    solver::run(rung.as_ref(), scene).unwrap_or_else(|e| panic!("{solver}: {e}"))
}

/// Each sample's neighbours: the triangles' other corners, or the grid's four neighbours.
fn neighbours(view: &FieldView) -> Vec<Vec<usize>> {
    let n = view.len();
    let mut around = vec![Vec::new(); n];
    match view.layout() {
        Layout::Triangles(triangles) => {
            for t in triangles {
                for &a in t {
                    around[a].extend(t.iter().copied().filter(|&b| b != a));
                }
            }
        }
        Layout::Grid { spacing } => {
            for (i, list) in around.iter_mut().enumerate() {
                let p = view.point(i);
                list.extend((0..n).filter(|&j| {
                    let q = view.point(j);
                    let d = (p[0] - q[0]).hypot(p[1] - q[1]);
                    d > 0.0 && d < 1.01 * spacing
                }));
            }
        }
        Layout::Profile => {}
    }
    for list in &mut around {
        list.sort_unstable();
        list.dedup();
    }
    around
}

fn report(label: &str, history: &History, friction: f64) {
    let (m, c) = study::measure(history, 5, friction, None).expect("a map at position 5");
    let view = FieldView::at_position(history, 5).expect("a field at position 5");
    let areas = view.areas().expect("a map");
    let contact: Vec<usize> = (0..view.len()).filter(|&i| view.in_contact(i)).collect();
    let q = |i: usize| view.traction(i).unwrap_or([0.0; 2]);
    let rms = |a: usize| {
        let s: f64 = contact.iter().map(|&i| q(i)[a].powi(2) * areas[i]).sum();
        let area: f64 = contact.iter().map(|&i| areas[i]).sum();
        (s / area).sqrt()
    };
    // The largest c/5 box averages, the reports' measure (report::claims::measure).
    let boxed = m.box_max;
    let around = neighbours(&view);
    let k = *contact
        .iter()
        .max_by(|&&a, &&b| q(a)[1].abs().total_cmp(&q(b)[1].abs()))
        .expect("contact");
    let mean_around = around[k].iter().map(|&j| q(j)[1]).sum::<f64>() / around[k].len().max(1) as f64;
    // Node-to-node roughness of p, q_x, q_y: the largest departure of a sample from the mean of
    // its neighbours, over the largest |value| (contact samples whose neighbours are all in
    // contact, so that the contact edge does not count).
    let roughness = |value: &dyn Fn(usize) -> f64| {
        let scale = contact.iter().map(|&i| value(i).abs()).fold(0.0, f64::max);
        contact
            .iter()
            .filter(|&&i| !around[i].is_empty() && around[i].iter().all(|&j| view.in_contact(j)))
            .map(|&i| {
                let mean = around[i].iter().map(|&j| value(j)).sum::<f64>() / around[i].len() as f64;
                (value(i) - mean).abs()
            })
            .fold(0.0, f64::max)
            / scale
    };
    println!(
        "  roughness (largest |v − neighbours' mean| / max|v|): p {:.3}, q_x {:.3}, q_y {:.3}",
        roughness(&|i| view.pressure(i)),
        roughness(&|i| q(i)[0]),
        roughness(&|i| q(i)[1])
    );
    let points2: Vec<[f64; 2]> = (0..view.len()).map(|i| view.point(i)).collect();
    let recovered = [0, 1].map(|a| {
        let v: Vec<f64> = (0..view.len())
            .map(|i| if view.in_contact(i) { q(i)[a] } else { 0.0 })
            .collect();
        view.triangles()
            .map_or(v.clone(), |t| hat_averages(&points2, t, &v))
    });
    let averaged = [0, 1].map(|a| contact.iter().map(|&i| recovered[a][i].abs()).fold(0.0, f64::max));
    let k_averaged = *contact
        .iter()
        .max_by(|&&a, &&b| recovered[1][a].abs().total_cmp(&recovered[1][b].abs()))
        .expect("contact");
    let [xa, ya] = view.point(k_averaged);
    let stick_radius = history
        .at_position(5)
        .and_then(|r| r.stick_radius)
        .unwrap_or(f64::NAN);
    let r_k = view.point(k)[0].hypot(view.point(k)[1]);
    let sticking = |i: usize| view.stick(i) == Some(true);
    // The second-moment semi-axes (`fit::stick::semi_axes`, fem-3d's per-step measure) on
    // the whole map, as the claims read them: integrals, they do not hinge on the edge's samples
    // along two lines.
    let moments = m.stick_moments;
    println!(
        "  hat-averaged max|q_y|/max|q_x| {:.4} at ({:.2}, {:.2}) c; second-moment stick semi-axes x/y {}; max|q_y| at r = {:.3} c \
         (stick radius {:.3} c), |q|/μp there {:.3}, its neighbours {} stick / {} slip",
        averaged[1] / averaged[0],
        xa / c,
        ya / c,
        moments.map_or("—".into(), |a| format!("{:.1}/{:.1} µm", 1e6 * a[0], 1e6 * a[1])),
        r_k / c,
        stick_radius / c,
        q(k)[0].hypot(q(k)[1]) / (friction * view.pressure(k)),
        around[k].iter().filter(|&&j| sticking(j)).count(),
        around[k].iter().filter(|&&j| view.in_contact(j) && !sticking(j)).count(),
    );
    let [x, y] = view.point(k);
    println!(
        "{label}: h = c/{:.0}; max|q_y|/max|q_x| {:.4}; RMS ratio {:.4}; box (c/5) ratio {:.4}; \
         ∫q_y dA (x, y > 0) {:+.4} N; stick semi-axes x/y {}; max|q_y| {:.3e} Pa at ({:.2}, {:.2}) c, {}, \
         its neighbours' mean {:+.3e} Pa ({} neighbours)",
        c / m.spacing,
        m.qy_max / m.qx_max,
        rms(1) / rms(0),
        boxed[1] / boxed[0],
        m.quadrants[0].total,
        m.stick_axes.map_or("—".into(), |a| format!(
            "{:.1}/{:.1} µm",
            1e6 * a[0],
            1e6 * a[1]
        )),
        q(k)[1],
        x / c,
        y / c,
        if view.stick(k) == Some(true) {
            "stick"
        } else {
            "slip"
        },
        mean_around,
        around[k].len()
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("shift") {
        shift(&args[1..]);
        return;
    }
    let runs: Vec<String> = if args.is_empty() {
        [
            "bem:64:10",
            "bem:128:10",
            "fem-3d:10:10",
            "bem:64:20",
            "bem:128:20",
            "fem-3d:10:20",
        ]
        .map(str::to_owned)
        .to_vec()
    } else {
        args
    };
    for run in &runs {
        let (solver, n, substeps, tolerance) = parse(run);
        let scene = scene(substeps);
        let t = std::time::Instant::now();
        let history = solve(solver, n, tolerance, &scene);
        let label = format!(
            "{solver} {n}, {substeps} increments a segment{} ({:.0} s)",
            tolerance.map_or(String::new(), |t| format!(", tolerance {t:e}")),
            t.elapsed().as_secs_f64()
        );
        report(&label, &history, scene.friction);
    }
}
