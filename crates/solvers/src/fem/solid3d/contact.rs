//! The 3D model's contact problem in the shared engine's terms ([`spherecontact_contact`]).
//!
//! Multipliers: the nodal pressure p_j and traction q_j of the sub-triangulated contact rule
//! ([`super::surface`]); the force-like unknowns of the condensation are λ_j = w_j p_j, so the
//! averaged displacement per unit pressure is C_p = C' W (C' the condensed compliance,
//! W = diag(w)), self-adjoint in the work product Σ a_j x_j y_j with a_j ∝ w_j. The point weights
//! are a_j = 2 w_j: the half body y ≥ 0 is modelled, and its mirror image carries the same normal
//! force and the same Q, so the engine's resultants Σ a_j p_j and Σ a_j q_x,j are the whole
//! contact's P and Q.
//!
//! Identical spheres: one body pushed by δn/2 towards the contact plane and shifted by δt/2
//! (the engine's approach and shift); its mirror image does the same, so the gap of the pair is
//! twice this body's and the relative slip twice the slip the engine accumulates.
//!
//! Tangential components: x and y at every candidate. On the symmetry plane u_y is fixed and
//! q_y = 0 by symmetry; those y components are given a compliance of their own, uncoupled from
//! everything (the x diagonal of the same node): no shift drives them, so their multiplier stays
//! zero and they cannot slip, whatever the engine's algorithm.

use faer::Mat;

use super::model::Model;
use spherecontact_contact::{Contact, ContactError, DenseCompliance, DenseError, FrictionSet, Settings};

/// The model's contact: the engine over its dense condensed compliances (multiplied by their
/// loaded columns only, see [`spherecontact_contact::dense`]).
pub type SolidContact = Contact<DenseCompliance, DenseCompliance>;

/// Point weights a_j = 2 w_j (see the module doc).
fn weights(model: &Model) -> Vec<f64> {
    model.surface.weights.iter().map(|w| 2.0 * w).collect()
}

/// The normal compliance per unit pressure, C'_zz W.
pub fn normal(model: &Model) -> Result<DenseCompliance, DenseError> {
    let (c, w) = (&model.condensed.normal, &model.surface.weights);
    let matrix = Mat::from_fn(c.nrows(), c.ncols(), |i, k| c[(i, k)] * w[k]);
    DenseCompliance::try_new(matrix, weights(model), 1)
}

/// The tangential compliance per unit traction on (x, y) at every candidate, component-major,
/// with the elastic slip 1/(2λ) on its diagonal for a stick slope λ = `stick_slope` [Pa/m]
/// ([`spherecontact_model::stick_slope`]).
pub fn tangential(model: &Model, stick_slope: Option<f64>) -> Result<DenseCompliance, DenseError> {
    let m = model.surface.len();
    let (c, w) = (&model.condensed.tangential, &model.surface.weights);
    let index: Vec<usize> = model
        .condensed
        .tangential_unknowns
        .iter()
        .map(|&(j, a)| a * m + j)
        .collect();
    let mut matrix = Mat::<f64>::zeros(2 * m, 2 * m);
    for (p, &i) in index.iter().enumerate() {
        for (q, &k) in index.iter().enumerate() {
            matrix[(i, k)] = c[(p, q)] * w[k % m];
        }
    }
    for j in (0..m).filter(|&j| model.surface.on_symmetry[j]) {
        matrix[(m + j, m + j)] = matrix[(j, j)];
    }
    if let Some(slope) = stick_slope {
        for i in 0..2 * m {
            matrix[(i, i)] += 0.5 / slope;
        }
    }
    DenseCompliance::try_new(matrix, weights(model), 2)
}

/// Why the engine could not be set up on the model.
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// A condensed compliance is not a valid operator.
    #[error("condensed compliance: {0}")]
    Compliance(#[from] DenseError),
    /// The engine refused the operators.
    #[error(transparent)]
    Engine(#[from] ContactError),
}

/// The engine on the model, with Coulomb friction μ = `friction` when `with_friction` (the
/// tangential operator is built only then), its stick regularised by the slope `stick_slope`
/// [Pa/m] when given ([`spherecontact_model::stick_slope`]).
pub fn engine(
    model: &Model,
    friction: f64,
    with_friction: bool,
    settings: Settings,
    stick_slope: Option<f64>,
) -> Result<SolidContact, SetupError> {
    let normal = normal(model)?;
    let contact: SolidContact = Contact::new(normal, model.surface.heights(), settings)?;
    if !with_friction {
        return Ok(contact);
    }
    let tangential = tangential(model, stick_slope)?;
    Ok(contact.with_friction(tangential, FrictionSet::Disc, friction)?)
}
