//! What a check finds of the solvers it needs: a history, or the verdict and message of its
//! absence (the solver not run, failed, not installed); and a quantity a history lacks because
//! its results file did not give it (`Metadata::unread`: that quantity's checks alone fail).

use crate::{Histories, Verdict};
use spherecontact_model::history::{History, Quantity};
use spherecontact_model::solver::SolveError;

/// The history of `name`, or the verdict and message of its absence.
pub fn lookup<'a>(histories: &'a Histories, name: &str) -> Result<&'a History, (Verdict, String)> {
    match histories.get(name) {
        Some(Ok(history)) => Ok(history),
        Some(Err(error @ SolveError::Unavailable(_))) => {
            Err((Verdict::Unavailable, format!("{name}: {error}")))
        }
        Some(Err(error)) => Err((Verdict::Nook, format!("{name}: {error}"))),
        None => Err((Verdict::Nook, format!("{name} was not run"))),
    }
}

/// Why `name`'s history has no `quantity` although it was read, as a check's message: the column
/// absent from its results file, or refused for a cell that is not a number (file, line, column).
pub fn unread(name: &str, history: &History, quantity: Quantity) -> Option<String> {
    history
        .metadata
        .unread
        .get(&quantity)
        .map(|why| format!("{name}: {why}"))
}

#[cfg(test)]
mod tests {
    use crate::tests::{histories, spec};
    use crate::{CheckSpec, ErrorMeasure, Verdict};
    use spherecontact_model::history::Quantity;

    /// Requirement: a quantity the judged solver or its reference did not read from its results
    /// file fails that quantity's checks with the reason, and no other quantity's (both solvers
    /// give P = 1 N: the P check passes).
    #[test]
    fn a_quantity_not_read_fails_its_checks_only() {
        let why = "h.csv:3: column `tangential_force`: not finite";
        for name in ["a", "b"] {
            let mut h = histories(&[Some(1.0)], &[Some(1.0)]);
            let history = h.get_mut(name).unwrap().as_mut().unwrap();
            history
                .metadata
                .unread
                .insert(Quantity::TangentialForce, why.into());
            let tangential = CheckSpec {
                quantity: Quantity::TangentialForce,
                ..spec(ErrorMeasure::Relative, Some(1.0))
            };
            let outcome = tangential.evaluate(&h);
            assert_eq!(outcome.verdict, Verdict::Nook);
            assert_eq!(outcome.message.unwrap(), format!("{name}: {why}"));
            let normal = spec(ErrorMeasure::Relative, Some(1.0)).evaluate(&h);
            assert_eq!((normal.verdict, normal.message), (Verdict::Ok, None));
        }
    }
}
