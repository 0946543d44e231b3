//! One sweep point placed as the DEM codes see it, the same for LAMMPS ([`super::lammps`]) and
//! YADE ([`super::yade`]) and read back against it ([`super::code_readback`]): body 1 above,
//! body 2 below on the z axis, the gap half a step of approach (first touch inside the first
//! step, interpolated). A **rigid flat is a fixed sphere of radius [`FLAT_RADIUS_FACTOR`] ×
//! R1**, not a wall: the codes' sphere–sphere contact is then the one law run in every test, and
//! LAMMPS's `fix wall/gran` is avoided (LAMMPS's `unittest/granular` found a wall model gaining
//! energy at grazing impact). One material (E', ν') for both bodies carries the pair's E* and G*
//! (`spherecontact_external::dem::lammps::equivalent_material`: a flat is a sphere of 2E and the same ν), since both
//! codes mix two materials differently from Hertz and Mindlin; against a flat, E' is raised by
//! √(R1/R*) = √(1 + 10⁻⁵) so that E*√R* and G*√R* — all Hertz's force, Mindlin's stiffness 8G*a
//! and both codes' damping depend on — are the flat's exactly. What the big sphere still costs:
//! the centres are ~R2 apart, so δ is resolved to ulp(R2) ≈ 2e-16 × 10⁵ R1 (4e-8 of δ_max in
//! tests 2 and 4); and the normal turns by x/R2 over the contact's tangential travel x (≤ 2e-5
//! rad in test 5, ≤ 2e-6 elsewhere). The step is h = t_c / `steps` (t_c Hertz's duration at the
//! point's normal speed), as the built-in laws'; docs/impact.md shows it converged.

use serde_json::json;

use super::budget::STEP_BUDGET;
use super::case::{ImpactCase, Point};
use super::closed_form::HertzImpact;
use spherecontact_model::hertz::Hertz;

/// A rigid flat is a fixed sphere this many times body 1's radius (see the module doc).
pub const FLAT_RADIUS_FACTOR: f64 = 1e5;

/// One sweep point as the codes see it: two spheres on the z axis (SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// The sweep point's index (its output is `point-<index>.txt`).
    pub index: usize,
    /// Radii; a flat's is [`FLAT_RADIUS_FACTOR`] × R1.
    pub radius: [f64; 2],
    /// Densities; a flat's is body 1's (it is fixed: its mass never enters).
    pub density: [f64; 2],
    /// Centres (x, z): body 2's at (0, −R2), body 1's half a step of approach above contact.
    pub centre: [[f64; 2]; 2],
    /// Centre velocities (v_x, v_z).
    pub velocity: [[f64; 2]; 2],
    /// Spins about the codes' y axis: −ω1 for body 1 (above), +ω2 for body 2 (below).
    pub spin_y: [f64; 2],
    /// Body 2 is fixed (the flat).
    pub fixed: bool,
    /// The one material (E', ν') of both bodies.
    pub young: f64,
    /// E' before a flat's raise: the pair's one-material E' (2 E1 for a sphere on a rigid flat),
    /// for a code that models the flat as its own wall (LIGGGHTS, [`super::liggghts`]).
    pub pair_young: f64,
    /// Its Poisson ratio ν'.
    pub poisson: f64,
    /// μ.
    pub friction: f64,
    /// The prescribed restitution (1: no damping).
    pub restitution: f64,
    /// The time step h [s].
    pub step: f64,
    /// The most steps the code may take.
    pub max_steps: usize,
    /// Half the side of the simulation box [m].
    pub half_box: f64,
}

impl Placement {
    /// The placement of `point` (sweep index `index`) of `case`.
    pub fn of(case: &ImpactCase, point: &Point, index: usize) -> Self {
        let hertz = Hertz::of(&case.pair());
        let step = HertzImpact::of(point, &hertz).duration / case.steps as f64;
        let r1 = point.body1.body.radius;
        let fixed = point.body2.is_rigid();
        let r2 = if fixed {
            FLAT_RADIUS_FACTOR * r1
        } else {
            point.body2.body.radius
        };
        let density1 = point.body1.density.unwrap_or_default();
        let (pair_young, poisson) = spherecontact_external::dem::lammps::equivalent_material(&case.pair());
        // E*√R* kept: R* = R1 R2 / (R1 + R2) is the flat's R1 only as R2 → ∞.
        let young = if fixed {
            pair_young * ((r1 + r2) / r2).sqrt()
        } else {
            pair_young
        };
        let gap = 0.5 * point.approach_speed() * step;
        let max_steps = STEP_BUDGET * case.steps + 2;
        let speed = |b: &super::case::ImpactBody| b.velocity[0].hypot(b.velocity[1]);
        let travel = (speed(&point.body1) + speed(&point.body2)) * step * max_steps as f64;
        Self {
            index,
            radius: [r1, r2],
            density: [density1, point.body2.density.unwrap_or(density1)],
            centre: [[0.0, r1 + gap], [0.0, -r2]],
            velocity: [point.body1.velocity, point.body2.velocity],
            spin_y: [-point.body1.spin, point.body2.spin],
            fixed,
            young,
            pair_young,
            poisson,
            friction: case.friction,
            restitution: point.restitution,
            step,
            max_steps,
            half_box: 2.0 * (r1 + r2) + travel,
        }
    }
}

/// The points file's name in the run folder.
pub const POINTS: &str = "points.json";

/// The points file for `placements`: every field of each, as JSON, which the YADE and Kratos
/// scripts read (numbers only: no case text reaches a script).
pub fn points_file(placements: &[Placement]) -> String {
    let points: Vec<serde_json::Value> = placements
        .iter()
        .map(|p| {
            json!({
                "index": p.index,
                "radius": p.radius,
                "density": p.density,
                "centre": p.centre,
                "velocity": p.velocity,
                "spin_y": p.spin_y,
                "fixed": p.fixed,
                "young": p.young,
                "poisson": p.poisson,
                "friction": p.friction,
                "restitution": p.restitution,
                "step": p.step,
                "max_steps": p.max_steps,
            })
        })
        .collect();
    serde_json::Value::Array(points).to_string()
}
