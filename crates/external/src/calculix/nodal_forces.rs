//! The contact's nodal forces of a `ccx-3d` run, recovered from the displacements CalculiX
//! writes, and their averages over the corners' linear hats: the read-back pressure and traction.
//!
//! Why not CalculiX's own contact output. Its nodal tractions (CPRESS, CSHEAR of
//! `*CONTACT FILE`) are extrapolated from the contact's integration points, and beyond the
//! contact edge they reach 3.9 p0 at c_max/5 (docs/external-decks.md, "ccx-3d's maps at
//! c_max/5"); the integration points' values (`*CONTACT PRINT`) come without positions; and the
//! contact's nodal forces are not printed at all: CalculiX counts its contact elements among the
//! internal forces, so RF at a slave node is the residual.
//!
//! The recovery. Sphere 1 is in equilibrium under its contact forces, its grip and its symmetry
//! plane, so at a slave node away from the grip the contact's force is the body's internal force
//! there, f_i = Σ_e (K_e u_e)_i = Σ_e ∫ σ ∇N_i dV ([`internal_forces`]), on CalculiX's own
//! elements: the same nodes, E and ν, and its own rules (C3D10 4 points, C3D20 27, C3D20R 8:
//! the CalculiX manual's element descriptions). On the symmetry plane y = 0 f_y also carries
//! the plane's reaction; the contact's own ∫ N_i q_y dA vanishes there (q_y is odd in y), so f_y
//! is set to 0 on that plane.
//!
//! The corner values. With f_i = ∫ N_i t dA at the nodes of the quadratic faces, a corner's
//! linear hat on its faces is L_c = N_c + ½ Σ_m N_m over the midside nodes m of the faces'
//! edges at c (on the 6-node triangle and on the 8-node quadrangle alike: for the serendipity
//! quadrangle N_c + ½ (N_m1 + N_m2) = ¼ (1 ± ξ)(1 ± η)), so ∫ L_c t dA = f_c + ½ Σ_m f_m
//! exactly. The read-back field is linear on the corners' triangles, t_h = Σ_c t_c L_c, and its
//! measures take its hat averages ∫ L_c t_h dA / ∫ L_c dA ([`spherecontact_solvers::fit::recovery`]), as for
//! fem-3d's multipliers; so the corner values are those whose hats carry the recovered forces,
//! M t = F with the hats' mass matrix M_ck = ∫ L_c L_k dA (on a triangle T, |T| (1 + δ_ck)/12,
//! the plane's areas as the measures take them): then the hat averages are F_c / ∫ L_c dA and the
//! integral of the field is Σ F. No extrapolation; the forces sum to the reaction. q_y is odd in
//! y, so its corner values on y = 0 are 0 (the mirrored map's values there), the others solved
//! with them fixed.
//!
//! Precision: the `.frd` prints the displacements with 6 digits, and that is all the recovery
//! loses: the maps' P and Q against the far face's reactions, −7.5e-7 and −6.4e-6 on
//! `cases/ccx-3d.toml` (C3D10), 7.3e-6 of P on `cases-heavy/ccx-3d-hex20.toml` (C3D20R); every
//! run checks it ([`super::solid_read::SolidRun::map_mismatch`]).

use std::collections::{HashMap, HashSet};

use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;

use super::body::{Body, Corners};
use super::hex20;
use super::results::DisplacementBlock;
use spherecontact_model::calculix_settings::Element;
use spherecontact_model::quadrature;
use spherecontact_solvers::fem::element::internal_force::{internal_forces, GradientPoint};
use spherecontact_solvers::fem::element::tet10;
use spherecontact_solvers::fem::element::tri6::Lame;
use spherecontact_solvers::fem::factor::{Factor, Ordering};

/// What recovers the corner forces of one deck's run at every step: the elements at the slave
/// faces with their rules, and how the face nodes' forces gather at the corners.
pub struct ForceRecovery {
    /// The elements with a node on a slave face: their node ids and integration points.
    elements: Vec<(Vec<usize>, Vec<GradientPoint>)>,
    /// The slave faces' nodes on the symmetry plane y = 0.
    on_plane: HashSet<usize>,
    /// Each corner's node and the midside nodes of its faces' edges.
    corners: Vec<(usize, Vec<usize>)>,
    /// The material (CalculiX's E and ν).
    lame: Lame,
    /// The hats' mass matrix, factored: for p and q_x, and for q_y with its corners on y = 0
    /// fixed (their rows and columns the identity's).
    mass: [Factor; 2],
    /// The corners on y = 0 (indices of the corners).
    plane_corners: Vec<usize>,
}

impl ForceRecovery {
    /// The recovery for the slave `faces` of `mesh` (each face's nodes, corners first, then the
    /// midside nodes of the edges 1–2, 2–3, …), integrated as `element`, read at the
    /// `corners` (the read-back points).
    pub fn try_new(
        mesh: &Body,
        element: Element,
        lame: Lame,
        faces: &[Vec<usize>],
        corners: &Corners,
    ) -> Result<Self, String> {
        let face_nodes = nodes_of(faces);
        let elements = elements_at(mesh, &face_nodes)
            .into_iter()
            .map(|e| Ok((native(mesh, e).to_vec(), integration(mesh, element, e)?)))
            .collect::<Result<_, String>>()?;
        let on_plane: HashSet<usize> = mesh
            .symmetry_nodes()
            .into_iter()
            .filter(|n| face_nodes.contains(n))
            .collect();
        let mut beside: HashMap<usize, HashSet<usize>> = HashMap::new();
        let count = mesh.face_corner_count();
        for face in faces {
            for (k, &m) in face[count..].iter().enumerate() {
                for c in [face[k], face[(k + 1) % count]] {
                    beside.entry(c).or_default().insert(m);
                }
            }
        }
        let plane_corners: Vec<usize> = (0..corners.nodes.len())
            .filter(|&j| on_plane.contains(&corners.nodes[j]))
            .collect();
        let mass = [mass_factor(corners, &[])?, mass_factor(corners, &plane_corners)?];
        let corners = corners
            .nodes
            .iter()
            .map(|&c| {
                let mut midsides: Vec<usize> = beside.get(&c).into_iter().flatten().copied().collect();
                midsides.sort_unstable();
                (c, midsides)
            })
            .collect();
        Ok(Self {
            elements,
            on_plane,
            corners,
            lame,
            mass,
            plane_corners,
        })
    }

    /// The corner values (p, q_x, q_y) of the field whose hats carry the corner `forces`
    /// [N]: p from f_z, q from f_x and f_y, as forces per area [Pa] (module doc); the signs are
    /// the caller's.
    pub fn hat_values(&self, forces: &[[f64; 3]]) -> [Vec<f64>; 3] {
        let n = forces.len();
        let mut symmetric = Mat::<f64>::from_fn(n, 2, |j, k| forces[j][[2, 0][k]]);
        self.mass[0].solve_in_place(symmetric.as_mut());
        let mut odd = Mat::<f64>::from_fn(n, 1, |j, _| forces[j][1]);
        for &j in &self.plane_corners {
            odd[(j, 0)] = 0.0;
        }
        self.mass[1].solve_in_place(odd.as_mut());
        [
            symmetric.col(0).iter().copied().collect(),
            symmetric.col(1).iter().copied().collect(),
            odd.col(0).iter().copied().collect(),
        ]
    }

    /// The hat integrals ∫ L_c t dA at the corners [N], in the order given to
    /// [`ForceRecovery::try_new`]: the traction t on sphere 1, from the displacements
    /// [mm] of one step (node number = mesh id + 1); `step` names the step in errors.
    pub fn corner_forces(&self, u: &DisplacementBlock, step: usize) -> Result<Vec<[f64; 3]>, String> {
        let mut f: HashMap<usize, [f64; 3]> = HashMap::new();
        for (nodes, points) in &self.elements {
            let ue = nodes
                .iter()
                .map(|&n| {
                    u.values.get(&(n as u64 + 1)).map(|v| v.map(|x| 1e-3 * x)).ok_or_else(|| {
                        format!("job.frd step {step}: no displacement of node {} (sphere 1, at the slave faces)", n + 1)
                    })
                })
                .collect::<Result<Vec<_>, String>>()?;
            for (&n, fe) in nodes.iter().zip(internal_forces(points, &ue, self.lame)) {
                let sum = f.entry(n).or_default();
                for (s, v) in sum.iter_mut().zip(fe) {
                    *s += v;
                }
            }
        }
        for n in &self.on_plane {
            if let Some(force) = f.get_mut(n) {
                force[1] = 0.0;
            }
        }
        let at = |n: &usize| f.get(n).copied().unwrap_or_default();
        Ok(self
            .corners
            .iter()
            .map(|(c, midsides)| {
                let half: [f64; 3] = midsides
                    .iter()
                    .map(at)
                    .fold([0.0; 3], |s, m| std::array::from_fn(|a| s[a] + m[a]));
                let own = at(c);
                std::array::from_fn(|a| own[a] + 0.5 * half[a])
            })
            .collect())
    }
}

/// The distinct nodes of `faces`.
fn nodes_of(faces: &[Vec<usize>]) -> HashSet<usize> {
    faces.iter().flatten().copied().collect()
}

/// The elements of `mesh` with a node among `face_nodes`, in increasing order.
fn elements_at(mesh: &Body, face_nodes: &HashSet<usize>) -> Vec<usize> {
    (0..mesh.element_count())
        .filter(|&e| native(mesh, e).iter().any(|n| face_nodes.contains(n)))
        .collect()
}

/// The nodes of the elements with a node on one of `faces`, sorted: the nodes whose
/// displacements the recovery reads (the deck's `NREAD1`).
pub fn read_nodes(mesh: &Body, faces: &[Vec<usize>]) -> Vec<usize> {
    let mut nodes: Vec<usize> = elements_at(mesh, &nodes_of(faces))
        .into_iter()
        .flat_map(|e| native(mesh, e).to_vec())
        .collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}

/// Element `e`'s nodes in the order of its shape functions here (gmsh's for the tetrahedron,
/// [`tet10`]; CalculiX's for the brick, [`hex20`]).
fn native(mesh: &Body, e: usize) -> &[usize] {
    match mesh {
        Body::Tet10(m) => &m.tetrahedra[e],
        Body::Hex20(m) => &m.hexahedra[e],
    }
}

/// Element `e`'s integration points on CalculiX's rule for `element`.
fn integration(mesh: &Body, element: Element, e: usize) -> Result<Vec<GradientPoint>, String> {
    let folded = || format!("element {} is inverted at an integration point", e + 1);
    match (mesh, element) {
        (Body::Tet10(m), Element::Tet10) => {
            let x: tet10::Coords = m.tetrahedra[e].map(|n| m.nodes[n]);
            quadrature::tetrahedron_degree2()
                .into_iter()
                .map(|p| {
                    let mapped = tet10::map(&x, p.at).ok_or_else(folded)?;
                    Ok(GradientPoint {
                        grad: mapped.grad.to_vec(),
                        volume: p.weight * mapped.det,
                    })
                })
                .collect()
        }
        (Body::Hex20(m), Element::Hex20 | Element::Hex20r) => {
            let x = m.coords(e);
            let rule: Vec<([f64; 3], f64)> = if element == Element::Hex20 {
                hex20::gauss_points().collect()
            } else {
                hex20::reduced_gauss_points().collect()
            };
            rule.into_iter()
                .map(|(xi, w)| {
                    let (grad, det) = hex20::gradients(&x, xi).ok_or_else(folded)?;
                    Ok(GradientPoint {
                        grad: grad.to_vec(),
                        volume: w * det,
                    })
                })
                .collect()
        }
        _ => Err(format!("element {} does not fit the mesh", element.name())),
    }
}

/// The factored mass matrix of the corners' hats on their triangles, M_ck = ∫ L_c L_k dA over the
/// triangles projected on the contact plane (on a triangle T, |T| (1 + δ_ck)/12: the matrix that
/// [`spherecontact_solvers::fit::recovery::hat_averages`] applies, divided there by ∫ L_c dA), with the corners
/// `fixed` (and any corner in no triangle) held: their rows and columns the identity's.
fn mass_factor(corners: &Corners, fixed: &[usize]) -> Result<Factor, String> {
    let n = corners.nodes.len();
    let mut held = vec![true; n];
    for t in &corners.triangles {
        for &j in t {
            held[j] = false;
        }
    }
    for &j in fixed {
        held[j] = true;
    }
    let mut triplets: Vec<Triplet<usize, usize, f64>> = (0..n)
        .filter(|&j| held[j])
        .map(|j| Triplet::new(j, j, 1.0))
        .collect();
    for t in &corners.triangles {
        let area = spherecontact_model::history::triangle_area(
            t.map(|j| [corners.points[j][0], corners.points[j][1]]),
        );
        for &i in t {
            for &k in t {
                if i >= k && !held[i] && !held[k] {
                    let delta = if i == k { 2.0 } else { 1.0 };
                    triplets.push(Triplet::new(i, k, delta * area / 12.0));
                }
            }
        }
    }
    let lower = SparseColMat::try_new_from_triplets(n, n, &triplets)
        .map_err(|e| format!("the hats' mass matrix: {e}"))?;
    Factor::new(&lower, Ordering::Amd)
}
