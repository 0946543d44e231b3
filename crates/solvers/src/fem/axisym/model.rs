//! The discrete model of a scene: one or two meshed bodies, each assembled and factored once,
//! condensed onto common candidate contact nodes.
//!
//! Reduction (chosen from the scene, recorded in the history):
//! - identical spheres: by symmetry the contact plane stays flat and frictionless, so one sphere
//!   is pushed by δn/2 against a rigid plane;
//! - otherwise both bodies are meshed, each in its own frame touching the plane, with their
//!   candidate nodes at the same radii; their compliances add and the approach is δn.

use std::time::Instant;

use faer::Mat;

use super::tangential::{Shear, ShearBody, ShearPlan};
use crate::fem::assembly::{self, System};
use crate::fem::condense::{condense, Condensed, BLOCK};
use crate::fem::element::tri6::{edge_weights, Integration, Lame};
use crate::fem::factor::{Factor, Ordering, Plan};
use crate::fem::mesh::meridian::{self, Grading, Mesh};
use spherecontact_contact::{Contact, DenseCompliance, FrictionSet, Settings as ContactSettings};
use spherecontact_model::domain::Domain;
use spherecontact_model::memory::{Budget, Estimate, MERIDIAN, WORD};
use spherecontact_model::pair::Body;
use spherecontact_model::scene::Scene;

/// How the scene was reduced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reduction {
    /// One sphere against a rigid frictionless plane at δn/2.
    Symmetric,
    /// Both bodies meshed; compliances added at common node radii.
    TwoBodies,
}

impl Reduction {
    /// The reduction a scene needs.
    pub fn of(scene: &Scene) -> Self {
        if scene.pair.is_symmetric() {
            Self::Symmetric
        } else {
            Self::TwoBodies
        }
    }

    /// In words, for the history's metadata.
    pub fn describe(self) -> &'static str {
        match self {
            Self::Symmetric => {
                "identical spheres by symmetry: one sphere against a rigid frictionless plane at δn/2"
            }
            Self::TwoBodies => "both bodies meshed, compliances added at common node radii, approach δn",
        }
    }

    /// The approach of the condensed problem at relative approach δn.
    pub fn approach(self, delta_n: f64) -> f64 {
        match self {
            Self::Symmetric => 0.5 * delta_n,
            Self::TwoBodies => delta_n,
        }
    }

    /// The shift increment of the condensed problem for a relative shift increment `delta_t`:
    /// half of it for one sphere against the symmetry plane (as the approach, [`Self::approach`]).
    pub fn shift(self, delta_t: f64) -> f64 {
        self.approach(delta_t)
    }
}

/// Mesh and solver settings derived from the scene and the user's pole size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Pole element size h0 [m].
    pub pole_size: f64,
    /// Surface radius within which nodes are contact candidates [m].
    pub candidate_radius: f64,
    /// Fill-reducing ordering.
    pub ordering: Ordering,
    /// Element integration.
    pub integration: Integration,
    /// The modelled finite body (cap height, grip).
    pub domain: Domain,
    /// Growth of the element size beyond the fine zone (default [`GROWTH`]).
    pub growth: f64,
    /// Whether the model includes the tangential problem (the Fourier mode n = 1,
    /// [`super::tangential`]).
    pub shear: bool,
    /// The path's largest contact radius c_max [m], the unit of the resolution in messages.
    pub contact_radius: f64,
}

/// Uniformly fine zone: 5 % beyond the candidate zone, so the contact edge sits in it.
const FINE_MARGIN: f64 = 1.05;
/// Growth of the element size beyond the fine zone (h = h0 + g (r − r_f)).
pub const GROWTH: f64 = 0.25;
/// Domain of a flat, in units of the largest contact radius: the far-arc offset of a
/// half-space region falls as c/D (Boussinesq), ≈ 1e-4 of P at 1000 c.
pub(super) const FLAT_DOMAIN: f64 = 1000.0;

/// One meshed, assembled, factored and condensed body.
pub struct BodyModel {
    /// The mesh.
    pub mesh: Mesh,
    /// The assembled system.
    pub system: System,
    /// The factorisation of its stiffness.
    pub factor: Factor,
    /// Its material.
    pub lame: Lame,
    /// Candidate contact nodes, by r from the pole.
    pub candidates: Vec<usize>,
    /// The condensed response at the candidates.
    pub condensed: Condensed,
    /// Wall times [s]: assembly, factorisation, condensation, and the whole mode n = 1 (0
    /// when not solved).
    pub times: [f64; 4],
}

/// One body assembled in the modes it needs, its factorisations planned (symbolic), nothing
/// factored yet: what its model will cost is known ([`BodyPlan::estimate`]) before it is paid.
pub struct BodyPlan {
    mesh: Mesh,
    lame: Lame,
    system: System,
    plan: Plan,
    candidates: Vec<usize>,
    contact_dofs: Vec<usize>,
    shear: Option<ShearPlan>,
    /// Wall times [s]: the mode n = 0's assembly and symbolic factorisation, the mode n = 1's
    /// assembly, ordering and symbolic factorisation.
    times: [f64; 3],
}

impl BodyPlan {
    /// Assembles `mesh` in the mode n = 0 (and n = 1 when `settings.shear`) and plans the
    /// factorisations.
    pub fn new(mesh: Mesh, lame: Lame, settings: &Settings) -> Result<Self, String> {
        let t0 = Instant::now();
        let system = assembly::assemble(&mesh, lame, settings.integration, settings.domain.grip)
            .map_err(|e| e.to_string())?;
        let t1 = Instant::now();
        let plan = Plan::new(&system.stiffness, settings.ordering)?;
        let t2 = Instant::now();
        let candidates: Vec<usize> = mesh
            .surface_nodes()
            .into_iter()
            .filter(|&n| mesh.nodes[n][0] <= settings.candidate_radius)
            .collect();
        let contact_dofs = candidates
            .iter()
            .map(|&n| system.dofs.free(2 * n + 1))
            .collect::<Option<Vec<usize>>>()
            .ok_or("a candidate contact node lies on the far boundary: the domain is too small")?;
        let shear = settings
            .shear
            .then(|| ShearPlan::new(&mesh, lame, &candidates, settings.integration))
            .transpose()?;
        let times = [t1 - t0, t2 - t1, t2.elapsed()].map(|d| d.as_secs_f64());
        Ok(Self {
            mesh,
            lame,
            system,
            plan,
            candidates,
            contact_dofs,
            shear,
            times,
        })
    }

    /// The peak memory of this body's model: the mesh, the systems, the factors, the
    /// condensation's solves and the dense condensed operators.
    pub fn estimate(&self) -> Result<Estimate, String> {
        let mut estimate = self.plan.estimate("n = 0", &self.system.stiffness)?;
        let (nodes, triangles) = (self.mesh.nodes.len(), self.mesh.triangles.len());
        estimate.add("mesh", WORD * (2 * nodes + 6 * triangles) as u64);
        let m = self.candidates.len();
        estimate.add_transient("n = 0 condensation solves", self.plan.solve_bytes(BLOCK));
        estimate.add_dense("n = 0 condensed compliance", m, m);
        if let Some(shear) = &self.shear {
            estimate.extend(shear.estimate(m)?);
        }
        Ok(estimate)
    }

    /// Factors and condenses the planned modes: the body's model and its mode n = 1.
    pub fn build(self) -> Result<(BodyModel, Option<ShearBody>), String> {
        let t1 = Instant::now();
        let factor = self.plan.factor(&self.system.stiffness)?;
        let t2 = Instant::now();
        let condensed = condense(
            &factor,
            self.system.dofs.count(),
            &self.contact_dofs,
            &self.system.reaction,
        );
        let t3 = Instant::now();
        let m = self.candidates.len();
        let shear = self.shear.map(|s| s.build(m)).transpose()?;
        let shear_s = if shear.is_some() {
            self.times[2] + t3.elapsed().as_secs_f64()
        } else {
            0.0
        };
        let factor_s = self.times[1] + (t2 - t1).as_secs_f64();
        let times = [self.times[0], factor_s, (t3 - t2).as_secs_f64(), shear_s];
        let body = BodyModel {
            mesh: self.mesh,
            system: self.system,
            factor,
            lame: self.lame,
            candidates: self.candidates,
            condensed,
            times,
        };
        Ok((body, shear))
    }
}

impl BodyModel {
    /// Radii of the candidate nodes.
    pub fn radii(&self) -> Vec<f64> {
        self.candidates.iter().map(|&n| self.mesh.nodes[n][0]).collect()
    }

    /// Surface heights of the candidate nodes.
    pub fn heights(&self) -> Vec<f64> {
        self.candidates.iter().map(|&n| self.mesh.nodes[n][1]).collect()
    }

    /// Ring weights 2π ∫ N_i r ds of the candidate nodes on this body's surface; exactly 0 on
    /// the axis.
    ///
    /// The axis node's ring has no circumference: its weight vanishes with r on a straight pole
    /// edge, but on a curved one (gmsh's quadratic edges follow the arc, whose midside node lies
    /// R sin(θ/2)(1 − cos(θ/2)) ≈ h³/8R² off the chord's r) the quadrature leaves a residue of
    /// order h⁴/R², some 1e-17 m², of either sign. Its force divided by that would be noise
    /// (measured 4.2e12 Pa on the decks' mesh at c_max/40), so the axis node has no nodal
    /// pressure or traction of its own: the profile recovery gives it the fitted p0 and the
    /// traction its neighbour's (as for the generated mesh, whose pole edge is straight in r).
    pub fn weights(&self) -> Vec<f64> {
        let mut by_node = vec![0.0; self.mesh.nodes.len()];
        for e in &self.mesh.surface {
            let w = edge_weights(
                self.mesh.nodes[e[0]],
                self.mesh.nodes[e[1]],
                self.mesh.nodes[e[2]],
            );
            for (k, n) in e.iter().enumerate() {
                by_node[*n] += w[k];
            }
        }
        self.candidates
            .iter()
            .map(|&n| {
                if self.mesh.nodes[n][0] == 0.0 {
                    0.0
                } else {
                    by_node[n]
                }
            })
            .collect()
    }

    /// Degrees of freedom (free).
    pub fn dofs(&self) -> usize {
        self.system.dofs.count()
    }
}

/// The discrete model of a scene.
pub struct Model {
    /// The reduction.
    pub reduction: Reduction,
    /// The meshed bodies (one when symmetric).
    pub bodies: Vec<BodyModel>,
    /// The pair's condensed normal compliance at the candidates [m/N].
    pub compliance: Mat<f64>,
    /// Initial separation of the surfaces at each candidate [m].
    pub heights: Vec<f64>,
    /// Candidate radii [m].
    pub radii: Vec<f64>,
    /// Ring weights of the candidates (body 1's surface) [m²].
    pub weights: Vec<f64>,
    /// The pair's Fourier mode n = 1 (each body's factorisation, the condensed compliance at
    /// the candidates' A DOFs [m/N]), when the tangential problem is solved
    /// ([`Settings::shear`]).
    pub shear: Option<super::tangential::Shear>,
    /// The estimate of its peak memory, made before it was factored [bytes] ([`spherecontact_model::memory`]).
    pub memory_estimate: u64,
}

/// The generator's grading for `body` under `settings`: a sphere's cap (the hemisphere, or the
/// case's cap), a flat's lens of [`FLAT_DOMAIN`] contact radii.
pub fn grading(body: &Body, settings: &Settings, contact_radius: f64) -> Grading {
    let domain = if body.radius.is_finite() {
        meridian::Domain::Cap(settings.domain.height(body.radius))
    } else {
        meridian::Domain::Lens(FLAT_DOMAIN * contact_radius.max(settings.candidate_radius))
    };
    Grading {
        radius: body.radius,
        domain,
        pole_size: settings.pole_size,
        fine_radius: FINE_MARGIN * settings.candidate_radius,
        growth: settings.growth,
    }
}

impl Model {
    /// Meshes (in-crate generator) and builds the model of `scene`.
    pub fn generate(scene: &Scene, settings: &Settings) -> Result<Self, String> {
        let reduction = Reduction::of(scene);
        let c = scene.max_contact_radius();
        let mut bodies = vec![scene.pair.body1];
        if reduction == Reduction::TwoBodies {
            bodies.push(scene.pair.body2);
        }
        let meshes = bodies
            .iter()
            .map(|b| meridian::graded(&grading(b, settings, c)).map_err(|e| e.to_string()))
            .collect::<Result<Vec<_>, _>>()?;
        let lames = bodies.iter().map(|b| Lame::of(&b.material)).collect();
        Self::from_meshes(reduction, meshes, lames, settings)
    }

    /// Builds the model from given meshes (one per body of the reduction): assembles them,
    /// plans the factorisations and refuses a model whose estimated peak memory exceeds the
    /// budget ([`spherecontact_model::memory`]) before any factor is allocated; then factors and condenses.
    pub fn from_meshes(
        reduction: Reduction,
        meshes: Vec<Mesh>,
        lames: Vec<Lame>,
        settings: &Settings,
    ) -> Result<Self, String> {
        let budget = Budget::new(SOLVER, settings.contact_radius, settings.pole_size, MERIDIAN);
        budget
            .check(&assembly_estimate(&meshes, settings.shear))
            .map_err(|e| e.to_string())?;
        let plans = meshes
            .into_iter()
            .zip(lames)
            .map(|(mesh, lame)| BodyPlan::new(mesh, lame, settings))
            .collect::<Result<Vec<_>, _>>()?;
        let mut estimate = Estimate::default();
        for plan in &plans {
            estimate.extend(plan.estimate()?);
        }
        budget.check(&estimate).map_err(|e| e.to_string())?;
        let (bodies, shear): (Vec<BodyModel>, Vec<Option<ShearBody>>) = plans
            .into_iter()
            .map(BodyPlan::build)
            .collect::<Result<Vec<_>, _>>()?
            .into_iter()
            .unzip();
        let shear = shear
            .into_iter()
            .collect::<Option<Vec<_>>>()
            .map(Shear::of)
            .transpose()?;
        let radii = bodies[0].radii();
        let m = radii.len();
        let mut heights = vec![0.0; m];
        let mut compliance = Mat::<f64>::zeros(m, m);
        for body in &bodies {
            let r = body.radii();
            let same = r.len() == m
                && r.iter()
                    .zip(&radii)
                    .all(|(a, b)| (a - b).abs() <= 1e-9 * (a.abs() + b.abs()));
            if !same {
                return Err("the bodies' candidate contact nodes are not at the same radii".into());
            }
            heights.iter_mut().zip(body.heights()).for_each(|(h, b)| *h += b);
            compliance += &body.condensed.compliance;
        }
        let weights = bodies[0].weights();
        Ok(Self {
            reduction,
            compliance,
            heights,
            bodies,
            radii,
            weights,
            shear,
            memory_estimate: estimate.total(),
        })
    }
}

/// The solver whose model this is, as named in messages.
const SOLVER: &str = "fem-axisym";

/// The peak memory of assembling `meshes` (the mode n = 1 too when `shear`), known from the
/// meshes alone: the element matrices' triplets of the largest mode and their conversion to a
/// sparse matrix (about as much again), over the meshes. Checked before anything is assembled.
pub fn assembly_estimate(meshes: &[Mesh], shear: bool) -> Estimate {
    let mut estimate = Estimate::default();
    let components: usize = if shear { 3 } else { 2 };
    let size = 6 * components;
    let triplet = 3 * WORD;
    for mesh in meshes {
        estimate.add(
            "mesh",
            WORD * (2 * mesh.nodes.len() + 6 * mesh.triangles.len()) as u64,
        );
        let triplets = (mesh.triangles.len() * size * (size + 1) / 2) as u64;
        estimate.add_transient("assembly triplets and their conversion", 2 * triplet * triplets);
    }
    estimate
}

/// The contact of a model on the shared engine: normal (n = 0) and, when the model has its
/// shear compliance, tangential (n = 1, an interval friction set).
pub type AxisymContact = Contact<DenseCompliance, DenseCompliance>;

impl Model {
    /// A fresh contact on the candidates (the engine picks the dense active-set solver for these
    /// few hundred nodes), with Coulomb friction μ = `friction` when the model has its shear
    /// compliance; `Err` when a condensed compliance is not a valid one.
    pub fn contact(&self, friction: f64) -> Result<AxisymContact, String> {
        let compliance = DenseCompliance::scalar(self.compliance.clone()).map_err(|e| e.to_string())?;
        let contact = Contact::new(compliance, self.heights.clone(), ContactSettings::default())
            .map_err(|e| e.to_string())?;
        match &self.shear {
            None => Ok(contact),
            Some(shear) => {
                let shear = DenseCompliance::scalar(shear.compliance.clone()).map_err(|e| e.to_string())?;
                contact
                    .with_friction(shear, FrictionSet::Interval, friction)
                    .map_err(|e| e.to_string())
            }
        }
    }
}
