//! A solver's peak memory, estimated before it allocates its large arrays, against the budget
//! of [`crate::limits::MEMORY_BUDGET`].
//!
//! The FEM solvers add up what their model will hold at its peak: each sparse Cholesky factor
//! (its non-zero count is known from the symbolic factorisation, before the numeric one
//! allocates it: `fem::factor::Plan` (spherecontact-solvers)), the factorisation's workspace, the assembled
//! stiffness matrices, the dense condensed contact operators and the solves' blocks. A model
//! over the budget is refused before any factor is allocated, with the estimate part by part,
//! the budget and the resolutions that fit ([`OverBudget`]). `cargo run --release --example
//! memory_estimate` measures the estimate against the peak resident memory of a child process
//! (docs/security.md, "Memory and time bounds").

use std::io::Read;
use std::os::unix::process::ExitStatusExt;
use std::process::{Command, ExitStatus, Output, Stdio};

use crate::limits::{MEMORY_BUDGET, MERIDIAN_POLE, SOLID_POLE};
use crate::resolution::PoleLimits;

/// Bytes of an `f64` (and of a `usize` index).
pub const WORD: u64 = 8;

/// What the measured peak adds to the large arrays, as a fraction of them: a few per cent for
/// the models above 0.5 GB (fem-axisym frictional and frictionless to c_max/320, fem-3d to
/// c_max/14: `examples/memory_estimate.rs`); the small models add a few tens of MB of program
/// and history on top, which the tests leave out by measuring against a closed form's run.
pub const SLACK: f64 = 0.05;

/// The memory a solver's model will hold at its peak, part by part [bytes]: what it holds to
/// the end, and what it holds for a while (a workspace, a block of solves), of which the largest
/// counts at the peak.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Estimate {
    /// What is held to the end: (what, bytes), in the order they were added.
    pub parts: Vec<(String, u64)>,
    /// What is held for a while and freed again: (what, bytes).
    pub transient: Vec<(String, u64)>,
}

impl Estimate {
    /// Adds a part held to the end.
    pub fn add(&mut self, what: impl Into<String>, bytes: u64) {
        self.parts.push((what.into(), bytes));
    }

    /// Adds a part held for a while (only the largest such part counts at the peak).
    pub fn add_transient(&mut self, what: impl Into<String>, bytes: u64) {
        self.transient.push((what.into(), bytes));
    }

    /// Adds a dense `rows` × `cols` matrix of `f64`.
    pub fn add_dense(&mut self, what: impl Into<String>, rows: usize, cols: usize) {
        self.add(what, WORD * rows as u64 * cols as u64);
    }

    /// Adds every part of `other`.
    pub fn extend(&mut self, other: Estimate) {
        self.parts.extend(other.parts);
        self.transient.extend(other.transient);
    }

    /// The largest transient part, if any.
    fn largest_transient(&self) -> Option<&(String, u64)> {
        self.transient.iter().max_by_key(|(_, b)| *b)
    }

    /// The large arrays at the peak [bytes]: everything held, and the largest transient part.
    fn arrays(&self) -> u64 {
        let held: u64 = self.parts.iter().map(|(_, b)| b).sum();
        held + self.largest_transient().map_or(0, |(_, b)| *b)
    }

    /// The allocator's slack and the many small arrays the parts leave out [bytes]: [`SLACK`]
    /// of the large arrays.
    pub fn slack(&self) -> u64 {
        (SLACK * self.arrays() as f64) as u64
    }

    /// The peak [bytes]: the large arrays and their slack.
    pub fn total(&self) -> u64 {
        self.arrays() + self.slack()
    }
}

/// How a solver's memory grows with its resolution, to say which resolutions fit the budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sizing {
    /// The pole sizes the solver accepts.
    pub limits: PoleLimits,
    /// The estimate grows at least as (c_max/h)^exponent: 2 for a meridian mesh (the element
    /// count; the factor's fill adds a logarithm), 3 for a solid one. Scaling the estimate down
    /// by this power gives a pole size that fits (the true estimate falls faster).
    pub exponent: f64,
}

/// A meridian (axisymmetric) mesh's sizing: fem-axisym, mdr-domain.
pub const MERIDIAN: Sizing = Sizing {
    limits: MERIDIAN_POLE,
    exponent: 2.0,
};

/// A solid (3D) mesh's sizing: fem-3d.
pub const SOLID: Sizing = Sizing {
    limits: SOLID_POLE,
    exponent: 3.0,
};

/// The budget of one solver's run at one resolution ([`MEMORY_BUDGET`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Budget {
    /// The solver, as named in messages.
    pub solver: String,
    /// Its pole size as c_max / divisions.
    pub divisions: f64,
    /// How its memory grows with the resolution.
    pub sizing: Sizing,
}

impl Budget {
    /// The budget of `solver` at pole size `pole_size` on a path of largest contact radius
    /// `contact_radius`.
    pub fn new(solver: &str, contact_radius: f64, pole_size: f64, sizing: Sizing) -> Self {
        Self {
            solver: solver.to_owned(),
            divisions: contact_radius / pole_size,
            sizing,
        }
    }

    /// `Ok` when `estimate` is within the budget; else what is over.
    pub fn check(&self, estimate: &Estimate) -> Result<(), OverBudget> {
        if estimate.total() <= MEMORY_BUDGET {
            return Ok(());
        }
        Err(OverBudget {
            solver: self.solver.clone(),
            estimate: estimate.clone(),
            divisions: self.divisions,
            sizing: self.sizing,
        })
    }
}

/// A model whose estimated peak memory exceeds the budget.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}", self.message())]
pub struct OverBudget {
    /// The solver.
    pub solver: String,
    /// The estimate.
    pub estimate: Estimate,
    /// Its pole size as c_max / divisions.
    pub divisions: f64,
    /// How its memory grows with the resolution.
    pub sizing: Sizing,
}

impl OverBudget {
    /// The finest pole size c_max / N that fits the budget by the sizing's power law.
    pub fn finest_fitting(&self) -> f64 {
        let ratio = MEMORY_BUDGET as f64 / self.estimate.total() as f64;
        (self.divisions * ratio.powf(1.0 / self.sizing.exponent)).floor()
    }

    fn message(&self) -> String {
        let parts: Vec<String> = self
            .estimate
            .parts
            .iter()
            .chain(self.estimate.largest_transient())
            .filter(|(_, b)| *b >= MEMORY_BUDGET / 100)
            .map(|(what, b)| format!("{what} {}", gigabytes(*b)))
            .chain([format!("slack {}", gigabytes(self.estimate.slack()))])
            .collect();
        let limits = self.sizing.limits;
        let fit = self.finest_fitting();
        let advice = if fit >= limits.coarsest {
            format!(
                "for this case, resolutions from about c_max/{fit:.0} to c_max/{} fit",
                limits.coarsest
            )
        } else {
            "no resolution of this case fits".to_owned()
        };
        format!(
            "{} at pole size c_max/{:.0}: estimated peak memory {} ({}) exceeds the budget of {} per solver \
             (limits::MEMORY_BUDGET); refused before allocating; {advice} (accepted range c_max/{} to c_max/{})",
            self.solver,
            self.divisions,
            gigabytes(self.estimate.total()),
            parts.join(", "),
            gigabytes(MEMORY_BUDGET),
            limits.finest,
            limits.coarsest
        )
    }
}

/// Runs `command` to its end, its stdout and stderr captured, and returns its output and its
/// peak resident memory [bytes] (the kernel's count of the child, `ru_maxrss` of `wait4`): how
/// the estimates are measured (`examples/memory_estimate.rs`, `tests/hostile_bounded.rs`).
pub fn run_measured(command: &mut Command) -> std::io::Result<(Output, u64)> {
    let mut child = command.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn()?;
    let drain = |pipe: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            if let Some(mut pipe) = pipe {
                // A read error leaves what was read: the output is for messages only.
                let _ = pipe.read_to_end(&mut bytes);
            }
            bytes
        })
    };
    let stdout = drain(child.stdout.take().map(|p| Box::new(p) as Box<dyn Read + Send>));
    let stderr = drain(child.stderr.take().map(|p| Box::new(p) as Box<dyn Read + Send>));
    let pid = libc::pid_t::try_from(child.id()).map_err(std::io::Error::other)?;
    let mut status = 0;
    // SAFETY: an all-zero rusage is a valid value of this plain C struct.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: `pid` is our own child, not yet reaped; `status` and `usage` are valid and writable.
    if unsafe { libc::wait4(pid, &mut status, 0, &mut usage) } != pid {
        return Err(std::io::Error::last_os_error());
    }
    let joined = |h: std::thread::JoinHandle<Vec<u8>>| h.join().unwrap_or_default();
    let output = Output {
        status: ExitStatus::from_raw(status),
        stdout: joined(stdout),
        stderr: joined(stderr),
    };
    // ru_maxrss is in kibibytes on Linux.
    Ok((output, 1024 * u64::try_from(usage.ru_maxrss).unwrap_or(0)))
}

/// `bytes` in GB (10⁹ bytes), three significant figures.
pub fn gigabytes(bytes: u64) -> String {
    format!("{:.3} GB", bytes as f64 * 1e-9)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn within_the_budget_passes_and_over_it_names_everything() {
        let mut small = Estimate::default();
        small.add("factor", MEMORY_BUDGET / 2);
        let budget = |divisions: f64| Budget {
            solver: "fem-axisym".into(),
            divisions,
            sizing: MERIDIAN,
        };
        assert!(budget(40.0).check(&small).is_ok());
        let mut big = Estimate::default();
        big.add("factor n = 1", 4 * MEMORY_BUDGET);
        let error = budget(320.0).check(&big).unwrap_err();
        // 4 × the budget and 5 % slack at (c/h)² scaling: 320 / √4.2 = 156.1 divisions fit.
        assert_eq!(error.finest_fitting(), 156.0);
        let text = error.to_string();
        for needle in [
            "fem-axisym",
            "c_max/320",
            "factor n = 1",
            "exceeds the budget",
            "c_max/156",
            "slack",
            "accepted range c_max/320 to c_max/2",
        ] {
            assert!(text.contains(needle), "{needle} not in {text}");
        }
    }
}
