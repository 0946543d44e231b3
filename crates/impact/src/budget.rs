//! The step and trace budgets of one impact, the same for every solver: the built-in laws
//! through the integrator ([`super::run`]) and the DEM codes over their sweeps
//! ([`super::code_run`], the codes' step limit set in [`super::placement`]).

/// The most steps a contact may take, as a multiple of the steps per Hertz contact duration:
/// an elastic contact lasts one duration, a damped one less (its rebound is faster).
pub(super) const STEP_BUDGET: usize = 4;

/// At most this many samples in the trace of the first sweep point.
pub(super) const TRACE_SAMPLES: usize = 2000;
