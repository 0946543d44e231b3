//! Reading back a `kratos-3d` run: the driver's `steps.csv` (per computed step Kratos' converged
//! flag, its Newton iterations, the residual left, and P, Q from both far faces' reactions) and
//! `surface.csv` (the slave nodes' contact state), as foreign input ([`readback::records`]: a
//! fault named by file, line and column).
//!
//! Units: the files are in mm, N, MPa; what is returned is SI.

use std::collections::HashMap;

use crate::readback::{self, Row};
use crate::surface3d::Node3;

/// The columns of `steps.csv`.
pub const STEP_COLUMNS: [&str; 9] = [
    "step",
    "converged",
    "iterations",
    "residual",
    "P1_N",
    "Q1_N",
    "P2_N",
    "Q2_N",
    "wall_s",
];

/// The columns of `surface.csv`.
pub const SURFACE_COLUMNS: [&str; 10] = [
    "step",
    "node",
    "p_MPa",
    "qx_MPa",
    "qy_MPa",
    "active",
    "slip",
    "uz_mm",
    "slip_x_mm",
    "slip_y_mm",
];

/// Largest disagreement of the two far faces' P and Q, relative to the larger P and 1 N, at a
/// converged step: the bodies' equilibrium, which Kratos' Newton reaches to its residual
/// tolerance (measured below 1e-12 of P on the paper's spheres), so 1e-6 flags a wrong reading.
pub const EQUILIBRIUM: f64 = 1e-6;

/// One computed step as Kratos left it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KratosStep {
    /// The path step.
    pub step: usize,
    /// Whether Kratos' Newton iteration converged.
    pub converged: bool,
    /// Its iterations.
    pub iterations: u32,
    /// The norm of the residual left (forces [N] and weighted gaps [mm]).
    pub residual: f64,
    /// (P, Q) of the whole spheres from sphere 1's far face [N].
    pub forces: [f64; 2],
    /// (P, Q) from sphere 2's far face [N].
    pub forces_other: [f64; 2],
    /// The step's wall time in Kratos [s].
    pub wall_s: f64,
}

/// Reads `steps.csv` from `text` for the computed path steps `expected` (their indices, in order).
pub fn parse_steps(text: &str, expected: &[usize]) -> Result<Vec<KratosStep>, String> {
    let rows = readback::records(text, "steps.csv", &STEP_COLUMNS)?;
    if rows.len() != expected.len() {
        return Err(format!(
            "steps.csv has {} rows for the {} computed steps of path.txt (a truncated run, or rows \
             of another path; allowed: one row per computed step)",
            rows.len(),
            expected.len()
        ));
    }
    rows.iter()
        .zip(expected)
        .map(|(row, &step)| parse_step(row, step))
        .collect()
}

fn parse_step(row: &Row, expected: usize) -> Result<KratosStep, String> {
    let step: usize = row.whole(0, "a step index")?;
    if step != expected {
        return Err(row.cell_error(0, format!("step {step} where path.txt has step {expected}")));
    }
    let converged = row.choice(1, &[("0", false), ("1", true)])?;
    let iterations = row.whole(2, "an iteration count")?;
    let [residual, p1, q1, p2, q2, wall_s] = [3, 4, 5, 6, 7, 8].map(|i| row.finite(i, 1.0));
    let read = KratosStep {
        step,
        converged,
        iterations,
        residual: residual?,
        forces: [p1?, q1?],
        forces_other: [p2?, q2?],
        wall_s: wall_s?,
    };
    let scale = read.forces[0].abs().max(read.forces_other[0].abs()).max(1.0);
    for k in 0..2 {
        let departure = (read.forces[k] - read.forces_other[k]).abs() / scale;
        if converged && departure > EQUILIBRIUM {
            return Err(row.error(format!(
                "{} from sphere 1's far face and from sphere 2's differ by {departure:.1e} of the \
                 larger P and 1 N at a converged step: not in equilibrium (allowed: {EQUILIBRIUM:e})",
                ["P", "Q"][k]
            )));
        }
    }
    Ok(read)
}

/// Where the slave nodes are read: their MDPA ids (1-based) and, for each, its point on the
/// contact plane [m] and weight ∫ L dA [m²].
pub struct SlaveNodes {
    /// The MDPA node ids, in the order of the surface's nodes.
    pub ids: Vec<usize>,
    /// Each node's (x, y, z) [m] before the load.
    pub points: Vec<[f64; 3]>,
    /// Each node's weight [m²].
    pub weights: Vec<f64>,
}

/// Reads `surface.csv` from `text`: for each computed step of `steps` (in order) one row per node
/// of `slaves`, any order. A node is in contact where Kratos flags it ACTIVE; its pressure and
/// traction are the augmented ones there and 0 elsewhere (the contact law's, whatever Kratos left
/// in the columns of a node out of contact: it leaves `nan` tangential pressures there, seen with
/// `ALMContactFrictional` at μ = 0 and on bricks), and it sticks where ACTIVE and not SLIP.
///
/// At a step Kratos did not converge, whose surface the History never shows, a number that is not
/// finite (Kratos leaves `nan` tractions in a diverged state) reads as 0, so that the run's
/// convergence record is kept; anything that is no number fails there too.
pub fn parse_surface(
    text: &str,
    steps: &[KratosStep],
    slaves: &SlaveNodes,
) -> Result<Vec<Vec<Node3>>, String> {
    let rows = readback::records(text, "surface.csv", &SURFACE_COLUMNS)?;
    let index: HashMap<usize, usize> = slaves.ids.iter().enumerate().map(|(j, &id)| (id, j)).collect();
    let n = slaves.ids.len();
    if rows.len() != n * steps.len() {
        return Err(format!(
            "surface.csv has {} rows, expected {} ({} slave nodes at {} computed steps: a truncated run?)",
            rows.len(),
            n * steps.len(),
            n,
            steps.len()
        ));
    }
    let mut surfaces = Vec::with_capacity(steps.len());
    for (block, computed) in rows.chunks(n).zip(steps) {
        let step = computed.step;
        let mut nodes: Vec<Option<Node3>> = vec![None; n];
        for row in block {
            let found: usize = row.whole(0, "a step index")?;
            if found != step {
                return Err(row.cell_error(0, format!("step {found} in the block of step {step}")));
            }
            let id: usize = row.whole(1, "a node id")?;
            let j = *index
                .get(&id)
                .ok_or_else(|| row.cell_error(1, "not a slave node of spheres.mdpa"))?;
            if nodes[j].is_some() {
                return Err(row.cell_error(1, format!("node {id} twice at step {step}")));
            }
            nodes[j] = Some(node(row, slaves, j, computed.converged)?);
        }
        surfaces.push(nodes.into_iter().flatten().collect());
    }
    Ok(surfaces)
}

/// The contact state of slave node `j` from its row: every cell a number, and finite where it is
/// used at a `converged` step (the tractions of a node out of contact are the law's zero, unused).
fn node(row: &Row, slaves: &SlaveNodes, j: usize, converged: bool) -> Result<Node3, String> {
    let lenient = |i: usize| {
        row.finite(i, 1.0)
            .or_else(|e| match row.text(i).parse::<f64>().is_ok() {
                true => Ok(0.0),
                false => Err(e),
            })
    };
    let number = |i: usize| match converged {
        true => row.finite(i, 1.0),
        false => lenient(i),
    };
    let flag = |i| row.choice(i, &[("0", false), ("1", true)]);
    let (active, slip) = (flag(5)?, flag(6)?);
    let traction = |i: usize| match active {
        true => number(i),
        false => lenient(i).map(|_| 0.0),
    };
    let [p, qx, qy] = [2, 3, 4].map(traction);
    let [uz, sx, sy] = [7, 8, 9].map(number);
    let [x, y, z] = slaves.points[j];
    Ok(Node3 {
        point: [x, y],
        weight: slaves.weights[j],
        gap: z + uz? * 1e-3,
        pressure: p?.max(0.0) * 1e6,
        traction: [qx? * 1e6, qy? * 1e6],
        stick: active && !slip,
        slip: [sx? * 1e-3, sy? * 1e-3],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "step,converged,iterations,residual,P1_N,Q1_N,P2_N,Q2_N,wall_s\n";

    /// Requirement: the converged flag, iterations and forces are read per step; a step of
    /// another path, a garbage flag or forces out of equilibrium at a converged step fail naming
    /// the line (tolerance: [`EQUILIBRIUM`]).
    #[test]
    fn the_convergence_record_is_read_and_faults_are_named() {
        let text = format!("{HEADER}0,1,5,1e-20,0,0,0,0,3.2\n1,0,30,2.5e-3,393.4,1.5,393.0,1.0,40\n");
        let steps = parse_steps(&text, &[0, 1]).unwrap();
        assert!(steps[0].converged && !steps[1].converged);
        assert_eq!((steps[1].iterations, steps[1].forces), (30, [393.4, 1.5]));
        let e = parse_steps(&text, &[0, 2]).unwrap_err();
        assert!(
            e.contains("steps.csv:3") && e.contains("path.txt has step 2"),
            "{e}"
        );
        let e = parse_steps(&format!("{HEADER}0,yes,5,0,0,0,0,0,1\n"), &[0]).unwrap_err();
        assert!(e.contains("steps.csv:2") && e.contains("converged"), "{e}");
        let e = parse_steps(&format!("{HEADER}0,1,5,0,393.4,0,393.0,0,1\n"), &[0]).unwrap_err();
        assert!(e.contains("not in equilibrium"), "{e}");
        let e = parse_steps(&format!("{HEADER}0,1,5,0,nan,0,0,0,1\n"), &[0]).unwrap_err();
        assert!(e.contains("P1_N"), "{e}");
        assert!(parse_steps(&text, &[0]).unwrap_err().contains("2 rows for the 1"));
    }

    /// Requirement: pressure and traction only where ACTIVE, stick where ACTIVE and not SLIP, SI
    /// units; a node not of the slave set fails; a `nan` is tolerated only at a step Kratos did not
    /// converge or where the value is unused (a traction out of contact).
    #[test]
    fn the_surface_is_read_in_si_with_the_contact_flags() {
        let slaves = SlaveNodes {
            ids: vec![4, 9],
            points: vec![[0.0, 0.0, 0.0], [1e-4, 0.0, 1e-7]],
            weights: vec![1e-9, 2e-9],
        };
        let text = "step,node,p_MPa,qx_MPa,qy_MPa,active,slip,uz_mm,slip_x_mm,slip_y_mm\n\
                    3,9,-0.5,0,0,0,0,0,0,0\n3,4,400,10,0,1,0,-1e-6,0,0\n";
        let step = |converged| KratosStep {
            step: 3,
            converged,
            iterations: 5,
            residual: 0.0,
            forces: [0.0; 2],
            forces_other: [0.0; 2],
            wall_s: 1.0,
        };
        let s = parse_surface(text, &[step(true)], &slaves).unwrap();
        assert_eq!(s[0][0].pressure, 400e6);
        assert!(s[0][0].stick && !s[0][1].stick);
        assert_eq!(s[0][1].pressure, 0.0);
        assert!((s[0][0].gap + 1e-9).abs() < 1e-24);
        let bad = text.replace("3,9,", "3,7,");
        assert!(parse_surface(&bad, &[step(true)], &slaves)
            .unwrap_err()
            .contains("not a slave node"));
        // Kratos' nan at a step it did not converge reads as 0 (never shown); at a converged
        // step it fails naming the column where it is used (the active node 4), and is the law's
        // zero where it is not (the tractions of node 9, out of contact); a cell that is no
        // number fails anywhere.
        let diverged = text.replace("3,4,400,10,", "3,4,400,nan,");
        assert_eq!(
            parse_surface(&diverged, &[step(false)], &slaves).unwrap()[0][0].traction,
            [0.0; 2]
        );
        let e = parse_surface(&diverged, &[step(true)], &slaves).unwrap_err();
        assert!(e.contains("surface.csv:3") && e.contains("qx_MPa"), "{e}");
        let inactive = text.replace("3,9,-0.5,0,", "3,9,-0.5,nan,");
        assert_eq!(
            parse_surface(&inactive, &[step(true)], &slaves).unwrap()[0][1].traction,
            [0.0; 2]
        );
        let garbage = text.replace("3,9,-0.5,0,", "3,9,-0.5,x,");
        assert!(parse_surface(&garbage, &[step(true)], &slaves).is_err());
        assert!(parse_surface(&garbage, &[step(false)], &slaves).is_err());
    }
}
