//! The engine on small dense problems with known answers, both algorithms.

use faer::Mat;

use super::*;

fn diagonal(values: &[f64]) -> DenseCompliance {
    let n = values.len();
    DenseCompliance::scalar(Mat::from_fn(n, n, |i, j| if i == j { values[i] } else { 0.0 })).unwrap()
}

fn settings(method: Method) -> Settings {
    Settings {
        method,
        normal_tolerance: 1e-13,
        tangential_tolerance: 1e-13,
        ..Settings::default()
    }
}

/// A random symmetric positive definite matrix (diagonally dominant) of side n, deterministic.
fn spd(n: usize, seed: u64) -> Mat<f64> {
    let mut state = seed;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let b = Mat::from_fn(n, n, |_, _| next() - 0.5);
    Mat::from_fn(n, n, |i, j| {
        let s: f64 = (0..n).map(|k| b[(i, k)] * b[(j, k)]).sum();
        s / n as f64 + if i == j { 1.0 } else { 0.0 }
    })
}

#[test]
fn a_diagonal_operator_has_the_closed_form_answer() {
    // Independent springs: λ_i = max(δ − h_i, 0)/C_ii; q_i = clamp(w/K_ii, ±μλ_i) from rest.
    let (c, k, h) = ([1.0, 2.0, 4.0], [0.5, 1.0, 2.0], [0.0, 0.2, 0.9]);
    for method in [Method::Direct, Method::Iterative] {
        let mut contact = Contact::new(diagonal(&c), h.to_vec(), settings(method))
            .unwrap()
            .with_friction(diagonal(&k), FrictionSet::Interval, 0.3)
            .unwrap();
        contact.advance(0.6, &[0.0]).unwrap();
        let expected = [0.6, 0.2, 0.0];
        for (i, (p, e)) in contact.pressure().iter().zip(expected).enumerate() {
            assert!((p - e).abs() < 1e-12, "{method:?} λ {i}");
        }
        contact.advance(0.6, &[0.05]).unwrap();
        // w/K = 0.1, 0.05 against μλ = 0.18, 0.06: both stick.
        let q = contact.traction().to_vec();
        assert!(
            (q[0] - 0.1).abs() < 1e-12 && (q[1] - 0.05).abs() < 1e-12 && q[2] == 0.0,
            "{method:?} {q:?}"
        );
        assert_eq!(contact.stick(), vec![true, true, false]);
        contact.advance(0.6, &[0.05]).unwrap();
        // 0.2 and 0.1 against 0.18 and 0.06: both slip, q at the bound, slip accumulated.
        let q = contact.traction().to_vec();
        assert!(
            (q[0] - 0.18).abs() < 1e-12 && (q[1] - 0.06).abs() < 1e-12,
            "{method:?} {q:?}"
        );
        assert_eq!(contact.stick(), vec![false, false, false]);
        // Slip: the shift 0.1 in all less the elastic part q K: 0.1 − 0.09, 0.1 − 0.06.
        let s = contact.slip();
        assert!(
            (s[0] - 0.01).abs() < 1e-12 && (s[1] - 0.04).abs() < 1e-12,
            "{s:?}"
        );
        // Reversal: −0.05 unloads elastically by 0.1 and 0.05 (stick).
        contact.advance(0.6, &[-0.05]).unwrap();
        let q = contact.traction().to_vec();
        assert!(
            (q[0] - 0.08).abs() < 1e-12 && (q[1] - 0.01).abs() < 1e-12,
            "{method:?} {q:?}"
        );
        // Separation clears the memory; re-contact starts from q = 0.
        contact.advance(-1.0, &[0.0]).unwrap();
        assert_eq!(contact.normal_force(), 0.0);
        assert!(contact.traction().iter().chain(contact.slip()).all(|&v| v == 0.0));
        contact.advance(0.6, &[0.01]).unwrap();
        assert!((contact.traction()[0] - 0.02).abs() < 1e-12);
    }
}

#[test]
fn two_coupled_points_match_the_hand_solution() {
    // C = [[2, 1], [1, 2]], h = (0, 0.5), δ = 1: both in contact would need λ = C⁻¹(1, 0.5) =
    // (0.5, 0); so point 1 just touches. At δ = 2: λ = C⁻¹(2, 1.5) = (5/6, 1/3).
    let c = Mat::from_fn(2, 2, |i, j| if i == j { 2.0 } else { 1.0 });
    for method in [Method::Direct, Method::Iterative] {
        let op = DenseCompliance::scalar(c.clone()).unwrap();
        let mut contact: Contact<_, DenseCompliance> =
            Contact::new(op, vec![0.0, 0.5], settings(method)).unwrap();
        contact.advance(2.0, &[]).unwrap();
        let p = contact.pressure();
        assert!(
            (p[0] - 5.0 / 6.0).abs() < 1e-12 && (p[1] - 1.0 / 3.0).abs() < 1e-12,
            "{method:?} {p:?}"
        );
        contact.advance(0.8, &[]).unwrap();
        // Point 1 alone would give λ0 = 0.4 and gap 0.5 − 0.8 + 0.4 = 0.1 ≥ 0 at point 1.
        let p = contact.pressure();
        assert!((p[0] - 0.4).abs() < 1e-12 && p[1] == 0.0, "{method:?} {p:?}");
        assert!(contact.gaps()[0].abs() < 1e-12 && (contact.gaps()[1] - 0.1).abs() < 1e-12);
    }
}

#[test]
fn the_two_algorithms_agree_along_a_path_on_a_disc() {
    // A 2-component tangential operator on 12 points, coupled between points and, weakly as
    // Cerruti's ν term couples them, between components; a path with loading, partial slip,
    // reversal, unloading to separation and re-contact: the iterative and direct answers agree.
    let m = 12;
    let normal = spd(m, 1);
    let (own, cross) = (spd(m, 2), spd(m, 3));
    let tangential = Mat::from_fn(2 * m, 2 * m, |r, c| {
        let (i, j) = (r % m, c % m);
        if r / m == c / m {
            own[(i, j)]
        } else {
            0.1 * (cross[(i, j)] - if i == j { 1.0 } else { 0.0 })
        }
    });
    let h: Vec<f64> = (0..m).map(|i| 0.02 * (i as f64 - 5.5).powi(2)).collect();
    let path = [
        (0.5, [0.0, 0.0]),
        (0.6, [0.05, 0.01]),
        (0.6, [0.05, 0.0]),
        (0.55, [-0.08, 0.02]),
        (0.3, [0.0, -0.03]),
        (-0.1, [0.0, 0.0]),
        (0.5, [0.1, 0.0]),
    ];
    let run = |method| {
        let mut contact = Contact::new(
            DenseCompliance::scalar(normal.clone()).unwrap(),
            h.clone(),
            settings(method),
        )
        .unwrap()
        .with_friction(
            DenseCompliance::try_new(tangential.clone(), vec![1.0; m], 2).unwrap(),
            FrictionSet::Disc,
            0.4,
        )
        .unwrap();
        path.iter()
            .map(|(d, w)| {
                contact.advance(*d, w).unwrap();
                (
                    contact.pressure().to_vec(),
                    contact.traction().to_vec(),
                    contact.stick(),
                )
            })
            .collect::<Vec<_>>()
    };
    let (direct, iterative) = (run(Method::Direct), run(Method::Iterative));
    let mut mixed = 0;
    for (step, (d, i)) in direct.iter().zip(&iterative).enumerate() {
        for (a, b) in d.0.iter().zip(&i.0).chain(d.1.iter().zip(&i.1)) {
            // Tolerance: both solve to 1e-13 of the scales (λ, μλ ~ 0.1–1).
            assert!((a - b).abs() < 1e-9, "step {step}: {a} vs {b}");
        }
        assert_eq!(d.2, i.2, "step {step}: stick sets");
        mixed += usize::from(d.2.iter().any(|&s| s) && d.2.iter().zip(&d.0).any(|(&s, &p)| !s && p > 0.0));
    }
    assert!(mixed >= 2, "the path must show partial slip");
}

#[test]
fn a_point_penetrating_beside_a_solved_contact_set_enters_it() {
    // C = I, point 0 in contact with zero gap already (λ0 = 1 for o0 = −1), point 1 open but
    // penetrating (o1 = −0.5): the CG step on the solved set is 0, which must not keep point 1
    // out (it once looped to the iteration cap, fem-3d at δn = 0.3 µm on the paper path).
    let mut op = diagonal(&[1.0, 1.0]);
    let mut state = normal::NormalState {
        multipliers: vec![1.0, 0.0],
        displacement: vec![1.0, 0.0],
    };
    let opening = [-1.0, -0.5];
    let mut problem = normal::NormalProblem {
        op: &mut op,
        opening: &opening,
        scale: 1.0,
        tolerance: 1e-13,
        max_iterations: 100,
        seed_stiffness: 1.0,
    };
    problem.solve_iterative(&mut state).expect("converges");
    let p = &state.multipliers;
    assert!((p[0] - 1.0).abs() < 1e-12 && (p[1] - 0.5).abs() < 1e-12, "{p:?}");
}

#[test]
fn a_normal_guess_changes_the_start_not_the_answer() {
    // Requirement: a guess (nested iteration's interpolated coarse answer) leaves the converged
    // pressures along a path as without it (both solve to 1e-13 of λ ~ 0.1–1); a guess that does
    // not fit the points is refused.
    let m = 10;
    let h: Vec<f64> = (0..m).map(|i| 0.03 * (i as f64 - 4.5).powi(2)).collect();
    let path = [0.4, 0.5, 0.6];
    let run = |guess: Option<Vec<f64>>| {
        let op = DenseCompliance::scalar(spd(m, 4)).unwrap();
        let mut contact =
            Contact::<_, DenseCompliance>::new(op, h.clone(), settings(Method::Iterative)).unwrap();
        if let Some(g) = guess {
            contact.guess_normal(g).unwrap();
        }
        path.iter()
            .map(|&d| {
                contact.advance(d, &[]).unwrap();
                contact.pressure().to_vec()
            })
            .collect::<Vec<_>>()
    };
    let plain = run(None);
    // A poor guess: pressure everywhere, the wrong shape.
    let guessed = run(Some((0..m).map(|i| 0.05 * i as f64).collect()));
    for (step, (a, b)) in plain.iter().zip(&guessed).enumerate() {
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() < 1e-9, "step {step}: {x} vs {y}");
        }
    }
    let op = DenseCompliance::scalar(spd(m, 4)).unwrap();
    let mut contact = Contact::<_, DenseCompliance>::new(op, h, settings(Method::Iterative)).unwrap();
    assert!(contact.guess_normal(vec![0.1; m - 1]).is_err());
    assert!(contact.guess_normal(vec![-0.1; m]).is_err());
    assert!(contact.guess_normal(vec![f64::NAN; m]).is_err());
}
