//! Reading a DEM code's impact back: one file per sweep point (`point-<i>.txt`), one row per
//! step of 13 numbers written with 17 significant digits,
//!
//! ```text
//! step  x1 z1  x2 z2  vx1 vz1 wy1  vx2 vz2 wy2  fx1 fz1
//! ```
//!
//! the centres, velocities and spins about the codes' y axis of both bodies and the contact force
//! on body 1 (lines starting with `#` are comments). LAMMPS prints them at the end of each step
//! (velocity Verlet: positions, velocities and force at t_k); YADE's script before each step's
//! motion (leapfrog: positions and force at t_k, velocities at t_k + h/2).
//!
//! From them, as [`spherecontact_reference::impact::integrator`] measures its own impacts: the approach δ = R1 + R2 − |c1 −
//! c2|, first touch and separation interpolated linearly where δ crosses zero, the largest δ and
//! normal force P = f·n (n from body 2's centre to body 1's), Q = −f·t (t = (n_z, −n_x), the
//! tangential direction x rotated with n), the velocities before (the first row) and after (the
//! row where δ fell to zero or below: no force acts beyond it), in the harness's spin sign
//! (ω1 = −ω_y1, ω2 = +ω_y2: body 1 is above).

use std::path::Path;

use super::placement::Placement;
use spherecontact_reference::impact::integrator::{Integration, Motion, Sample};

/// The file of sweep point `index`.
pub fn file_name(index: usize) -> String {
    format!("point-{index}.txt")
}

/// A row: step, x1, z1, x2, z2, vx1, vz1, wy1, vx2, vz2, wy2, fx1, fz1.
type Row = [f64; 13];

/// What is wrong with a code's output.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum ReadbackError {
    /// The file could not be read.
    #[error("cannot read it: {0}")]
    Unreadable(String),
    /// A line is not a row.
    #[error("line {line}: {why}: `{text}`")]
    Malformed {
        /// The line number (from 1).
        line: usize,
        /// What is wrong.
        why: &'static str,
        /// The line.
        text: String,
    },
    /// The bodies never touched.
    #[error("the bodies never touched in {0} steps")]
    NoTouch(usize),
    /// The contact did not end.
    #[error("the contact did not end within {0} steps")]
    NoSeparation(usize),
}

/// The rows of one sweep point.
#[derive(Clone, Debug, PartialEq)]
pub struct Rows(Vec<Row>);

impl Rows {
    /// Reads `file`.
    pub fn read(file: &Path) -> Result<Self, ReadbackError> {
        let text = std::fs::read_to_string(file).map_err(|e| ReadbackError::Unreadable(e.to_string()))?;
        Self::parse(&text)
    }

    /// Parses the rows of `text`: 13 finite numbers a line, the steps 0, 1, 2, … in order.
    pub fn parse(text: &str) -> Result<Self, ReadbackError> {
        let mut rows: Vec<Row> = Vec::new();
        for (number, line) in text.lines().enumerate() {
            if line.starts_with('#') || line.trim().is_empty() {
                continue;
            }
            let bad = |why| ReadbackError::Malformed {
                line: number + 1,
                why,
                text: line.chars().take(200).collect(),
            };
            let values: Vec<f64> = line
                .split_whitespace()
                .map(str::parse)
                .collect::<Result<_, _>>()
                .map_err(|_| bad("not 13 numbers"))?;
            let row: Row = values.try_into().map_err(|_| bad("not 13 numbers"))?;
            if !row.iter().all(|v| v.is_finite()) {
                return Err(bad("a value is not finite"));
            }
            if row[0] != rows.len() as f64 {
                return Err(bad("step out of sequence"));
            }
            rows.push(row);
        }
        Ok(Self(rows))
    }

    /// The impact these rows record for `placement`, with every `stride`-th step of the contact
    /// in its trace (0: none).
    pub fn integration(&self, placement: &Placement, stride: usize) -> Result<Integration, ReadbackError> {
        let rows = &self.0;
        let h = placement.step;
        let [r1, r2] = placement.radius;
        let overlap = |r: &Row| r1 + r2 - (r[1] - r[3]).hypot(r[2] - r[4]);
        let touch = (1..rows.len())
            .find(|&k| overlap(&rows[k]) > 0.0)
            .ok_or(ReadbackError::NoTouch(rows.len()))?;
        let exit = (touch + 1..rows.len())
            .find(|&k| overlap(&rows[k]) <= 0.0)
            .ok_or(ReadbackError::NoSeparation(rows.len()))?;
        // Linear interpolation of δ between the rows k − 1 and k: the time δ = 0 since t_{k−1}.
        let crossing = |k: usize| {
            let (before, after) = (overlap(&rows[k - 1]), overlap(&rows[k]));
            h * before / (before - after)
        };
        let time = |k: usize| k as f64 * h;
        let touched_at = time(touch - 1) + crossing(touch);
        let duration = time(exit - 1) + crossing(exit) - touched_at;
        let mut trace = Vec::new();
        let (mut max_normal_force, mut max_overlap) = (0.0_f64, 0.0_f64);
        for (k, row) in rows.iter().enumerate().take(exit + 1).skip(touch) {
            let sample = sample(row, time(k) - touched_at, overlap(row));
            max_normal_force = max_normal_force.max(sample.normal_force);
            max_overlap = max_overlap.max(sample.overlap);
            if stride > 0 && ((k - touch).is_multiple_of(stride) || k == exit) {
                trace.push(sample);
            }
        }
        Ok(Integration {
            duration,
            max_normal_force,
            max_overlap,
            before: motion(&rows[0]),
            after: motion(&rows[exit]),
            trace,
        })
    }
}

/// The velocities of a row in the harness's convention.
fn motion(row: &Row) -> Motion {
    Motion {
        body1: [row[5], row[6], -row[7]],
        body2: [row[8], row[9], row[10]],
    }
}

/// A row as a trace sample at `time` since first touch, with approach `overlap`.
fn sample(row: &Row, time: f64, overlap: f64) -> Sample {
    let (dx, dz) = (row[1] - row[3], row[2] - row[4]);
    let distance = dx.hypot(dz);
    let (nx, nz) = (dx / distance, dz / distance);
    let (fx, fz) = (row[11], row[12]);
    Sample {
        time,
        overlap,
        normal_force: fx * nx + fz * nz,
        tangential_force: -(fx * nz - fz * nx),
        motion: motion(row),
    }
}
