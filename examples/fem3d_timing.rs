//! Set-up cost and normal-contact accuracy of the 3D model (`fem-3d`) on the paper's spheres
//! (R 0.1 m, E 70 GPa, ν 0.3), half hemisphere gripped rigidly on its equatorial face.
//!
//! Run: `cargo run --release --example fem3d_timing -- [DIVISIONS…] [--variants] [--cattaneo]`,
//! or the whole paper path: `cargo run --release --example fem3d_timing -- --path SUBSTEPS
//! [--iterative] [--tolerance T] [--sub-triangles]` (the path of cases/paper-fig7.toml with
//! SUBSTEPS increments a segment, the default mesh; the solver `fem-3d` end to end: mesh, set-up
//! and every increment timed, Q against mdr-domain and MDR, peak memory; `--iterative`: the
//! engine's iterative algorithm; T: its tangential tolerance; `--sub-triangles`: multipliers at
//! every node on the sub-triangulated faces rather than at the corners).
//!
//! Set-up only:
//! (DIVISIONS: pole size = c_max / DIVISIONS, c_max the contact radius at δn = 20 µm; default 10).
//! For each mesh: gmsh's time, nodes, DOFs, candidates, the times of assembly, ordering,
//! factorisation and condensation, the factor's entries, the peak resident memory, and P at
//! δn = 17 µm against Hertz (the raw offset: finite body against half-space), the median wall and
//! CPU time of one frictionless increment of the engine (δn 1 … 25 µm); with `--cattaneo`, the
//! Cattaneo shift at 17 µm (disc friction, 60 increments) against Cattaneo–Mindlin. With
//! `--variants`, also the factorisation with faer's minimum degree on the whole DOF graph and the
//! condensation by blocked solves, side by side.

use std::time::Instant;

use spherecontact::bench::process_cpu_seconds;
use spherecontact::case::Case;
use spherecontact::contact::operator::work;
use spherecontact::contact::{Compliance, Method, Settings as ContactSettings};
use spherecontact::fem::element::tri6::Lame;
use spherecontact::fem::mesh::solid::SolidMesh;
use spherecontact::fem::ordering::NodeOrder;
use spherecontact::fem::solid3d::condense::Condensation;
use spherecontact::fem::solid3d::contact;
use spherecontact::fem::solid3d::meshing::{self, Zones};
use spherecontact::fem::solid3d::model::{Elimination, Model, Settings};
use spherecontact::fem::solid3d::surface::Rule;
use spherecontact::fem::solid3d::system::Grip;
use spherecontact::fem::FemSolid3d;
use spherecontact::history::{History, Quantity};
use spherecontact::pair::{Body, ContactPair, Material};
use spherecontact::path::LoadingPath;
use spherecontact::toolchain::Toolchain;
use spherecontact::{registry, solver};

/// Peak resident memory of this process so far [GB] (Linux VmHWM).
fn peak_memory_gb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1).and_then(|v| v.parse::<f64>().ok()))
        })
        .map_or(f64::NAN, |kb| kb / 1048576.0)
}

/// Median of the values (sorted here).
fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    spherecontact::bench::median(&values)
}

/// The frictionless engine along δn = 1 … 25 µm in 1 µm increments (the loading of
/// cases/hertz-normal.toml): median wall and CPU time of one increment.
fn normal_increments(model: &Model) {
    let mut engine = contact::engine(model, 0.0, false, ContactSettings::default(), None).unwrap();
    let (mut wall, mut cpu) = (Vec::new(), Vec::new());
    for k in 1..=25 {
        let (start, cpu0) = (Instant::now(), process_cpu_seconds());
        engine.advance(0.5e-6 * f64::from(k), &[]).unwrap();
        wall.push(start.elapsed().as_secs_f64());
        cpu.push(process_cpu_seconds() - cpu0);
    }
    println!(
        "    normal increments (δn 1 … 25 µm): median {:.4} s wall, {:.4} s CPU; max {:.4} s wall",
        median(wall.clone()),
        median(cpu),
        wall.iter().copied().fold(0.0, f64::max)
    );
}

/// The largest eigenvalue of `op` in its work product by 200 power iterations (a lower
/// estimate), against the Gershgorin bound the engine steps by.
fn spectrum(label: &str, op: &mut dyn Compliance) {
    let a = op.weights().to_vec();
    let n = a.len() * op.components();
    let mut x: Vec<f64> = (0..n).map(|i| 1.0 + 0.1 * (i % 7) as f64).collect();
    let mut y = vec![0.0; n];
    let mut estimate = 0.0;
    for _ in 0..200 {
        op.apply(&x, &mut y);
        estimate = work(&a, &x, &y) / work(&a, &x, &x);
        let norm = work(&a, &y, &y).sqrt();
        x.iter_mut().zip(&y).for_each(|(x, y)| *x = y / norm);
    }
    println!(
        "    {label} compliance: Gershgorin bound {:.4e}, power iteration {:.4e} (bound / estimate {:.3})",
        op.largest_eigenvalue(),
        estimate,
        op.largest_eigenvalue() / estimate
    );
}

fn report(label: &str, model: &Model, pair: &ContactPair, friction: bool) {
    spectrum("normal", &mut contact::normal(model).unwrap());
    spectrum("tangential", &mut contact::tangential(model, None).unwrap());
    normal_increments(model);
    let t = model.times;
    let hertz = spherecontact::hertz::Hertz::of(pair);
    let d = 17e-6;
    let start = Instant::now();
    let mut engine = contact::engine(model, 0.2, friction, ContactSettings::default(), None).unwrap();
    engine.advance(0.5 * d, &[0.0, 0.0]).unwrap();
    let solve = start.elapsed().as_secs_f64();
    let force = engine.normal_force();
    println!(
        "  {label}: assembly {:.2} s, ordering {:.2} s, factor {:.2} s ({:.1} M entries), condense {:.2} s; \
         P(17 µm) {:+.3} % against Hertz (engine set-up + normal solve {:.3} s); peak memory {:.2} GB",
        t.assembly,
        t.ordering,
        t.factor,
        model.factor.factor_entries() as f64 / 1e6,
        t.condense,
        100.0 * (force / hertz.force(d) - 1.0),
        solve,
        peak_memory_gb()
    );
    if !friction {
        return;
    }
    // Cattaneo: shift 0 → 6 µm at δn = 17 µm in 0.1 µm increments, against Cattaneo–Mindlin
    // with this model's own P (the raw tangential offset of the finite body).
    let mu = 0.2;
    let c = hertz.contact_radius(d);
    let shear = pair.mindlin_shear_modulus();
    let slide = 3.0 * mu * force / (16.0 * c * shear);
    let (mut times, mut cpu) = (Vec::new(), Vec::new());
    for k in 1..=60 {
        let dt = 0.1e-6 * k as f64;
        let (start, cpu0) = (Instant::now(), process_cpu_seconds());
        let cost = engine.advance(0.5 * d, &[0.05e-6, 0.0]).unwrap();
        times.push(start.elapsed().as_secs_f64());
        cpu.push(process_cpu_seconds() - cpu0);
        if k % 10 == 0 {
            let q = engine.tangential_force(0);
            let reference = mu * force * (1.0 - (1.0 - (dt / slide).min(1.0)).powf(1.5));
            let stick = engine.stick().iter().filter(|&&s| s).count();
            println!(
                "    δt {:.1} µm: Q {:.3} N, Cattaneo(FE P) {:.3} N ({:+.3} %), Qy {:.2e} N, {} stick nodes, {} iterations",
                1e6 * dt,
                q,
                reference,
                100.0 * (q / reference - 1.0),
                engine.tangential_force(1),
                stick,
                cost.tangential.iterations
            );
        }
    }
    println!(
        "    per increment: median {:.3} s wall, {:.3} s CPU, max {:.3} s wall",
        median(times.clone()),
        median(cpu),
        times.iter().copied().fold(0.0, f64::max)
    );
}

/// The whole paper path through the solver `fem-3d` (see the module doc).
fn paper_path(substeps: usize, method: Method, tolerance: f64, rule: Rule) {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/paper-fig7.toml");
    let mut scene = Case::load(&file).expect("the paper case").scene;
    let positions = scene.path.positions().to_vec();
    let segments = positions.len() - 1;
    scene.path = LoadingPath::try_new(positions, vec![substeps; segments]).expect("path");
    let run = |name: &str| {
        let solver = registry::by_name(name).expect("registered");
        solver::run(solver.as_ref(), &scene).unwrap_or_else(|e| panic!("{name}: {e}"))
    };
    let (mdr, corrected) = (run("mdr"), run("mdr-domain"));
    let (start, cpu0) = (Instant::now(), process_cpu_seconds());
    let solver = FemSolid3d {
        rule,
        contact: ContactSettings {
            method,
            tangential_tolerance: tolerance,
            ..ContactSettings::default()
        },
        ..FemSolid3d::default()
    };
    let history = solver::run(&solver, &scene).expect("fem-3d");
    let (wall, cpu) = (start.elapsed().as_secs_f64(), process_cpu_seconds() - cpu0);
    let extra = &history.metadata.extra;
    let number = |key: &str| extra.get(key).and_then(|v| v.as_f64()).unwrap_or(f64::NAN);
    let peak = corrected.peak(Quantity::TangentialForce);
    let worst = |reference: &History| {
        history
            .steps
            .iter()
            .zip(&reference.steps)
            .map(|(a, b)| (a.tangential_force.unwrap_or(0.0) - b.tangential_force.unwrap_or(0.0)).abs())
            .fold(0.0, f64::max)
            / peak
    };
    println!(
        "paper path, {substeps} increments a segment ({} steps), {method:?}, tangential tolerance {tolerance:e}, multipliers {rule:?}: {} DOFs, {} candidates",
        history.steps.len(),
        number("dofs"),
        number("candidates")
    );
    println!(
        "  whole run {wall:.1} s wall, {cpu:.1} s CPU: gmsh + read {:.2} s, assembly {:.2} s, ordering {:.2} s, \
         factor {:.2} s, condense {:.2} s, contact {:.2} s ({} increments: median {:.4} s, max {:.3} s); \
         tangential rounds {} (max {}); peak memory {:.2} GB",
        number("mesh_s"),
        number("assembly_s"),
        number("ordering_s"),
        number("factor_s"),
        number("condense_s"),
        number("contact_s"),
        number("increments"),
        number("increment_median_s"),
        number("increment_max_s"),
        number("tangential_iterations_total"),
        number("tangential_iterations_max"),
        peak_memory_gb()
    );
    println!(
        "  Q: worst |Q − Q_mdr-domain| {:.3} % of the peak, |Q − Q_mdr| {:.3} %",
        100.0 * worst(&corrected),
        100.0 * worst(&mdr)
    );
    for row in history.at_positions() {
        let k = row.position.unwrap();
        let (c, m) = (corrected.at_position(k).unwrap(), mdr.at_position(k).unwrap());
        let axes = extra["stick_semi_axes_m"][row.step].as_array().map(|a| {
            format!(
                "{:.1}/{:.1} µm",
                1e6 * a[0].as_f64().unwrap_or(0.0),
                1e6 * a[1].as_f64().unwrap_or(0.0)
            )
        });
        println!(
            "  P{k}: P {:.2} N (mdr-domain {:.2}, MDR {:.2}), Q {:+.3} N (mdr-domain {:+.3}, MDR {:+.3}), \
             stick radius {:.1} µm, semi-axes x/y {}",
            row.normal_force.unwrap_or(0.0),
            c.normal_force.unwrap_or(0.0),
            m.normal_force.unwrap_or(0.0),
            row.tangential_force.unwrap_or(0.0),
            c.tangential_force.unwrap_or(0.0),
            m.tangential_force.unwrap_or(0.0),
            1e6 * row.stick_radius.unwrap_or(0.0),
            axes.unwrap_or_else(|| "—".into())
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Some(k) = args.iter().position(|a| a == "--path") {
        let substeps = args.get(k + 1).and_then(|a| a.parse().ok()).unwrap_or(10);
        let method = if args.iter().any(|a| a == "--iterative") {
            Method::Iterative
        } else {
            Method::Direct
        };
        let tolerance = args
            .iter()
            .position(|a| a == "--tolerance")
            .and_then(|k| args.get(k + 1)?.parse().ok())
            .unwrap_or(ContactSettings::default().tangential_tolerance);
        let rule = if args.iter().any(|a| a == "--sub-triangles") {
            Rule::SubTriangles
        } else {
            Rule::Corners
        };
        paper_path(substeps, method, tolerance, rule);
        return;
    }
    let variants = args.iter().any(|a| a == "--variants");
    let friction = args.iter().any(|a| a == "--cattaneo");
    let divisions: Vec<f64> = args.iter().filter_map(|a| a.parse().ok()).collect();
    let divisions = if divisions.is_empty() {
        vec![10.0]
    } else {
        divisions
    };
    let body = Body {
        radius: 0.1,
        material: Material {
            young: 70e9,
            poisson: 0.3,
        },
    };
    let pair = ContactPair {
        body1: body,
        body2: body,
    };
    let radius = pair.body1.radius;
    let c_max = spherecontact::hertz::Hertz::of(&pair).contact_radius(20e-6);
    let lame = Lame::of(&pair.body1.material);
    for n in divisions {
        let h = c_max / n;
        let zones = Zones::new(c_max, h);
        let geometry = meshing::geometry(radius, radius, h, zones);
        let (mesh, mesh_s): (SolidMesh, f64) = match meshing::generate(&geometry, &Toolchain::default()) {
            Ok(m) => m,
            Err(e) => {
                println!("c/{n}: {e}");
                continue;
            }
        };
        println!(
            "pole size c_max/{n} = {:.1} µm: gmsh + read {:.2} s, {} nodes, {} tetrahedra",
            1e6 * h,
            mesh_s,
            mesh.nodes.len(),
            mesh.tetrahedra.len()
        );
        let mut runs = vec![(
            Elimination::ContactLast(NodeOrder::MinimumDegree),
            Condensation::TrailingBlock,
        )];
        if variants {
            runs.push((
                Elimination::ContactLast(NodeOrder::NestedDissection),
                Condensation::TrailingBlock,
            ));
            runs.push((Elimination::DofAmd, Condensation::BlockedSolves));
        }
        for (elimination, condensation) in runs {
            let settings = Settings {
                candidate_radius: zones.candidate_radius,
                elimination,
                condensation,
                grip: Grip::Rigid,
                rule: Rule::Corners,
            };
            let model = Model::build(mesh.clone(), lame, &settings).unwrap();
            println!(
                "  {} DOFs, {} candidate nodes ({} tangential unknowns)",
                model.dofs(),
                model.surface.len(),
                model.condensed.tangential_unknowns.len()
            );
            report(
                &format!("{elimination:?} + {condensation:?}"),
                &model,
                &pair,
                friction,
            );
        }
    }
}
