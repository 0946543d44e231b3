//! fem-axisym's tangential problem: the Fourier mode n = 1 of the same meshes, condensed onto the
//! contact candidates and solved by the shared contact engine with Coulomb's law and memory.
//!
//! A shift along x of a body of revolution is the mode n = 1 (`fem::element::tri6_n1`: DOFs A,
//! B, W a node; u_x = A + B cos 2θ, u_y = B sin 2θ). Mindlin–Deresiewicz's model holds the
//! traction along x everywhere on the contact: q_r = q cos θ, q_θ = −q sin θ, which loads the A
//! DOFs alone with the ring force f_i = 2π ∫ q N_i r ds (the same ring weights as the pressure
//! in the mode n = 0), and stick holds A, the θ-mean of u_x, to the shift. So the tangential
//! compliance is the n = 1 stiffness, assembled and factored once with the far face gripped
//! rigidly (all of A, B, W fixed: a rigid shift of the far face is a rigid translation of the
//! whole body, A = const, which adds the shift itself to every surface A), condensed onto the
//! candidates' A DOFs from the factor's trailing block (the candidates ordered last). The contact engine takes it with
//! [`FrictionSet::Interval`] and the bound g_i = μ λ_i on the n = 0 nodal forces λ_i.
//!
//! Identical spheres (Dundurs β = 0) decouple exactly: p(r) from the n = 0 problem does not
//! depend on the shift. By the same symmetry as the normal problem, one sphere shifts by δt/2
//! against the contact plane's midline; two bodies add their compliances and shift by δt.
//! Dissimilar bodies couple the normal and tangential problems: not solved here.
//!
//! What it cannot show: the transverse traction q_y and a non-circular stick zone (B is free
//! and unloaded: the surface's u_y distortion is computed but no q_y resists it), which need
//! a 3D model.

use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::{Accum, Mat, Par};

use crate::fem::assembly::{self, System};
use crate::fem::element::tri6::{Integration, Lame};
use crate::fem::factor::{Factor, Plan};
use crate::fem::mesh::meridian::Mesh;
use crate::fem::ordering::{self, ContactLast, NodeOrder};
use spherecontact_model::memory::{Estimate, WORD};
use spherecontact_model::scene::{Scene, DISSIMILARITY_BETA};

/// What fem-axisym does about the tangential problem of a scene.
#[derive(Clone, Debug, PartialEq)]
pub enum Mode {
    /// The mode n = 1 is solved: Q, the stick radius and q(r) at every step.
    Solved,
    /// μ = 0 with tangential motion: Q = 0 exactly (|q| ≤ μp = 0), nothing to solve.
    Zero,
    /// A path without tangential motion: no tangential columns.
    Absent,
    /// Not solved, for this reason (dissimilar bodies): no tangential columns.
    NotApplicable(String),
}

impl Mode {
    /// The mode for `scene`.
    pub fn of(scene: &Scene) -> Self {
        if scene.path.is_normal_only() {
            return Self::Absent;
        }
        if scene.friction == 0.0 {
            return Self::Zero;
        }
        let beta = scene.pair.dundurs_beta();
        if beta.abs() > DISSIMILARITY_BETA {
            return Self::NotApplicable(format!(
                "tangential path not solved: dissimilar bodies (Dundurs β = {beta:.4}) couple the normal and \
                 tangential problems, which the uncoupled Fourier n = 1 model does not capture"
            ));
        }
        Self::Solved
    }
}

/// One body's mode n = 1: its system and factorisation (kept for the displacement fields) and
/// its condensed compliance ([`ShearPlan::build`]).
pub struct ShearBody {
    /// The assembled n = 1 system (A, B, W a node; far face and axis conditions eliminated).
    pub system: System,
    /// Its factorisation.
    pub factor: Factor,
    /// The compliance at the candidates' A DOFs [m/N]: the mean x displacement of ring i under
    /// a unit x ring force at ring j, far face held.
    pub compliance: Mat<f64>,
}

/// One body's mode n = 1 assembled and its factorisation planned, nothing factored yet.
pub struct ShearPlan {
    system: System,
    order: ContactLast,
    plan: Plan,
}

impl ShearPlan {
    /// Assembles the mode n = 1 of `mesh` with the element `integration` and plans its
    /// factorisation with the `candidates`' DOFs ordered last ([`crate::fem::ordering`]), so that
    /// the factor's trailing block L₂₂ factors their Schur complement.
    pub fn new(
        mesh: &Mesh,
        lame: Lame,
        candidates: &[usize],
        integration: Integration,
    ) -> Result<Self, String> {
        let system = assembly::assemble_fourier_one(mesh, lame, integration).map_err(|e| e.to_string())?;
        let points: Vec<[f64; 3]> = mesh.nodes.iter().map(|p| [p[0], p[1], 0.0]).collect();
        let order = ordering::contact_last(
            &ordering::node_graph(mesh.nodes.len(), &mesh.triangles),
            &points,
            &system.dofs,
            candidates,
            NodeOrder::MinimumDegree,
        )?;
        let plan = Plan::with_permutation(&system.stiffness, &order.forward)?;
        Ok(Self { system, order, plan })
    }

    /// The peak memory of the mode n = 1 of a body with `m` candidates: its system and factor,
    /// the trailing block, the solve's right-hand sides and the condensed compliance.
    pub fn estimate(&self, m: usize) -> Result<Estimate, String> {
        let mut estimate = self.plan.estimate("n = 1", &self.system.stiffness)?;
        let trailing = self.order.trailing.len();
        estimate.add_transient(
            "n = 1 trailing block and its solve",
            WORD * (trailing * trailing + trailing * m) as u64,
        );
        estimate.add_dense("n = 1 condensed compliance", m, m);
        Ok(estimate)
    }

    /// Factors and condenses onto the `m` candidates' A DOFs: the compliance of their A DOFs is
    /// Eᵀ (L₂₂ L₂₂ᵀ)⁻¹ E = ZᵀZ with Z = L₂₂⁻¹ E (E selects the A rows): one dense triangular
    /// solve of the candidates' size instead of one solve through the whole factor per
    /// candidate.
    pub fn build(self, m: usize) -> Result<ShearBody, String> {
        let Self { system, order, plan } = self;
        let factor = plan.factor(&system.stiffness)?;
        let mut z = Mat::<f64>::zeros(order.trailing.len(), m);
        let mut loaded = vec![false; m];
        for (p, &(j, a)) in order.trailing.iter().enumerate() {
            if a == 0 {
                z[(p, j)] = 1.0;
                loaded[j] = true;
            }
        }
        if loaded.contains(&false) {
            return Err("a candidate contact node lies on the far boundary: the domain is too small".into());
        }
        let l22 = factor.trailing_block(order.trailing.len());
        solve_lower_triangular_in_place(l22.as_ref(), z.as_mut(), Par::Seq);
        let mut compliance = Mat::<f64>::zeros(m, m);
        matmul(
            compliance.as_mut(),
            Accum::Replace,
            z.transpose(),
            z.as_ref(),
            1.0,
            Par::Seq,
        );
        Ok(ShearBody {
            system,
            factor,
            compliance,
        })
    }
}

/// The pair's mode n = 1: each body's, and their compliances added (one body for identical
/// spheres).
pub struct Shear {
    /// Each body's mode n = 1, in the model's order.
    pub bodies: Vec<ShearBody>,
    /// The pair's condensed compliance [m/N].
    pub compliance: Mat<f64>,
}

impl Shear {
    /// The pair's mode n = 1 from every body's.
    pub fn of(bodies: Vec<ShearBody>) -> Result<Self, String> {
        let mut compliance = bodies
            .first()
            .map(|b| b.compliance.clone())
            .ok_or("no body to condense")?;
        for b in &bodies[1..] {
            compliance += &b.compliance;
        }
        Ok(Self { bodies, compliance })
    }
}
