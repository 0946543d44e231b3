//! A case's `labels`: words that say what kind of work it is, so that `verify --label L` and
//! `--skip-label L` select cases by kind rather than by folder.
//!
//! ```toml
//! labels = ["fast", "dem"]              # optional; each from the known set below, once
//! ```
//!
//! The set is closed (a typo in a case file or on the command line is an error, not a label
//! that silently selects nothing).

use toml::Spanned;

use crate::{CaseError, Validator};

/// The known labels and what each means.
pub const LABELS: &[(&str, &str)] = &[
    (
        "fast",
        "no FEM, BEM or deck: closed forms, laws and small programs, seconds in a debug build",
    ),
    (
        "heavy",
        "minutes: kept out of the default verification (cases-heavy/)",
    ),
    (
        "external",
        "needs an external tool (gmsh, FreeFEM, FEniCSx, LAMMPS, YADE, python3)",
    ),
    ("dem", "DEM force laws or DEM codes"),
    ("paper", "the paper's spheres along its Figure 7 path"),
    ("hard", "a hard case for the in-crate solvers (cases/hard/)"),
    ("fem", "finite elements, in-crate or external"),
    ("bem", "the half-space boundary elements"),
    (
        "impact",
        "a dynamic impact case (cases/impact/): rigid-body dynamics with a contact law",
    ),
];

/// True when `label` is one of [`LABELS`].
pub fn is_known(label: &str) -> bool {
    LABELS.iter().any(|(name, _)| *name == label)
}

/// The known labels, comma-separated (for messages).
pub fn allowed() -> String {
    LABELS
        .iter()
        .map(|(name, _)| *name)
        .collect::<Vec<_>>()
        .join(", ")
}

impl Validator<'_> {
    /// The case's labels: each known, none twice.
    pub(super) fn labels(
        &self,
        raw: Option<&Spanned<Vec<Spanned<String>>>>,
    ) -> Result<Vec<String>, CaseError> {
        let mut labels: Vec<String> = Vec::new();
        for label in raw.map(|r| r.get_ref().as_slice()).unwrap_or_default() {
            let name = label.get_ref();
            if !is_known(name) {
                let message = format!("unknown label `{name}` (allowed: {})", allowed());
                return Err(self.error(label, "labels", message));
            }
            if labels.contains(name) {
                return Err(self.error(label, "labels", format!("`{name}` is listed twice")));
            }
            labels.push(name.clone());
        }
        Ok(labels)
    }
}

#[cfg(test)]
mod tests {
    use crate::Case;
    use std::path::Path;

    fn case(labels: &str) -> Result<Case, String> {
        let text = format!(
            "friction = 0.2\nsolvers = [\"hertz\"]\nlabels = {labels}\n[body1]\nradius = 0.1\nyoung = 70e9\n\
             poisson = 0.3\n[path]\nunit = \"um\"\ndelta_n = [0, 10]\ndelta_t = [0, 0]\nsubsteps = 1\n"
        );
        Case::parse(Path::new("labels.toml"), &text).map_err(|e| e.to_string())
    }

    #[test]
    fn known_labels_are_kept_in_order() {
        assert_eq!(case("[\"fast\", \"dem\"]").unwrap().labels, ["fast", "dem"]);
    }

    #[test]
    fn an_unknown_or_repeated_label_is_an_error_naming_the_field() {
        let error = case("[\"fats\"]").unwrap_err();
        assert!(
            error.contains("labels") && error.contains("unknown label `fats`"),
            "{error}"
        );
        assert!(error.contains("allowed: fast, heavy"), "{error}");
        let error = case("[\"fast\", \"fast\"]").unwrap_err();
        assert!(error.contains("`fast` is listed twice"), "{error}");
    }
}
