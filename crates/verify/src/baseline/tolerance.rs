//! The non-regression tolerance of each solver's values: how far a value may move between a
//! baseline and a rerun before it is a DRIFT (relative), with the reason
//! (docs/verification-at-scale.md's table). In-crate solvers are deterministic and get round-off;
//! an external code its own last digits.

/// The non-regression tolerance of a solver's values (relative) and its reason.
pub fn tolerance(solver: &str) -> (f64, &'static str) {
    match solver {
        "freefem-axisym" | "fenicsx-axisym" | "fenicsx-3d" => (
            1e-9,
            "an external FEM program: FreeFEM's MUMPS_seq differs in the last bits run to run (about \
             1e-14 of P and Q on the same files, external::deck::single_threaded), FEniCSx under MPI sums \
             by rank, and a penalty system amplifies rounding; a change of mesh, penalty or model moves P \
             by 1e-6 or more",
        ),
        name if name.starts_with("ccx") => (
            1e-6,
            "CalculiX: its results are read from the text it prints (.dat and .frd numbers of 7 \
             significant digits), so a rounding change in its SPOOLES solve that moves one printed digit \
             moves the value by up to 1e-6 relative; a change of mesh, penalty or formulation moves P by \
             1e-5 or more (docs/external-decks.md, the penalty sweep)",
        ),
        name if ["lammps", "yade", "liggghts", "kratos"]
            .iter()
            .any(|code| name.starts_with(code)) =>
        {
            (
                1e-9,
                "an external code (LAMMPS, YADE, LIGGGHTS, Kratos) driven through text input and output: \
                 positions and forces pass through its own arithmetic and formatting, which another build \
                 of the same version may order differently",
            )
        }
        _ => (
            1e-12,
            "deterministic: the same source on the same machine gives the same bits (the BEM's team too, \
             on one or two threads); 1e-12 leaves four orders over double rounding for another compiler's \
             contractions (FMA)",
        ),
    }
}

/// The largest change accepted for a check: the loosest of its solvers' tolerances.
pub(crate) fn check_tolerance(solvers: &[String]) -> f64 {
    solvers.iter().map(|s| tolerance(s).0).fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Requirement: every external code's values are compared at its own last-digit tolerance
    /// (docs/verification-at-scale.md's table), the in-crate solvers at round-off; a DEM code
    /// left at 1e-12 fails a clean rerun on its own formatting.
    #[test]
    fn every_external_code_has_its_tolerance_and_the_in_crate_solvers_round_off() {
        for code in [
            "lammps-mindlin",
            "yade-mindlin",
            "liggghts-hertz-history",
            "kratos-hertz-coulomb",
            "freefem-axisym",
        ] {
            assert_eq!(tolerance(code).0, 1e-9, "{code}");
        }
        assert_eq!(tolerance("ccx-3d").0, 1e-6);
        for in_crate in [
            "mdr",
            "mdr-yade",
            "mdr-liggghts",
            "hertz-mindlin-spring",
            "fem-3d",
        ] {
            assert_eq!(tolerance(in_crate).0, 1e-12, "{in_crate}");
        }
    }
}
