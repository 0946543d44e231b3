//! An impact case's checks under non-regression baselines, as a path case's: each check's value at every sweep point (a value's step is the point's
//! index), each solver's version, resolution (steps and springs) and wall time over its variants.

use std::collections::BTreeMap;

use crate::{baseline::two_digits, baseline::Baselined, baseline::Judgement, baseline::SolverRecord};
use spherecontact_check::{Drift, Verdict};
use spherecontact_impact::ImpactRun;
use spherecontact_reference::impact::problem::REFERENCE;

/// What sets `solver`'s numbers in `run` besides the case: the step (and MDR's springs).
fn resolution_of(run: &ImpactRun, solver: &str) -> String {
    let steps = format!("{} steps per Hertz contact duration", run.case.steps);
    if solver == REFERENCE {
        format!("{steps}, {} springs", run.case.springs)
    } else {
        steps
    }
}

impl Baselined for ImpactRun {
    fn case_name(&self) -> &str {
        &self.case.name
    }

    fn solver_records(&self) -> BTreeMap<String, SolverRecord> {
        let mut records: BTreeMap<String, SolverRecord> = BTreeMap::new();
        for run in &self.runs {
            let record = records.entry(run.solver.clone()).or_insert_with(|| SolverRecord {
                version: env!("CARGO_PKG_VERSION").to_owned(),
                resolution: resolution_of(self, &run.solver),
                wall_s: 0.0,
            });
            record.wall_s += run.wall_time_s;
        }
        for record in records.values_mut() {
            record.wall_s = two_digits(record.wall_s);
        }
        records
    }

    fn resolution(&self, solver: &str) -> Option<String> {
        self.runs
            .iter()
            .any(|r| r.solver == solver)
            .then(|| resolution_of(self, solver))
    }

    fn judgements(&self) -> Vec<Judgement> {
        self.outcomes
            .iter()
            .filter_map(|o| {
                Some(Judgement {
                    index: self.case.checks.iter().position(|c| *c == o.check)?,
                    key: o.check.key(),
                    solvers: o.check.solvers().cloned().collect(),
                    values: o.judged.clone(),
                    verdict: o.verdict,
                })
            })
            .collect()
    }

    fn unit(&self) -> &'static str {
        "sweep point"
    }

    fn mark(&mut self, check: usize, drift: Drift, verdict: Verdict) {
        if let Some(outcome) = self.outcomes.get_mut(check) {
            outcome.drift = Some(drift);
            outcome.verdict = verdict;
        }
    }
}
