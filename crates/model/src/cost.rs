//! Coarse wall-time models of the in-crate solvers, to announce a long run before it starts
//! ([`crate::progress`]): a set-up that grows with the resolution and a cost an increment.
//!
//! Each constant was measured on one core of the shared development machine (release build,
//! `cargo run --release --example memory_estimate -- --time`, docs/security.md "Memory and time
//! bounds") and is stated as the cost of the unit it multiplies. The models leave out what varies
//! from path to path (the contact's size at each step, the iterations an increment takes, open
//! gaps), so they are coarse: within a factor of about 3 of the measured times on the shipped
//! paths. That is enough to tell seconds from hours.

/// MDR: one spring over one step [s] (the bed is walked spring by spring at every step):
/// measured 1.05e-9 (10⁵ springs over the paper path's 1101 steps); issue 27 measured about
/// 25 min for 10⁶ springs over 10⁶ increments (1.5e-9).
pub const MDR_SPRING_STEP: f64 = 1.2e-9;

/// BEM: one panel over one step, per binary digit of the panel count [s] (FFT products on the
/// doubled grid, a few tens of them an increment). Measured 3.7e-8 on the paper path's small
/// increments at 128² and 1.6e-7 on large ones from rest at 512² (issue 27: 0.4 s an increment
/// at 512², 8.5e-8).
pub const BEM_PANEL_STEP: f64 = 6.0e-8;

/// fem-axisym's set-up per (c_max/h)² ln(c_max/h) [s]: assembly and factorisation (modes n = 0
/// and 1) of a meridian mesh whose element count grows as (c_max/h)², the factor's fill as its
/// logarithm more (about 11 s at c_max/160 on the paper's spheres).
pub const AXISYM_SETUP: f64 = 8.0e-5;

/// fem-axisym: one candidate pair over one step [s] (the dense contact solve on the candidates,
/// about 2.5 c_max/h of them).
pub const AXISYM_CANDIDATE_PAIR_STEP: f64 = 2.0e-8;

/// fem-3d's set-up per (c_max/h)⁴ [s] (the factorisation's fill of a tetrahedral mesh: 30 s at
/// c_max/14), and its fixed part [s] (gmsh's start, the far field).
pub const SOLID_SETUP: f64 = 1.0e-3;
/// See [`SOLID_SETUP`].
pub const SOLID_FIXED: f64 = 0.5;

/// fem-3d: one candidate pair over one step [s] (candidates grow as (c_max/h)²).
pub const SOLID_CANDIDATE_PAIR_STEP: f64 = 1.0e-9;

/// An incremental law (the DEM laws, Cattaneo–Mindlin) over one step [s].
pub const LAW_STEP: f64 = 2.0e-7;

/// MDR with `springs` springs over `steps` steps [s].
pub fn mdr(springs: usize, steps: usize) -> f64 {
    MDR_SPRING_STEP * springs as f64 * steps as f64
}

/// The BEM on `grid`² panels over `steps` steps [s].
pub fn bem(grid: usize, steps: usize) -> f64 {
    let panels = (grid * grid).max(2) as f64;
    BEM_PANEL_STEP * panels * panels.log2() * steps as f64
}

/// fem-axisym at pole size c_max / `divisions` over `steps` steps [s].
pub fn fem_axisym(divisions: f64, steps: usize) -> f64 {
    let candidates = 2.5 * divisions;
    AXISYM_SETUP * divisions.powi(2) * divisions.max(1.0).ln()
        + AXISYM_CANDIDATE_PAIR_STEP * candidates.powi(2) * steps as f64
}

/// fem-3d at pole size c_max / `divisions` over `steps` steps [s].
pub fn fem_3d(divisions: f64, steps: usize) -> f64 {
    let candidates = 3.0 * divisions.powi(2);
    SOLID_FIXED
        + SOLID_SETUP * divisions.powi(4)
        + SOLID_CANDIDATE_PAIR_STEP * candidates.powi(2) * steps as f64
}

/// An incremental law over `steps` steps [s].
pub fn law(steps: usize) -> f64 {
    LAW_STEP * steps as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 27 measured these runs; the models hold them within their stated factor of 3.
    #[test]
    fn the_models_hold_the_measured_runs_within_a_factor_of_three() {
        let within = |model: f64, measured: f64| (measured / 3.0..=3.0 * measured).contains(&model);
        // MDR, 10⁶ springs over 10⁶ increments: about 25 min.
        assert!(within(mdr(1_000_000, 1_000_001), 1500.0));
        // BEM at 512²: about 0.4 s an increment.
        assert!(within(bem(512, 1), 0.4));
        // fem-axisym, paper path (1101 steps) at c_max/160: 14.8 s of CPU
        // (examples/memory_estimate.rs).
        assert!(within(fem_axisym(160.0, 1101), 14.8));
        // fem-3d, paper path at c_max/14: 34 s of CPU.
        assert!(within(fem_3d(14.0, 1101), 34.0));
    }
}
