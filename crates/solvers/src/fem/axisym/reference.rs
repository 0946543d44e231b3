//! `mdr-domain`: the reference a finite body must reproduce — Mindlin–Deresiewicz (the MDR
//! bed) in series with the compliances of the case's `[domain]`, computed on the same meshes as
//! `fem-axisym` ([`super::compliance`], [`spherecontact_reference::mdr_series`]).
//!
//! It gives P, Q, the stick radius and Hertz's c, p0 and p(r) at the local approach along any
//! path, so that a finite body's checks compare against the physics it models (the finite body)
//! and not against the half-space; the raw offset of a finite body from Hertz and MDR is then the
//! domain effect, reported beside the corrected error.

use std::time::Instant;

use serde_json::json;

use super::compliance::{BodyCompliance, FiniteBody};
use super::model::{grading, Reduction, GROWTH};
use super::solver::FemAxisym;
use crate::fem::mesh::meridian;
use spherecontact_model::history::History;
use spherecontact_model::limits::MERIDIAN_POLE;
use spherecontact_model::memory::{self, Budget};
use spherecontact_model::resolution::{self, ResolutionError};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};
use spherecontact_reference::mdr::Mdr;
use spherecontact_reference::mdr_series::{SeriesCompliance, SeriesMdr};

/// Contact radii of the compliance table, from c_max/4 to c_max, evenly in ln c: the compliance
/// is linear in ln c to 0.3 % of itself over that range (`tests/domain_compliance.rs`).
const TABLE_RADII: usize = 5;

/// The grading's growth ([`GROWTH`]) is divided by this on the compliance meshes: with
/// `fem-axisym`'s pole size c_max/40 that is level 2 of the uniform ladder (c_max/10 · 2^-k, growth / 2^k), where
/// λ has converged to 0.05 % of itself (level 2 → 3: λ_n 0.04 %, λ_t 0.02 % for the
/// hemisphere; `examples/domain_compliance.rs`). `fem-axisym`'s own mesh keeps the full growth:
/// its far field is 2.4 % off in λ_n, which is part of its discretisation error, and the
/// reference must not share it.
pub const FAR_FIELD_REFINEMENT: f64 = 4.0;

/// The reference solver: the compliances on a mesh of `fem-axisym`'s pole size (default
/// c_max/40) refined away from it ([`FAR_FIELD_REFINEMENT`]), MDR's bed of `springs` springs.
#[derive(Clone, Debug)]
pub struct MdrDomain {
    /// The resolution of the compliance meshes.
    pub mesh: FemAxisym,
    /// Springs of the MDR bed.
    pub springs: usize,
}

impl Default for MdrDomain {
    fn default() -> Self {
        Self {
            mesh: FemAxisym {
                growth: Some(GROWTH / FAR_FIELD_REFINEMENT),
                ..FemAxisym::default()
            },
            springs: Mdr::default().springs,
        }
    }
}

impl MdrDomain {
    /// Each modelled body's compliance table (one body for identical spheres, counted twice).
    pub fn body_tables(&self, scene: &Scene) -> Result<Vec<Vec<BodyCompliance>>, SolveError> {
        let settings = self.mesh.settings(scene)?;
        let c_max = scene.max_contact_radius();
        let bodies = match Reduction::of(scene) {
            Reduction::Symmetric => vec![scene.pair.body1],
            Reduction::TwoBodies => vec![scene.pair.body1, scene.pair.body2],
        };
        bodies
            .iter()
            .map(|body| {
                let mesh = meridian::graded(&grading(body, &settings, c_max)).map_err(|e| e.to_string())?;
                let tangential = !scene.is_frictionless();
                let budget = Budget::new(self.name(), c_max, settings.pole_size, memory::MERIDIAN);
                FiniteBody::new(
                    mesh,
                    body.material,
                    settings.domain.grip,
                    settings.integration,
                    tangential,
                    &budget,
                )?
                .table(c_max, TABLE_RADII)
            })
            .collect::<Result<_, String>>()
            .map_err(SolveError::Failed)
    }

    /// The compliances in series: the bodies' tables summed (twice the one for identical spheres).
    pub fn series_compliance(
        scene: &Scene,
        tables: &[Vec<BodyCompliance>],
    ) -> Result<SeriesCompliance, SolveError> {
        let count = if Reduction::of(scene) == Reduction::Symmetric {
            2.0
        } else {
            1.0
        };
        let sum = |f: &dyn Fn(&BodyCompliance) -> f64| -> Vec<f64> {
            (0..tables[0].len())
                .map(|k| count * tables.iter().map(|t| f(&t[k])).sum::<f64>())
                .collect()
        };
        SeriesCompliance::try_new(
            tables[0].iter().map(|b| b.contact_radius).collect(),
            sum(&|b| b.normal),
            sum(&|b| b.tangential.unwrap_or(0.0)),
        )
        .ok_or_else(|| SolveError::Failed("the domain's compliance table is not finite".into()))
    }
}

impl Solver for MdrDomain {
    fn name(&self) -> &'static str {
        "mdr-domain"
    }

    fn kind(&self) -> Kind {
        Kind::Analytic
    }

    fn description(&self) -> &'static str {
        "reference for finite bodies: MDR in series with the [domain]'s computed normal and tangential compliances"
    }

    /// Twice fem-axisym's set-up (the compliance meshes are refined in the far field) and MDR's
    /// bed along the path.
    fn estimated_seconds(&self, scene: &Scene) -> Option<f64> {
        let steps = scene.steps().len();
        let settings = self.mesh.settings(scene).ok()?;
        let divisions = settings.contact_radius / settings.pole_size;
        Some(
            2.0 * spherecontact_model::cost::fem_axisym(divisions, 0)
                + spherecontact_model::cost::mdr(self.springs, steps),
        )
    }

    /// The pole element size of its compliance meshes: `c/N` or a length, within
    /// [`MERIDIAN_POLE`].
    fn at_resolution(&self, scene: &Scene, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        let h = resolution::pole_size(self.name(), scene, value, MERIDIAN_POLE)?;
        let mut solver = self.clone();
        solver.mesh.pole_size = Some(h);
        Ok(Box::new(solver))
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        if scene.max_contact_radius() == 0.0 {
            // The gap never closes: no contact, no finite-body effect.
            return Mdr {
                springs: self.springs,
            }
            .solve(scene);
        }
        let start = Instant::now();
        let tables = self.body_tables(scene)?;
        let compliance = Self::series_compliance(scene, &tables)?;
        let compliance_s = start.elapsed().as_secs_f64();
        let mut history = SeriesMdr {
            springs: self.springs,
            compliance,
        }
        .history(scene);
        let meta = &mut history.metadata;
        meta.model = format!("{}; domain: {}", meta.model, scene.domain.describe());
        meta.resolution = format!(
            "{}; compliances on meshes of pole size {:.3e} m, growth {}",
            meta.resolution,
            self.mesh.settings(scene)?.pole_size,
            self.mesh.settings(scene)?.growth
        );
        meta.extra.insert("domain".into(), json!(scene.domain));
        meta.extra.insert("body_compliances".into(), json!(tables));
        meta.extra.insert("compliance_s".into(), json!(compliance_s));
        if scene.is_frictionless() {
            meta.warnings
                .push("frictionless scene: the tangential compliance is not computed (taken as 0)".into());
        }
        Ok(history)
    }
}
