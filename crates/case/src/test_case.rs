//! The unit tests' case: the paper's spheres pressed to δn = 10 µm (`c.toml`, Hertz alone), with a
//! table of the test's appended: what every deck table's tests parse.

use std::path::Path;

use crate::{Case, CaseError};

/// The paper's spheres on a one-step normal path, `table` appended.
pub(crate) fn paper_case(table: &str) -> Result<Case, CaseError> {
    let text = format!(
        "friction = 0.2\nsolvers = [\"hertz\"]\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
         [path]\nunit = \"um\"\ndelta_n = [0, 10]\ndelta_t = [0, 0]\nsubsteps = 1\n{table}"
    );
    Case::parse(Path::new("c.toml"), &text)
}
