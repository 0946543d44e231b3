//! The loading path: positions of relative normal approach δn and relative tangential
//! displacement δt, joined by straight segments cut into substeps.
//!
//! δn is the total approach of the two bodies' far points (the paper's 2α); δt is the relative
//! tangential displacement of the far points, along one fixed direction. Step 0 is position 0;
//! segment k (position k → k + 1) contributes its substeps, the last of which reaches position k + 1.

use serde::Serialize;

/// A point of the loading path [m].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Position {
    /// Relative normal approach δn [m] (negative: a gap).
    pub delta_n: f64,
    /// Relative tangential displacement δt [m].
    pub delta_t: f64,
}

/// One increment of the path as the solvers see it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Step {
    /// Step index, 0 for the start.
    pub index: usize,
    /// The index of the path position this step reaches; `None` between positions.
    pub position: Option<usize>,
    /// Relative normal approach δn [m].
    pub delta_n: f64,
    /// Relative tangential displacement δt [m].
    pub delta_t: f64,
}

/// A validated loading path: at least one position, at least one substep per segment.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LoadingPath {
    positions: Vec<Position>,
    substeps: Vec<usize>,
}

impl LoadingPath {
    /// A path through `positions`, with `substeps[k]` increments on segment k.
    ///
    /// Returns `None` unless there is at least one position, one substep count per segment,
    /// and every count is at least one. (Case validation reports these with file and field.)
    pub fn try_new(positions: Vec<Position>, substeps: Vec<usize>) -> Option<Self> {
        let ok = !positions.is_empty()
            && substeps.len() + 1 == positions.len()
            && substeps.iter().all(|&m| m >= 1);
        ok.then_some(Self { positions, substeps })
    }

    /// The path positions.
    pub fn positions(&self) -> &[Position] {
        &self.positions
    }

    /// The substep count of each segment.
    pub fn substeps(&self) -> &[usize] {
        &self.substeps
    }

    /// A copy of this path with every segment's substep count multiplied by `factor` (≥ 1).
    pub fn refined(&self, factor: usize) -> Self {
        let factor = factor.max(1);
        Self {
            positions: self.positions.clone(),
            substeps: self.substeps.iter().map(|m| m * factor).collect(),
        }
    }

    /// Every step of the path, step 0 first; a segment's substeps interpolate linearly.
    pub fn steps(&self) -> Vec<Step> {
        let first = self.positions[0];
        let mut steps = vec![Step {
            index: 0,
            position: Some(0),
            delta_n: first.delta_n,
            delta_t: first.delta_t,
        }];
        for (k, (pair, &m)) in self.positions.windows(2).zip(&self.substeps).enumerate() {
            let (from, to) = (pair[0], pair[1]);
            for j in 1..=m {
                let s = j as f64 / m as f64;
                let (delta_n, delta_t) = if j == m {
                    (to.delta_n, to.delta_t) // exact at the position, no rounding drift
                } else {
                    (
                        from.delta_n + s * (to.delta_n - from.delta_n),
                        from.delta_t + s * (to.delta_t - from.delta_t),
                    )
                };
                steps.push(Step {
                    index: steps.len(),
                    position: (j == m).then_some(k + 1),
                    delta_n,
                    delta_t,
                });
            }
        }
        steps
    }

    /// The largest normal approach on the path [m] (it sizes models and meshes).
    pub fn max_approach(&self) -> f64 {
        self.positions
            .iter()
            .map(|p| p.delta_n)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// True when δt is zero everywhere: a normal-only path.
    pub fn is_normal_only(&self) -> bool {
        self.positions.iter().all(|p| p.delta_t == 0.0)
    }
}

/// How close a row's δn and δt must be to the path's, relative to the path's largest |δn|, |δt|.
///
/// Reason: a file written with 7 significant digits or more is within 5e-7 of the path; a unit
/// slip (×1e3, ×1e6) or a row of a neighbouring step (one substep away, ≥ 1e-6 of the largest
/// value for paths of up to a million increments) is far outside.
pub const PATH_MATCH: f64 = 5e-7;

#[cfg(test)]
mod tests {
    use super::*;

    fn pos(delta_n: f64, delta_t: f64) -> Position {
        Position { delta_n, delta_t }
    }

    #[test]
    fn steps_interpolate_and_mark_positions() {
        let path =
            LoadingPath::try_new(vec![pos(0.0, 0.0), pos(4.0, 0.0), pos(4.0, 2.0)], vec![4, 2]).unwrap();
        let steps = path.steps();
        assert_eq!(steps.len(), 7);
        assert_eq!(steps[2].delta_n, 2.0);
        assert_eq!(steps[4].position, Some(1));
        assert_eq!(steps[3].position, None);
        assert_eq!(steps[5].delta_t, 1.0);
        assert_eq!(steps[6].position, Some(2));
        assert!(steps.iter().enumerate().all(|(i, s)| s.index == i));
    }

    #[test]
    fn try_new_rejects_malformed_paths() {
        assert!(LoadingPath::try_new(vec![], vec![]).is_none());
        assert!(LoadingPath::try_new(vec![pos(0.0, 0.0), pos(1.0, 0.0)], vec![0]).is_none());
        assert!(LoadingPath::try_new(vec![pos(0.0, 0.0), pos(1.0, 0.0)], vec![]).is_none());
        assert!(LoadingPath::try_new(vec![pos(1.0, 0.0)], vec![]).is_some());
    }

    #[test]
    fn refined_multiplies_substeps() {
        let path = LoadingPath::try_new(vec![pos(0.0, 0.0), pos(1.0, 0.0)], vec![3]).unwrap();
        assert_eq!(path.refined(10).steps().len(), 31);
    }
}
