//! Long runs say so before they start and show their progress while they run, on stderr.
//!
//! Before a solver runs, [`run`] prints its estimated wall time ([`Solver::estimated_seconds`],
//! a coarse cost model per solver: docs/security.md, "Memory and time bounds") when it is above
//! [`ANNOUNCE_SECONDS`]. While it runs, the path walkers report each step done ([`tick`]: the one
//! path walker `driver::walk` (this crate) for bem, mdr, fem-3d and the DEM laws; fem-axisym's and
//! mdr-domain's own loops), and a line `progress: CASE SOLVER: k/n steps (p %), t s, about
//! r s left` is printed at most every [`INTERVAL_SECONDS`] (the first after that long, so a
//! short run prints none). The lines only read the walkers' counters: results do not depend on
//! them. An impact run (`run` (spherecontact-impact)) is metered the same way in sweep points
//! (`k/n points`, [`Work::points`]); a program that runs a whole sweep (LAMMPS, YADE) is
//! [`watching`] its output folder, which the process's waiting loop asks through [`poll`].
//!
//! Where: `run`, `verify`, `compare`, `reproduce-paper` (the latter two above their bar) and
//! `impact`; `bench` times its rungs without them. When: the announcement always (one line, in a CI log
//! too), the progress lines if stderr is a terminal; the environment variable [`ENV`] changes
//! that: `off` (neither), `on` (the lines also when stderr is not a terminal), or a number of
//! seconds (on, with that interval).

use std::cell::RefCell;
use std::io::IsTerminal;
use std::time::Instant;

/// The environment variable that turns the progress lines on or off (see the module doc).
pub const ENV: &str = "SPHERECONTACT_PROGRESS";

/// A run estimated above this [s] is announced before it starts.
pub const ANNOUNCE_SECONDS: f64 = 30.0;

/// The least time between two progress lines [s], unless [`ENV`] sets another.
pub const INTERVAL_SECONDS: f64 = 5.0;

/// Whether and how often progress is shown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mode {
    /// Nothing on stderr.
    Off,
    /// The announcement of a long run only (stderr is not a terminal).
    Announce,
    /// The announcement, and a progress line at most every this many seconds.
    Every(f64),
}

impl Mode {
    /// The mode from [`ENV`]'s value (`None`: unset) and whether stderr is a terminal; an
    /// unreadable value counts as unset.
    pub fn from(value: Option<&str>, terminal: bool) -> Self {
        match value.map(str::trim) {
            Some("off") => Self::Off,
            Some("on") => Self::Every(INTERVAL_SECONDS),
            Some(text) => match text.parse::<f64>() {
                Ok(s) if s.is_finite() && s >= 0.0 => Self::Every(s),
                _ => Self::from(None, terminal),
            },
            None if terminal => Self::Every(INTERVAL_SECONDS),
            None => Self::Announce,
        }
    }

    /// The mode of this process: [`ENV`] and stderr.
    pub fn current() -> Self {
        Self::from(
            std::env::var(ENV).ok().as_deref(),
            std::io::stderr().is_terminal(),
        )
    }
}

/// What a run counts its progress in: `count` units called `unit`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Work {
    /// How many units the run goes through.
    pub count: usize,
    /// Their name in the lines (plural).
    pub unit: &'static str,
}

impl Work {
    /// The steps of a path.
    pub fn steps(count: usize) -> Self {
        Self { count, unit: "steps" }
    }

    /// The points of an impact sweep (over every variant).
    pub fn points(count: usize) -> Self {
        Self {
            count,
            unit: "points",
        }
    }
}

/// The meter of the run in progress on this thread.
struct Meter {
    label: String,
    unit: &'static str,
    interval: f64,
    /// The first step's time (the rate leaves the set-up out) and the last line's.
    first: Option<Instant>,
    last: Instant,
}

/// How a line reaches the user: stderr, or through a progress bar that owns the terminal.
type Printer = Box<dyn Fn(&str)>;

/// How far a program is ([`watching`]): the units done and in all, when more are done than at
/// the last call (`None`: no change).
pub type Watcher = Box<dyn FnMut() -> Option<(usize, usize)>>;

thread_local! {
    static METER: RefCell<Option<Meter>> = const { RefCell::new(None) };
    static PRINTER: RefCell<Option<Printer>> = const { RefCell::new(None) };
    static WATCHER: RefCell<Option<Watcher>> = const { RefCell::new(None) };
}

/// Prints `line` through this thread's printer ([`printing_through`]), else on stderr.
fn print(line: &str) {
    PRINTER.with(|cell| match cell.borrow().as_ref() {
        Some(printer) => printer(line),
        None => eprintln!("{line}"),
    });
}

/// Runs `f` with every line of this module printed by `printer` (e.g. a bar's `println`, so
/// that the lines do not break the bar it draws on the terminal).
pub fn printing_through<R>(printer: Printer, f: impl FnOnce() -> R) -> R {
    let previous = PRINTER.with(|cell| cell.borrow_mut().replace(printer));
    let result = f();
    PRINTER.with(|cell| *cell.borrow_mut() = previous);
    result
}

/// Reports `done` of `total` path steps of the run in progress on this thread (no-op when none
/// is metered, e.g. under `bench`, in tests, or on a worker thread).
pub fn tick(done: usize, total: usize) {
    METER.with(|cell| {
        if let Some(meter) = cell.borrow_mut().as_mut() {
            meter.tick(done, total);
        }
    });
}

/// Runs `f` (a program that runs many units in one process, e.g. a DEM code over a sweep) with
/// `watcher` telling [`poll`] how far it is (e.g. from the files it has written so far).
pub fn watching<R>(watcher: Watcher, f: impl FnOnce() -> R) -> R {
    let previous = WATCHER.with(|cell| cell.borrow_mut().replace(watcher));
    let result = f();
    WATCHER.with(|cell| *cell.borrow_mut() = previous);
    result
}

/// Reports the progress of the program [`watching`] on this thread (called by the loop that
/// waits for a program, `process` (spherecontact-system)): a tick when it has done more, as a
/// walker's after a step; no-op when no run is metered or watched, and the watcher is asked only
/// when a line is due.
pub fn poll() {
    METER.with(|meter| {
        let mut meter = meter.borrow_mut();
        let Some(meter) = meter.as_mut().filter(|m| m.due(Instant::now())) else {
            return;
        };
        WATCHER.with(|watcher| {
            if let Some((done, total)) = watcher.borrow_mut().as_mut().and_then(|w| w()) {
                meter.tick(done, total);
            }
        });
    });
}

impl Meter {
    /// True when a line may be printed at `now` (the interval has passed since the last).
    fn due(&self, now: Instant) -> bool {
        now.duration_since(self.last).as_secs_f64() >= self.interval
    }

    fn tick(&mut self, done: usize, total: usize) {
        let now = Instant::now();
        let first = *self.first.get_or_insert_with(|| {
            self.last = now;
            now
        });
        if !self.due(now) || done == 0 {
            return;
        }
        self.last = now;
        let elapsed = now.duration_since(first).as_secs_f64();
        let left = elapsed / done as f64 * total.saturating_sub(done) as f64;
        print(&format!(
            "progress: {}: {done}/{total} {} ({:.0} %), {}, about {} left",
            self.label,
            self.unit,
            100.0 * done as f64 / total.max(1) as f64,
            duration(elapsed),
            duration(left)
        ));
    }
}

/// Runs `f`, a run of `work` estimated at `seconds` (e.g. [`crate::solver::run_reported`], an
/// impact run), under `label` (e.g. the case and the solver): announced when its estimate is
/// long and metered (see the module doc).
pub fn metered<R>(label: &str, seconds: Option<f64>, work: Work, f: impl FnOnce() -> R) -> R {
    let mode = Mode::current();
    if mode != Mode::Off {
        if let Some(line) = announcement(label, seconds, work, mode) {
            print(&line);
        }
    }
    let Mode::Every(interval) = mode else {
        return f();
    };
    let start = Instant::now();
    let previous = METER.with(|cell| {
        cell.borrow_mut().replace(Meter {
            label: label.to_owned(),
            unit: work.unit,
            interval,
            first: None,
            last: start,
        })
    });
    let result = f();
    METER.with(|cell| *cell.borrow_mut() = previous);
    result
}

/// The line that announces a run of `work` estimated at `seconds`, when that is above
/// [`ANNOUNCE_SECONDS`].
pub fn announcement(label: &str, seconds: Option<f64>, work: Work, mode: Mode) -> Option<String> {
    let seconds = seconds.filter(|&s| s > ANNOUNCE_SECONDS)?;
    let follows = match mode {
        Mode::Every(_) => "progress follows".to_owned(),
        Mode::Off | Mode::Announce => format!("progress is shown on a terminal, or with {ENV}=on"),
    };
    Some(format!(
        "note: {label}: estimated {} for {} {} (a coarse estimate, within a factor of about 3); {follows}",
        duration(seconds),
        work.count,
        work.unit
    ))
}

/// `seconds` in words: `42 s`, `3.5 min`, `2.1 h`, `1.5 days`.
pub fn duration(seconds: f64) -> String {
    match seconds {
        s if s < 100.0 => format!("{s:.0} s"),
        s if s < 6000.0 => format!("{:.1} min", s / 60.0),
        s if s < 172_800.0 => format!("{:.1} h", s / 3600.0),
        s => format!("{:.1} days", s / 86_400.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mode_follows_the_terminal_unless_the_variable_says() {
        assert_eq!(Mode::from(None, false), Mode::Announce);
        assert_eq!(Mode::from(None, true), Mode::Every(INTERVAL_SECONDS));
        assert_eq!(Mode::from(Some("off"), true), Mode::Off);
        assert_eq!(Mode::from(Some("on"), false), Mode::Every(INTERVAL_SECONDS));
        assert_eq!(Mode::from(Some("0.5"), false), Mode::Every(0.5));
        assert_eq!(Mode::from(Some("-1"), false), Mode::Announce);
        assert_eq!(Mode::from(Some("nan"), true), Mode::Every(INTERVAL_SECONDS));
    }

    #[test]
    fn only_a_long_run_is_announced() {
        let every = Mode::Every(INTERVAL_SECONDS);
        assert_eq!(announcement("case mdr", Some(29.0), Work::steps(10), every), None);
        assert_eq!(announcement("case mdr", None, Work::steps(10), every), None);
        let line = announcement("case mdr", Some(1500.0), Work::steps(1_000_001), every).unwrap();
        assert!(
            line.contains("case mdr: estimated 25.0 min for 1000001 steps"),
            "{line}"
        );
        let quiet = announcement("case mdr", Some(1500.0), Work::steps(10), Mode::Announce).unwrap();
        assert!(quiet.contains("SPHERECONTACT_PROGRESS=on"), "{quiet}");
    }

    /// Requirement (issue 42): a long impact run is announced with its estimate in sweep points,
    /// as a path run is in steps.
    #[test]
    fn an_impact_run_is_announced_in_sweep_points() {
        let every = Mode::Every(INTERVAL_SECONDS);
        let line = announcement("sweep-200 mdr", Some(240_000.0), Work::points(400), every).unwrap();
        assert_eq!(
            line,
            "note: sweep-200 mdr: estimated 2.8 days for 400 points (a coarse estimate, within a factor \
             of about 3); progress follows"
        );
    }

    /// Requirement (issue 42): a program watched while it runs (a DEM code over a sweep) ticks
    /// the run's meter each time it has done more, in the run's unit, and not otherwise.
    #[test]
    fn a_watched_program_ticks_the_meter_when_it_advances() {
        let lines = std::rc::Rc::new(RefCell::new(Vec::<String>::new()));
        let sink = lines.clone();
        printing_through(
            Box::new(move |line| sink.borrow_mut().push(line.to_owned())),
            || {
                let meter = Meter {
                    label: "case yade-mindlin".into(),
                    unit: "points",
                    interval: 0.0,
                    first: None,
                    last: Instant::now(),
                };
                METER.with(|cell| *cell.borrow_mut() = Some(meter));
                let mut calls = 0;
                let watcher: Watcher = Box::new(move || {
                    calls += 1;
                    [None, Some((1, 2)), None, Some((2, 2))][calls - 1]
                });
                watching(watcher, || (0..4).for_each(|_| poll()));
                METER.with(|cell| *cell.borrow_mut() = None);
            },
        );
        let lines = lines.borrow();
        assert_eq!(lines.len(), 2, "{lines:?}");
        assert!(
            lines[0].starts_with("progress: case yade-mindlin: 1/2 points (50 %), "),
            "{lines:?}"
        );
        assert!(
            lines[1].starts_with("progress: case yade-mindlin: 2/2 points (100 %), "),
            "{lines:?}"
        );
    }

    #[test]
    fn durations_read_in_their_unit() {
        assert_eq!(duration(42.0), "42 s");
        assert_eq!(duration(1500.0), "25.0 min");
        assert_eq!(duration(7200.0), "2.0 h");
        assert_eq!(duration(3.0 * 86_400.0), "3.0 days");
    }
}
