//! The path walker's rules (crates/model/src/driver.rs) hold for every incremental solver that walks with it:
//! a path that never closes the gap is zeros with a note, not a failure; an open gap in the
//! middle of a path is zero force (the history-clearing half is in tangential_laws.rs).

use crate::common;

use common::{paper_scene_with_path, solve};
use spherecontact::driver::NEVER_CLOSES;

/// The in-crate solvers whose paths the walker drives (fem-axisym: its never-closing rule).
const WALKING: [&str; 8] = [
    "bem",
    "mdr",
    "fem-axisym",
    "hertz-mindlin-spring",
    "hertz-mindlin-total",
    "thornton",
    "md-incremental",
    "walton-braun",
];

#[test]
fn a_path_that_never_closes_gives_zeros_and_a_note() {
    // Touching (δn = 0) and separated, with tangential motion.
    let scene = paper_scene_with_path(&[(0.0, 0.0), (-1.0, 1.0), (0.0, 2.0)], 3);
    for name in WALKING {
        let history = solve(name, &scene);
        assert_eq!(history.steps.len(), scene.steps().len(), "{name}");
        for row in &history.steps {
            assert_eq!(row.normal_force, Some(0.0), "{name} step {}", row.step);
            if let Some(q) = row.tangential_force {
                assert_eq!(q, 0.0, "{name} step {}", row.step);
            }
        }
        assert!(
            history.metadata.warnings.iter().any(|w| w == NEVER_CLOSES),
            "{name}: no note {:?}",
            history.metadata.warnings
        );
    }
}

#[test]
fn an_open_gap_inside_a_path_is_zero_force() {
    let scene = paper_scene_with_path(&[(0.0, 0.0), (5.0, 0.5), (-1.0, 1.0), (5.0, 1.0)], 2);
    for name in ["bem", "mdr", "thornton"] {
        let history = solve(name, &scene);
        let open = history.at_position(2).expect("position 2");
        assert_eq!(
            (open.normal_force, open.tangential_force, open.contact_radius),
            (Some(0.0), Some(0.0), Some(0.0)),
            "{name}"
        );
        assert!(
            history.at_position(3).unwrap().normal_force.unwrap() > 0.0,
            "{name}"
        );
    }
}
