//! What a case asks of the solvers: the contact pair, friction, the loading path, and the facts
//! derived from them that decide how much model the case needs.

use serde::Serialize;

use crate::domain::Domain;
use crate::hertz::Hertz;
use crate::pair::ContactPair;
use crate::path::{LoadingPath, Step};

/// |β| above which the pair counts as elastically dissimilar (MD's decoupling fails).
///
/// Reason: β enters the tangential compliance through products with the normal traction;
/// at |β| < 1e-3 the neglected coupling is below 0.1 % of the tangential force.
pub const DISSIMILARITY_BETA: f64 = 1e-3;

/// c/R above which Hertz's small-strain, half-space assumptions are no longer sound.
///
/// Reason: the Hertz profile z = r²/2R is the parabolic approximation of the sphere; its error
/// in the gap grows as (c/R)², about 1 % of the gap at c/R = 0.1 (Johnson 1985, §4.2).
pub const SMALL_STRAIN_LIMIT: f64 = 0.1;

/// A validated, solver-independent description of one contact problem.
#[derive(Clone, Debug, Serialize)]
pub struct Scene {
    /// The case's name.
    pub name: String,
    /// The two bodies.
    pub pair: ContactPair,
    /// Coulomb friction coefficient μ.
    pub friction: f64,
    /// The loading path.
    pub path: LoadingPath,
    /// The finite body that finite element models mesh (`[domain]`).
    pub domain: Domain,
    /// The path positions at which solvers keep surface fields.
    pub fields: FieldPositions,
}

/// The path positions at which solvers keep surface fields (pressure, traction, stick/slip) and
/// write field files: each kept position costs memory and output (a BEM grid's fields are
/// megabytes), so a case names them and validation bounds their number
/// (`case::limits::MAX_FIELD_POSITIONS`).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FieldPositions {
    /// Every path position (what a scene built in code gets; a case file gets it only for a
    /// path of few positions).
    #[default]
    Every,
    /// These positions, sorted, without repeats.
    Listed(Vec<usize>),
}

impl FieldPositions {
    /// The positions listed in `positions` (sorted and deduplicated here).
    pub fn listed(mut positions: Vec<usize>) -> Self {
        positions.sort_unstable();
        positions.dedup();
        Self::Listed(positions)
    }
}

impl Scene {
    /// The Hertz solution of this pair.
    pub fn hertz(&self) -> Hertz {
        Hertz::of(&self.pair)
    }

    /// True when the tangential problem is void: μ = 0 or a path without tangential motion.
    pub fn is_frictionless(&self) -> bool {
        self.friction == 0.0 || self.path.is_normal_only()
    }

    /// Whether solvers keep surface fields at path position `position`: the one rule every
    /// solver consults before it records a field.
    pub fn records_fields_at(&self, position: usize) -> bool {
        match &self.fields {
            FieldPositions::Every => true,
            FieldPositions::Listed(positions) => positions.binary_search(&position).is_ok(),
        }
    }

    /// Every step of the path.
    pub fn steps(&self) -> Vec<Step> {
        self.path.steps()
    }

    /// The largest Hertz contact radius along the path [m]: what meshes, grids and spring
    /// windows are sized by (0 if the path never closes the gap).
    pub fn max_contact_radius(&self) -> f64 {
        self.hertz().contact_radius(self.path.max_approach())
    }

    /// Warnings about the assumptions that the analytic models make and this scene breaks.
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings = Vec::new();
        let beta = self.pair.dundurs_beta();
        if beta.abs() > DISSIMILARITY_BETA && !self.path.is_normal_only() {
            warnings.push(format!(
                "bodies are elastically dissimilar (Dundurs β = {beta:.4}): Mindlin–Deresiewicz and the \
                 DEM laws assume β = 0 and neglect the normal–tangential coupling"
            ));
        }
        let radius = self.pair.body1.radius.min(self.pair.body2.radius);
        let ratio = self.max_contact_radius() / radius;
        if ratio > SMALL_STRAIN_LIMIT {
            warnings.push(format!(
                "largest contact radius is {ratio:.3} of the smaller body radius (> {SMALL_STRAIN_LIMIT}): \
                 outside Hertz's small-strain, half-space validity"
            ));
        }
        warnings
    }
}
