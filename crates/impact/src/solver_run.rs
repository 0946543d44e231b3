//! What one solver's run over an impact sweep in one variant yields ([`SolverRun`]): each sweep
//! point's outcome, the first point's trace, the wall time, or why the solver could not run. The
//! built-in laws' runs ([`super::run`]) and the DEM codes' ([`super::code_run`]) make it; the
//! checks ([`super::judge`]), the files ([`super::files`]), the report and the run files read it.

use super::case::Variant;
use spherecontact_reference::impact::integrator::Sample;
use spherecontact_reference::impact::outcome::Outcome;

/// One solver in one variant over the sweep. A run file (`runfile` (spherecontact-verify)) carries it without
/// its trace (the sweep's outcomes are what the checks judge; the trace is `run`'s file).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct SolverRun {
    /// The solver.
    pub solver: String,
    /// The variant.
    pub variant: Variant,
    /// Each sweep point's value and outcome, or why it has none.
    pub points: Vec<(Option<f64>, Result<Outcome, String>)>,
    /// The trace of the first sweep point.
    #[serde(skip)]
    pub trace: Vec<Sample>,
    /// Wall time of the sweep [s].
    pub wall_time_s: f64,
    /// Why the solver could not run at all (a DEM code not installed): its checks are N/A.
    pub unavailable: Option<String>,
}
