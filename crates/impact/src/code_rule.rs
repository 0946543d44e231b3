//! Each DEM code's own rule for a damped impact, so that its comparison with the exact reference
//! is fair: a prescribed restitution has no exact reference until the damping law and the
//! normal force that bounds friction are chosen, and each code chooses its own.
//!
//! Every law here is Tsuji's form, a viscous normal force c δn^{1/4} δ̇ added to Hertz's and the
//! total clamped at zero; they differ in c and in the friction bound:
//!
//! | rule | c | friction bounded by | reference |
//! |---|---|---|---|
//! | harness (LIGGGHTS' Tsuji) | 2 √(5/6) \|β\| √(2E*√R* m*), β = ln e / √(ln² e + π²) | elastic force | `mdr` |
//! | LIGGGHTS `coefficientRestitution` (+ `limitForce on`) | the harness's | total force | `mdr-liggghts` |
//! | LAMMPS `damping tsuji` (+ `limit_damping`) | α(e) √(4/3 E*√R* m*), α Tsuji's polynomial | total force | `mdr-lammps` |
//! | YADE `Ip2_FrictMat_FrictMat_MindlinPhys(en = e)`, Kratos `COEFFICIENT_OF_RESTITUTION = e` | 2 β_T(e) √(2E*√R* m*), β_T Thornton et al.'s fit | total force | `mdr-yade` |
//!
//! Sources (the installed builds): LAMMPS 29 Sep 2021, `pair_granular.cpp` — `coeff()` turns the
//! restitution into α = 1.2728 − 4.2783e + 11.087e² − 22.348e³ + 27.467e⁴ − 18.022e⁵ + 4.8218e⁶,
//! `compute()` damps with α √(m* k), k = 4/3 E* a, a = √(R*δ), clamps the total at zero under
//! `limit_damping` and caps the tangential force at μ |F_total|. YADE 2023.02a, `HertzMindlin.cpp`
//! — `en` gives β from Thornton, Cummins & Cleary (2013) eqs. B6–B7 (β(0.5) = 0.23302485768 read
//! back from YADE), the law damps with 2β √(m̄ k_n), k_n = 3/2 k_no √δ = 2E*√(R*δ), clamps the
//! total at zero and caps the shear force at μ |F_total|. YADE's shear damping (β_s = β_n unless
//! `es` is given) is switched off (`es = 1`), as LAMMPS's tangential damping is (0): both codes
//! are compared on their normal damping only, the MDR reference having none tangentially.
//! LIGGGHTS 3.8.0, `normal_model_hertz.h` — β from the restitution (`global_properties.cpp:539`),
//! γ_n = 2 √(5/6) β √(S_n m*), S_n = 2E*√(R*δ) (:231, :237): the harness's coefficient; the total
//! clamped at zero only under `limitForce on` (:258, off by default: set here), the Coulomb cap
//! μ |F_n| of the total (`tangential_model_history.h:175`); its tangential damping γ_t (on by
//! default, :238) is switched off (`tangential_damping off`), as the others'.
//! Kratos 10.4.4 takes the same β: its `DEM_D_Hertz_viscous_Coulomb` is a "Hertz" law, for which
//! the DEMApplication's material set-up computes `DAMPING_GAMMA = GammaForHertzThornton(e)`, and
//! damps with 2γ √(m* K_n), K_n = 2E*√(R*δ), the total clamped at zero and the shear capped at
//! μ times it (`DEM_D_Hertz_viscous_Coulomb_CL.cpp`): YADE's rule, so `mdr-yade` is its reference
//! too. Unlike the others it damps the tangential spring as well (2γ √(m* K_t), which no
//! option turns off), which the reference has not: at e < 1 its tangential outcomes carry that
//! difference (docs/impact.md); at e = 1 (the elastic variants) none is damped.

use super::case::{LAMMPS_REFERENCE, LIGGGHTS_REFERENCE, REFERENCE, YADE_REFERENCE};
use spherecontact_external::dem::kratos::KratosLaw;
use spherecontact_external::dem::lammps::TangentialModel;
use spherecontact_external::dem::liggghts;
use spherecontact_external::dem::yade::YadeLaw;
use spherecontact_model::hertz::Hertz;
use spherecontact_reference::impact::law::{Damping, FrictionBound};

/// Whose damping law and friction bound an impact runs under.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// The harness's (the built-in laws and `mdr`).
    Harness,
    /// LAMMPS's (`lammps-*` and `mdr-lammps`).
    Lammps,
    /// YADE's (`yade-mindlin` and `mdr-yade`), which is Kratos' too (`kratos-*`).
    Yade,
    /// LIGGGHTS' (`liggghts-hertz-history` and `mdr-liggghts`).
    Liggghts,
}

impl Rule {
    /// The rule `solver` runs under.
    pub fn of(solver: &str) -> Self {
        if solver == LAMMPS_REFERENCE || TangentialModel::ALL.iter().any(|m| m.solver_name() == solver) {
            Rule::Lammps
        } else if solver == YADE_REFERENCE
            || solver == YadeLaw::Mindlin.solver_name()
            || KratosLaw::ALL.iter().any(|law| law.solver_name() == solver)
        {
            Rule::Yade
        } else if solver == LIGGGHTS_REFERENCE || solver == liggghts::NAME {
            Rule::Liggghts
        } else {
            Rule::Harness
        }
    }

    /// The exact reference under this rule.
    pub fn reference(self) -> &'static str {
        match self {
            Rule::Harness => REFERENCE,
            Rule::Lammps => LAMMPS_REFERENCE,
            Rule::Yade => YADE_REFERENCE,
            Rule::Liggghts => LIGGGHTS_REFERENCE,
        }
    }

    /// The damping of restitution `restitution` for effective mass `mass` and `hertz`; none at 1.
    pub fn damping(self, restitution: f64, mass: f64, hertz: &Hertz) -> Option<Damping> {
        if restitution >= 1.0 {
            return None;
        }
        let scale = hertz.effective_modulus * hertz.effective_radius.sqrt() * mass;
        Some(match self {
            Rule::Harness => Damping::new(restitution, mass, hertz),
            Rule::Lammps => Damping::with_coefficient(
                tsuji_alpha(restitution) * (4.0 / 3.0 * scale).sqrt(),
                FrictionBound::Total,
            ),
            Rule::Yade => Damping::with_coefficient(
                2.0 * thornton_beta(restitution) * (2.0 * scale).sqrt(),
                FrictionBound::Total,
            ),
            Rule::Liggghts => Damping::with_coefficient(
                Damping::new(restitution, mass, hertz).coefficient(),
                FrictionBound::Total,
            ),
        })
    }
}

/// True for the exact references (MDR under each rule).
pub fn is_reference(solver: &str) -> bool {
    [REFERENCE, LAMMPS_REFERENCE, YADE_REFERENCE, LIGGGHTS_REFERENCE].contains(&solver)
}

/// Tsuji's polynomial α(e), as LAMMPS's `damping tsuji` computes it from the restitution.
pub fn tsuji_alpha(e: f64) -> f64 {
    const C: [f64; 7] = [1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218];
    C.iter().rev().fold(0.0, |sum, c| sum * e + c)
}

/// Thornton, Cummins & Cleary's (2013) damping ratio β(e) for Hertz (their eqs. B6–B7), as
/// YADE's `Ip2_FrictMat_FrictMat_MindlinPhys` computes it from `en`.
pub fn thornton_beta(e: f64) -> f64 {
    const H: [f64; 10] = [
        -6.918798, -16.41105, 146.8049, -796.4559, 2928.711, -7206.864, 11494.29, -11342.18, 6276.757,
        -1489.915,
    ];
    if e == 1.0 {
        return 0.0;
    }
    let alpha = e * H.iter().rev().fold(0.0, |sum, h| sum * e + h);
    (1.0 / (1.0 - (1.0 + e).powi(2) * alpha.exp()) - 1.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's aluminium spheres (R 0.1 m, E 70 GPa, ν 0.3).
    fn hertz() -> Hertz {
        Hertz::of(&spherecontact_model::fixtures::test_scene(&[0.0, 17.0]).pair)
    }

    #[test]
    fn each_solver_runs_under_its_codes_rule() {
        assert_eq!(Rule::of("lammps-mindlin-rescale-force"), Rule::Lammps);
        assert_eq!(Rule::of("mdr-lammps"), Rule::Lammps);
        assert_eq!(Rule::of("yade-mindlin"), Rule::Yade);
        assert_eq!(Rule::of("kratos-hertz-coulomb"), Rule::Yade);
        assert_eq!(Rule::of("thornton"), Rule::Harness);
        assert_eq!(Rule::of("lammps-mindlin").reference(), "mdr-lammps");
        assert!(is_reference("mdr-yade") && !is_reference("yade-mindlin"));
        assert_eq!(Rule::of("liggghts-hertz-history").reference(), "mdr-liggghts");
        assert!(is_reference("mdr-liggghts"));
    }

    #[test]
    fn thorntons_beta_is_the_one_yade_computes() {
        // YADE 2023.02a printed betan = 0.2330248576834424 for en = 0.5 (docs/impact.md); the
        // fit's evaluation order differs from YADE's by rounding only.
        assert!((thornton_beta(0.5) - 0.2330248576834424).abs() < 1e-14);
        assert_eq!(thornton_beta(1.0), 0.0);
    }

    #[test]
    fn the_rules_differ_in_their_coefficient_and_bound() {
        let h = hertz();
        assert!(Rule::Lammps.damping(1.0, 1.0, &h).is_none());
        let harness = Rule::Harness.damping(0.5, 2.0, &h).unwrap();
        assert_eq!(harness, Damping::new(0.5, 2.0, &h));
        let lammps = Rule::Lammps.damping(0.5, 2.0, &h).unwrap();
        let yade = Rule::Yade.damping(0.5, 2.0, &h).unwrap();
        // LIGGGHTS' coefficient is the harness's; only its friction bound differs.
        let liggghts = Rule::Liggghts.damping(0.5, 2.0, &h).unwrap();
        assert_eq!(liggghts.coefficient(), harness.coefficient());
        assert_eq!(liggghts.bound, FrictionBound::Total);
        assert_ne!(harness.bound, FrictionBound::Total);
        assert_eq!(lammps.bound, FrictionBound::Total);
        assert_eq!(yade.bound, FrictionBound::Total);
        // At δn = 1, δ̇ = 1 the viscous force is the coefficient itself.
        let scale = h.effective_modulus * h.effective_radius.sqrt() * 2.0;
        let c = |d: &Damping| d.total(0.0, 1.0, 1.0);
        assert!((c(&lammps) / (tsuji_alpha(0.5) * (4.0 / 3.0 * scale).sqrt()) - 1.0).abs() < 1e-14);
        assert!((c(&yade) / (2.0 * thornton_beta(0.5) * (2.0 * scale).sqrt()) - 1.0).abs() < 1e-14);
    }
}
