//! The discrete model of one 3D body: assembled, factored and condensed once onto its contact
//! candidate surface.
//!
//! Identical spheres (the only reduction built): the contact plane is a plane of symmetry of the
//! pair, so one body is modelled; its far face is pushed by δn/2 towards the plane and shifted by
//! δt/2 along x, and the mirror-image body's displacements are this one's reflected. The normal
//! and tangential problems then decouple exactly (the cross compliances of the two bodies
//! cancel), and only the half y ≥ 0 is meshed (the shift lies in the plane y = 0).

use std::time::Instant;

use super::condense::{self, Condensation, Condensed};
use super::surface::{Rule, Surface};
use super::system::{self, Grip, System};
use crate::fem::assembly::Dofs;
use crate::fem::element::tri6::Lame;
use crate::fem::factor::{Factor, Ordering, Plan};
use crate::fem::mesh::solid::SolidMesh;
use crate::fem::ordering::{self, ContactLast, NodeOrder};
use spherecontact_model::memory::{Estimate, WORD};

/// The elimination order of the factorisation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Elimination {
    /// The interior's nodes ordered by `NodeOrder`, the contact DOFs last
    /// ([`ordering::contact_last`]); needed by [`Condensation::TrailingBlock`].
    ContactLast(NodeOrder),
    /// faer's minimum degree on the whole DOF graph (contact DOFs wherever it puts them).
    DofAmd,
}

/// How the model is built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Surface radius within which faces are contact candidates [m].
    pub candidate_radius: f64,
    /// The elimination order.
    pub elimination: Elimination,
    /// How the condensed compliance is computed.
    pub condensation: Condensation,
    /// How the far face is held.
    pub grip: Grip,
    /// Where the contact multipliers live.
    pub rule: Rule,
}

impl Settings {
    /// The fastest combination (measured by `examples/fem3d_timing.rs`), for `grip` and `rule`.
    pub fn fastest(candidate_radius: f64, grip: Grip, rule: Rule) -> Self {
        Self {
            candidate_radius,
            grip,
            rule,
            elimination: Elimination::ContactLast(NodeOrder::MinimumDegree),
            condensation: Condensation::TrailingBlock,
        }
    }
}

/// Wall times of the set-up [s].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Times {
    /// Assembly of K.
    pub assembly: f64,
    /// The elimination order.
    pub ordering: f64,
    /// The sparse Cholesky factorisation.
    pub factor: f64,
    /// The condensed compliance.
    pub condense: f64,
}

/// One meshed, assembled, factored and condensed body.
pub struct Model {
    /// The mesh.
    pub mesh: SolidMesh,
    /// Its material.
    pub lame: Lame,
    /// The assembled system.
    pub system: System,
    /// The factorisation of its stiffness.
    pub factor: Factor,
    /// The contact candidate surface and its rule.
    pub surface: Surface,
    /// The condensed compliances.
    pub condensed: Condensed,
    /// Set-up times.
    pub times: Times,
    /// The estimate of its peak memory, made before it was factored [bytes] ([`spherecontact_model::memory`]).
    pub memory_estimate: u64,
}

/// A body assembled and its factorisation planned (symbolic), nothing factored yet: what its
/// model will cost is known ([`Planned::estimate`]) before it is paid.
pub struct Planned {
    mesh: SolidMesh,
    lame: Lame,
    system: System,
    surface: Surface,
    order: ContactLast,
    plan: Plan,
    condensation: Condensation,
    times: Times,
}

impl Planned {
    /// The peak memory of the model: the mesh, the system and its graph, the factor and its
    /// workspace, and the condensation (trailing block and right-hand sides, or blocked solves)
    /// with its dense compliances.
    pub fn estimate(&self) -> Result<Estimate, String> {
        let mut estimate = self.plan.estimate("the", &self.system.stiffness)?;
        let nodes = self.mesh.nodes.len();
        let graph: usize = self.system.graph.iter().map(Vec::len).sum();
        estimate.add(
            "mesh and node graph",
            WORD * (3 * nodes + 10 * self.mesh.tetrahedra.len() + graph + 3 * nodes) as u64,
        );
        let (m, trailing) = (self.surface.len(), self.order.trailing.len());
        let dense = WORD * (3 * m * trailing) as u64;
        let solves = match self.condensation {
            Condensation::TrailingBlock => WORD * (trailing * trailing) as u64,
            Condensation::BlockedSolves => self.plan.solve_bytes(condense::BLOCK),
        };
        estimate.add_transient("condensation solves", dense + solves);
        estimate.add_dense("condensed compliances", m, 5 * m);
        Ok(estimate)
    }

    /// Factors and condenses: the model.
    pub fn build(self) -> Result<Model, String> {
        let memory_estimate = self.estimate()?.total();
        let mut times = self.times;
        let t2 = Instant::now();
        let factor = self.plan.factor(&self.system.stiffness)?;
        let t3 = Instant::now();
        let condensed = condense::condense(
            &self.system,
            &factor,
            &self.order,
            &self.surface,
            self.condensation,
        );
        times.factor += (t3 - t2).as_secs_f64();
        times.condense = t3.elapsed().as_secs_f64();
        Ok(Model {
            mesh: self.mesh,
            lame: self.lame,
            system: self.system,
            factor,
            surface: self.surface,
            condensed,
            times,
            memory_estimate,
        })
    }
}

impl Model {
    /// Builds the model of `mesh` (already read or generated) for material `lame`
    /// ([`Model::plan`], then [`Planned::build`]).
    pub fn build(mesh: SolidMesh, lame: Lame, settings: &Settings) -> Result<Self, String> {
        Self::plan(mesh, lame, settings)?.build()
    }

    /// Assembles the model of `mesh` for material `lame`, orders it and plans its factorisation.
    pub fn plan(mesh: SolidMesh, lame: Lame, settings: &Settings) -> Result<Planned, String> {
        let t0 = Instant::now();
        let surface = Surface::new(&mesh, settings.candidate_radius, settings.rule)?;
        let fixed = system::fixed_dofs(&mesh, settings.grip);
        if surface.nodes.iter().any(|&n| fixed[3 * n + 2]) {
            return Err(
                "a contact candidate node lies on the gripped far face: the domain is too small".into(),
            );
        }
        let system = system::assemble(&mesh, lame, Dofs::from_fixed(&fixed)).map_err(|e| e.to_string())?;
        let t1 = Instant::now();
        let how = match settings.elimination {
            Elimination::ContactLast(how) => how,
            Elimination::DofAmd if settings.condensation == Condensation::TrailingBlock => {
                return Err("the trailing-block condensation needs the contact DOFs ordered last".into())
            }
            Elimination::DofAmd => NodeOrder::MinimumDegree,
        };
        let order: ContactLast =
            ordering::contact_last(&system.graph, &mesh.nodes, &system.dofs, &surface.nodes, how)?;
        let t2 = Instant::now();
        let plan = match settings.elimination {
            Elimination::ContactLast(_) => Plan::with_permutation(&system.stiffness, &order.forward)?,
            Elimination::DofAmd => Plan::new(&system.stiffness, Ordering::Amd)?,
        };
        let times = Times {
            assembly: (t1 - t0).as_secs_f64(),
            ordering: (t2 - t1).as_secs_f64(),
            factor: t2.elapsed().as_secs_f64(),
            condense: 0.0,
        };
        Ok(Planned {
            mesh,
            lame,
            system,
            surface,
            order,
            plan,
            condensation: settings.condensation,
            times,
        })
    }

    /// Free degrees of freedom.
    pub fn dofs(&self) -> usize {
        self.system.dofs.count()
    }
}
