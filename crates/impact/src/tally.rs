//! Where one variant's sweep stands in its solver's metered run ([`Tally`]), so that the
//! built-in laws' runs ([`super::run`]) and the DEM codes' sweeps ([`super::code_run`]) report
//! their points done to the one meter of the run ([`spherecontact_model::progress`]).

use spherecontact_model::progress;

/// Where one variant's sweep stands in its solver's metered run ([`super::run::run_case`]): the
/// points of the variants run before it, and the points of the whole run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Tally {
    before: usize,
    total: usize,
}

impl Tally {
    /// A sweep of `points` metered alone.
    pub(super) fn alone(points: usize) -> Self {
        Self {
            before: 0,
            total: points,
        }
    }

    /// The sweep after `before` points of a run of `total` points.
    pub(super) fn after(before: usize, total: usize) -> Self {
        Self { before, total }
    }

    /// The run's points done and in all, with `done` points of this sweep done.
    pub(super) fn at(self, done: usize) -> (usize, usize) {
        (self.before + done, self.total)
    }

    /// Reports `done` points of this sweep done to the run's meter.
    pub(super) fn tick(self, done: usize) {
        let (done, total) = self.at(done);
        progress::tick(done, total);
    }
}
