//! The 3D contact surface: both contact rules (multipliers at the corners, linear on the faces;
//! at every node, linear on the sub-triangles) pass the uniform-pressure patch test point by
//! point, and the two ways of condensing the contact compliance
//! agree. Run: `cargo test --test suite fem3d_surface::`.

use crate::solid_common;

use faer::Mat;
use spherecontact::contact::{Contact, DenseCompliance, Settings};
use spherecontact::fem::assembly::Dofs;
use spherecontact::fem::element::tri6::Lame;
use spherecontact::fem::factor::Factor;
use spherecontact::fem::mesh::solid::SolidMesh;
use spherecontact::fem::ordering::{self, NodeOrder};
use spherecontact::fem::solid3d::condense::{self, Condensation, Condensed};
use spherecontact::fem::solid3d::surface::{Rule, Surface};
use spherecontact::fem::solid3d::system;
use spherecontact::pair::Material;

const YOUNG: f64 = 2.0;

/// A bar on its contact face z = 0: u_z = 0 on the top z = 1, rollers on x = 0 and y = 0, the
/// sides x = 1 and y = 1 free. Pressed by δ onto a frictionless rigid plane, its exact state is
/// uniaxial: σ_zz = −E δ, a uniform contact pressure p = E δ.
fn bar(distort: bool, rule: Rule) -> (SolidMesh, Surface, Vec<Condensed>) {
    let mesh = solid_common::block(3, [1.0; 3], distort);
    let mut fixed = vec![false; 3 * mesh.nodes.len()];
    for (n, x) in mesh.nodes.iter().enumerate() {
        fixed[3 * n + 2] |= (x[2] - 1.0).abs() < 1e-12;
        fixed[3 * n] |= x[0].abs() < 1e-12;
        fixed[3 * n + 1] |= x[1].abs() < 1e-12;
    }
    let lame = Lame::of(&Material {
        young: YOUNG,
        poisson: 0.3,
    });
    let sys = system::assemble(&mesh, lame, Dofs::from_fixed(&fixed)).unwrap();
    let surface = Surface::new(&mesh, 10.0, rule).unwrap();
    let order = ordering::contact_last(
        &sys.graph,
        &mesh.nodes,
        &sys.dofs,
        &surface.nodes,
        NodeOrder::NestedDissection,
    )
    .unwrap();
    let factor = Factor::with_permutation(&sys.stiffness, &order.forward).unwrap();
    let condensed = [Condensation::TrailingBlock, Condensation::BlockedSolves]
        .map(|how| condense::condense(&sys, &factor, &order, &surface, how))
        .to_vec();
    (mesh, surface, condensed)
}

#[test]
fn a_uniform_pressure_is_recovered_at_every_node_corners_included() {
    let delta = 1e-3;
    for (distort, rule) in [false, true]
        .into_iter()
        .flat_map(|d| [(d, Rule::Corners), (d, Rule::SubTriangles)])
    {
        let (_, surface, condensed) = bar(distort, rule);
        let c = &condensed[0];
        let w = &surface.weights;
        // Multipliers: nodal pressures, acting through the compliance C' W.
        let compliance = Mat::from_fn(w.len(), w.len(), |i, k| c.normal[(i, k)] * w[k]);
        let normal = DenseCompliance::try_new(compliance, w.clone(), 1).unwrap();
        let mut contact: Contact<DenseCompliance, DenseCompliance> =
            Contact::new(normal, surface.heights(), Settings::default()).unwrap();
        contact.advance(delta, &[]).unwrap();
        let p = YOUNG * delta;
        for (j, pj) in contact.pressure().iter().enumerate() {
            // Round-off of the factorisation and the dense contact solve.
            assert!(
                (pj - p).abs() < 1e-9 * p,
                "{rule:?}: point {j} at {:?}: p = {pj}, uniform {p}",
                surface.points[j]
            );
        }
        // Equilibrium: P = p × the face area (1), and the top carries it.
        let total = contact.normal_force();
        let forces = contact.pressure().iter().zip(w).map(|(p, w)| p * w);
        let reaction: f64 = c.reaction[1].iter().zip(forces).map(|(r, f)| r * f).sum();
        assert!((total - p).abs() < 1e-9 * p && (reaction - total).abs() < 1e-9 * total);
    }
}

#[test]
fn the_trailing_block_and_the_blocked_solves_give_one_compliance() {
    let (_, _, condensed) = bar(true, Rule::Corners);
    let (a, b) = (&condensed[0], &condensed[1]);
    for (x, y) in [(&a.normal, &b.normal), (&a.tangential, &b.tangential)] {
        let scale = (0..x.nrows()).map(|i| x[(i, i)]).fold(0.0, f64::max);
        for i in 0..x.nrows() {
            for j in 0..x.ncols() {
                // Two exact computations of the same matrix: round-off apart.
                assert!((x[(i, j)] - y[(i, j)]).abs() < 1e-10 * scale, "({i}, {j})");
                assert!((x[(i, j)] - x[(j, i)]).abs() < 1e-10 * scale);
            }
        }
    }
    assert_eq!(a.tangential_unknowns, b.tangential_unknowns);
}
