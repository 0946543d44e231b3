//! # spherecontact
//!
//! The whole harness as one library: every layer crate of the workspace, re-exported under the
//! names the code and the tests use (`spherecontact::pair`, `spherecontact::case`, …). Each
//! layer is a crate of its own (README, "The map"); depend on the one you need — the exact
//! references alone are `spherecontact-reference` — or on this one for all of them.

pub use spherecontact_case as case;
pub use spherecontact_case::registry;
pub use spherecontact_check as check;
pub use spherecontact_check::judged;
pub use spherecontact_contact as contact;
pub use spherecontact_external as external;
pub use spherecontact_external::{calculix, dem, exchange, kratos};
pub use spherecontact_impact as impact;
pub use spherecontact_model::*;
pub use spherecontact_reference as analytic;
pub use spherecontact_report as report;
pub use spherecontact_report::conclusion;
pub use spherecontact_solvers::*;
pub use spherecontact_system::*;
pub use spherecontact_verify as verify;
pub use spherecontact_verify::{baseline, bench, merge, plan, runfile, schedule, slurm};
