//! Reading CalculiX's own output: the `.dat` text (`*NODE PRINT, TOTALS=ONLY`: the total force
//! on a node set at each output time) and the `.frd` ASCII results (the node coordinates and the
//! `CONTACT` blocks: COPEN, CSLIP1, CSLIP2, CPRESS, CSHEAR1, CSHEAR2 at the slave nodes).
//! Missing, truncated or non-finite output is an error that names the file and the line, never a
//! panic, and quotes nothing of the file (a deck's folder may come from elsewhere: docs/security.md,
//! "Deck folders").
//!
//! CalculiX may print a step's output twice (after the step's last increment and after an extra
//! increment of 1e-6 step time that a change of the contact set triggers); the last block of each
//! output time is the step's answer.

use std::collections::HashMap;

/// The total force on a node set at one output time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Total {
    /// The output (total) time.
    pub time: f64,
    /// The force (fx, fy, fz) [N] on the 2-degree segment.
    pub force: [f64; 3],
}

/// Every `total force (fx,fy,fz) for set SET and time T` block of a `.dat` text, in order.
pub fn totals(dat: &str, set: &str) -> Result<Vec<Total>, String> {
    let head = format!("total force (fx,fy,fz) for set {} and time", set.to_uppercase());
    let lines: Vec<&str> = dat.lines().collect();
    let mut totals = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some(rest) = line.trim().strip_prefix(&head) else {
            continue;
        };
        let at = |what: &str| format!("job.dat line {}: {what}", i + 1);
        let time = finite(rest.trim()).ok_or_else(|| at("the output time is not a number"))?;
        let values = lines[i + 1..]
            .iter()
            .find(|l| !l.trim().is_empty())
            .ok_or_else(|| at("the totals are missing (truncated output)"))?;
        let force: Vec<f64> = values.split_whitespace().filter_map(finite).collect();
        let [fx, fy, fz] = force[..] else {
            return Err(at("not three finite forces (allowed: the totals fx fy fz)"));
        };
        totals.push(Total {
            time,
            force: [fx, fy, fz],
        });
    }
    Ok(totals)
}

/// A finite number, if `text` is one.
fn finite(text: &str) -> Option<f64> {
    text.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// One result block of a `.frd` with `N` values a node: its output time and, per node, the values.
#[derive(Clone, Debug, PartialEq)]
pub struct Block<const N: usize> {
    /// The output (total) time.
    pub time: f64,
    /// Node number → the values.
    pub values: HashMap<u64, [f64; N]>,
}

impl<const N: usize> Default for Block<N> {
    fn default() -> Self {
        Self {
            time: 0.0,
            values: HashMap::new(),
        }
    }
}

/// A `CONTACT` block: per slave node (COPEN, CSLIP1, CSLIP2, CPRESS, CSHEAR1, CSHEAR2) [mm, MPa].
pub type ContactBlock = Block<6>;

/// A `DISP` block: per node (u_x, u_y, u_z) [mm].
pub type DisplacementBlock = Block<3>;

/// What the `.frd` holds that the decks read: the node coordinates (all of them, the expanded
/// 3D nodes included under `OUTPUT=3D`), the contact blocks and the displacement blocks, each in
/// output order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frd {
    /// Node number → (x, y, z) [mm].
    pub nodes: HashMap<u64, [f64; 3]>,
    /// The contact blocks, in output order.
    pub contact: Vec<ContactBlock>,
    /// The displacement blocks, in output order.
    pub displacement: Vec<DisplacementBlock>,
}

impl Frd {
    /// The last contact block of the `*STEP` numbered `k` from 0: the decks give each step a
    /// total time of 1, so its output is at time k + 1; `None` when the step wrote none (no
    /// contact).
    pub fn contact_at_step(&self, k: usize) -> Option<&ContactBlock> {
        at_step(&self.contact, k)
    }

    /// The last displacement block of the `*STEP` numbered `k` from 0 (as [`Frd::contact_at_step`]).
    pub fn displacement_at_step(&self, k: usize) -> Option<&DisplacementBlock> {
        at_step(&self.displacement, k)
    }
}

/// The last of `blocks` at the output time of step `k` (from 0): k + 1.
fn at_step<const N: usize>(blocks: &[Block<N>], k: usize) -> Option<&Block<N>> {
    let time = (k + 1) as f64;
    blocks.iter().rev().find(|b| (b.time - time).abs() < 1e-6)
}

/// A `-1` record of the `.frd` (fixed columns: the key, an I10 number, then E12.5 values): the
/// number and `count` values.
fn record(line: &str, count: usize) -> Option<(u64, Vec<f64>)> {
    let id = line.get(3..13)?.trim().parse().ok()?;
    let values = (0..count)
        .map(|k| line.get(13 + 12 * k..25 + 12 * k).and_then(|v| finite(v.trim())))
        .collect::<Option<Vec<f64>>>()?;
    Some((id, values))
}

/// Parses an ASCII `.frd` (its node block, contact blocks and displacement blocks).
pub fn parse_frd(text: &str) -> Result<Frd, String> {
    let lines: Vec<&str> = text.lines().collect();
    let mut frd = Frd::default();
    let mut time = None;
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        if line.starts_with("    2C") {
            i += 1;
            while i < lines.len() && !lines[i].starts_with(" -3") {
                let (id, xyz) = record(lines[i], 3).ok_or_else(|| at_line(i, "not a node record"))?;
                frd.nodes.insert(id, [xyz[0], xyz[1], xyz[2]]);
                i += 1;
            }
        } else if line.starts_with("  100C") {
            time = line.get(12..24).and_then(|t| finite(t.trim()));
            if time.is_none() {
                return Err(at_line(i, "a result block without its time"));
            }
        } else if line.starts_with(" -4  CONTACT") {
            let block;
            (block, i) = result_block(&lines, i, time, "contact")?;
            frd.contact.push(block);
        } else if line.starts_with(" -4  DISP") {
            let block;
            (block, i) = result_block(&lines, i, time, "displacement")?;
            frd.displacement.push(block);
        }
        i += 1;
    }
    Ok(frd)
}

/// `job.frd line <i + 1>: <what>`.
fn at_line(i: usize, what: &str) -> String {
    format!("job.frd line {}: {what}", i + 1)
}

/// The result block (`what`: its name in errors) whose `-4` line is `lines[i]`, at output
/// `time`, and the index of its closing `-3` line.
fn result_block<const N: usize>(
    lines: &[&str],
    mut i: usize,
    time: Option<f64>,
    what: &str,
) -> Result<(Block<N>, usize), String> {
    let time = time.ok_or_else(|| at_line(i, &format!("a {what} block without its time")))?;
    let mut block = Block {
        time,
        values: HashMap::new(),
    };
    i += 1;
    while i < lines.len() && lines[i].starts_with(" -5") {
        i += 1;
    }
    while i < lines.len() && !lines[i].starts_with(" -3") {
        let (id, v) = record(lines[i], N)
            .ok_or_else(|| at_line(i, &format!("not a {what} record of {} finite values", words(N))))?;
        block.values.insert(id, std::array::from_fn(|k| v[k]));
        i += 1;
    }
    if i == lines.len() {
        return Err(at_line(
            i,
            &format!("the {what} block is not closed (truncated output)"),
        ));
    }
    Ok((block, i))
}

/// A record's value count in words.
fn words(n: usize) -> String {
    match n {
        3 => "three".into(),
        6 => "six".into(),
        n => n.to_string(),
    }
}

/// The last of `items` at each output time 1, 2, …, `steps` (one step of unit time per path
/// position), or an error naming the first step with none (`what` names the output).
pub fn last_per_step<T: Clone>(
    items: &[T],
    time: impl Fn(&T) -> f64,
    steps: usize,
    what: &str,
) -> Result<Vec<T>, String> {
    (1..=steps)
        .map(|k| {
            items
                .iter()
                .rev()
                .find(|item| (time(item) - k as f64).abs() < 1e-6)
                .cloned()
                .ok_or_else(|| {
                    format!("{what}: no output for step {k} of {steps} (the run stopped early or did not converge)")
                })
        })
        .collect()
}

/// The contact opening and pressure [mm, MPa] of `block` at each meridian point of `points`
/// (r, z) [mm], sorted by r: from the expanded nodes at those points (r = √(x² + z²), z = y; the
/// `.frd` keeps 6 digits, so a node is matched to the nearest point within `tolerance` [mm]),
/// zero where no slave node reports. Records of zeros say nothing (the master's nodes, open
/// slaves) and are skipped; a record that matches no point is an error. The copies of one
/// meridian node (the wedge's faces and middle) must agree, else the output is not a field of the
/// axisymmetric solution.
pub fn on_meridian(
    block: &ContactBlock,
    nodes: &HashMap<u64, [f64; 3]>,
    points: &[[f64; 2]],
    tolerance: f64,
) -> Result<Vec<(f64, f64)>, String> {
    let mut found: Vec<Option<(f64, f64)>> = vec![None; points.len()];
    for (id, (open, pressure)) in block
        .values
        .iter()
        .map(|(id, v)| (id, (v[0], v[3])))
        .filter(|(_, v)| *v != (0.0, 0.0))
    {
        let [x, y, z] = *nodes.get(id).ok_or_else(|| {
            "job.frd: contact output at a node without coordinates (allowed: the nodes of the node block)"
                .to_owned()
        })?;
        let (r, height) = (x.hypot(z), y);
        let i = nearest(points, r, height)
            .filter(|&i| (points[i][0] - r).hypot(points[i][1] - height) <= tolerance)
            .ok_or_else(|| {
                "job.frd: contact output at a node off the slave surface (allowed: the slave nodes)"
                    .to_owned()
            })?;
        match found[i] {
            Some((_, p)) if (p - pressure).abs() > 1e-6 * p.abs().max(1.0) => {
                return Err(format!(
                    "job.frd: the copies of the meridian node at r = {} mm carry different pressures \
                     (allowed: one pressure, within 1e-6)",
                    points[i][0]
                ))
            }
            _ => found[i] = Some((open, pressure)),
        }
    }
    Ok(found.into_iter().map(|v| v.unwrap_or((0.0, 0.0))).collect())
}

/// The point of `points` (sorted by r) nearest (r, z), if any.
fn nearest(points: &[[f64; 2]], r: f64, z: f64) -> Option<usize> {
    let at = points.partition_point(|p| p[0] < r);
    let distance = |i: usize| (points[i][0] - r).hypot(points[i][1] - z);
    [at.checked_sub(1), Some(at)]
        .into_iter()
        .flatten()
        .filter(|&i| i < points.len())
        .min_by(|&a, &b| distance(a).total_cmp(&distance(b)))
}

/// The contact force totals (`*CONTACT PRINT, TOTALS=ONLY` with CF: "total surface force" of a
/// slave and master pair) in order; none where CalculiX printed none.
pub fn contact_totals(dat: &str) -> Vec<Total> {
    let lines: Vec<&str> = dat.lines().collect();
    let mut totals = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some((_, time)) = line
            .trim()
            .strip_prefix("statistics for slave set")
            .and_then(|l| l.split_once("and time"))
        else {
            continue;
        };
        let force = lines[i + 1..]
            .iter()
            .skip_while(|l| !l.contains("total surface force"))
            .skip(1)
            .find(|l| !l.trim().is_empty())
            .map(|l| l.split_whitespace().filter_map(finite).collect::<Vec<f64>>());
        if let (Some(time), Some([fx, fy, fz, ..])) = (finite(time.trim()), force.as_deref()) {
            totals.push(Total {
                time,
                force: [*fx, *fy, *fz],
            });
        }
    }
    totals
}

#[cfg(test)]
mod tests {
    use super::*;

    const DAT: &str = "
 total force (fx,fy,fz) for set NFAR and time  0.1000000E+01

       -1.505923E-02 -2.018877E+00  2.765801E-13

 total force (fx,fy,fz) for set NFAR and time  0.2000000E+01

       -3.342363E-02 -4.480983E+00  1.317428E-12

 total force (fx,fy,fz) for set NPLANE and time  0.2000000E+01

        0.000000E+00  4.480983E+00  0.000000E+00

 total force (fx,fy,fz) for set NFAR and time  0.2000000E+01

       -3.342407E-02 -4.481041E+00  4.327374E-13
";

    #[test]
    fn totals_are_read_per_set_and_the_last_of_each_time_kept() {
        let far = totals(DAT, "nfar").unwrap();
        assert_eq!(far.len(), 3);
        let steps = last_per_step(&far, |t| t.time, 2, "job.dat").unwrap();
        assert_eq!(steps[0].force[1], -2.018877);
        assert_eq!(steps[1].force[1], -4.481041);
        let plane = totals(DAT, "NPLANE").unwrap();
        assert_eq!(plane[0].force, [0.0, 4.480983, 0.0]);
        let e = last_per_step(&far, |t| t.time, 3, "job.dat").unwrap_err();
        assert!(e.contains("step 3 of 3"), "{e}");
    }

    #[test]
    fn contact_print_totals_are_read_where_printed() {
        let dat = "
 statistics for slave set SSPHERE, master set SPLANE and time  0.1000000E+01

   total surface force (fx,fy,fz) and moment about the origin (mx,my,mz)

    0.000000E+00  7.998643E+00  0.000000E+00  7.928228E-19  0.000000E+00  5.269544E+00
";
        let totals = contact_totals(dat);
        assert_eq!(
            totals,
            [Total {
                time: 1.0,
                force: [0.0, 7.998643, 0.0]
            }]
        );
        assert!(contact_totals(DAT).is_empty());
    }

    #[test]
    fn bad_totals_are_errors() {
        let e = totals(&DAT.replace("-2.018877E+00", "NaN"), "NFAR").unwrap_err();
        assert!(e.contains("line 2") && e.contains("three finite"), "{e}");
        let cut = &DAT[..DAT.find("-1.505923E-02").unwrap()];
        let e = totals(cut, "NFAR").unwrap_err();
        assert!(e.contains("truncated"), "{e}");
    }

    /// Three nodes of one meridian point (the wedge at −1°, 0°, +1°) and one at the axis, with a
    /// contact block at time 1 whose copies agree.
    fn frd(pressure_copy: &str) -> String {
        let node = |id: u32, x: f64, y: f64, z: f64| format!(" -1{id:>10}{x:>12.5E}{y:>12.5E}{z:>12.5E}\n");
        let (c, s) = (1.0_f64.to_radians().cos(), 1.0_f64.to_radians().sin());
        let contact = |id: u32, p: &str| {
            format!(" -1{id:>10}-3.85247E-07 0.00000E+00 0.00000E+00{p} 0.00000E+00 0.00000E+00\n")
        };
        format!(
            "    1C\n    2C                             4                                     1\n{}{}{}{} -3\n\
             \x20   1PSTEP                         2           1           1\n\
             \x20 100CL  101 1.000000000           3                     0    1           1\n\
             \x20-4  CONTACT     6    1\n -5  COPEN       1    4    1    1\n{}{}{} -3\n",
            node(1, 0.0, 0.0, 0.0),
            node(7, 0.5 * c, 1e-3, -0.5 * s),
            node(8, 0.5, 1e-3, 0.0),
            node(9, 0.5 * c, 1e-3, 0.5 * s),
            contact(7, " 4.81405E+02"),
            contact(8, " 4.81405E+02"),
            contact(9, pressure_copy),
        )
    }

    #[test]
    fn contact_blocks_map_onto_the_meridian() {
        let frd = parse_frd(&frd(" 4.81405E+02")).unwrap();
        assert_eq!((frd.nodes.len(), frd.contact.len()), (4, 1));
        assert_eq!(frd.contact[0].time, 1.0);
        let points = [[0.0, 0.0], [0.5, 1e-3], [0.7, 2e-3]];
        let values = on_meridian(&frd.contact[0], &frd.nodes, &points, 1e-4).unwrap();
        assert_eq!(values[0], (0.0, 0.0));
        assert_eq!(values[1], (-3.85247e-7, 481.405));
        assert_eq!(values[2], (0.0, 0.0));
    }

    #[test]
    fn disagreeing_copies_truncation_and_garbage_are_errors() {
        let frd_text = frd(" 3.00000E+02");
        let parsed = parse_frd(&frd_text).unwrap();
        let e = on_meridian(&parsed.contact[0], &parsed.nodes, &[[0.5, 1e-3]], 1e-4).unwrap_err();
        assert!(e.contains("copies"), "{e}");
        let e = on_meridian(&parsed.contact[0], &parsed.nodes, &[[0.6, 1e-3]], 1e-4).unwrap_err();
        assert!(e.contains("off the slave surface"), "{e}");
        let cut = frd_text.trim_end().trim_end_matches(" -3");
        let e = parse_frd(cut).unwrap_err();
        assert!(e.contains("truncated"), "{e}");
        let e = parse_frd(&frd_text.replace(" 4.81405E+02", " garbage!!!!")).unwrap_err();
        assert!(e.contains("six finite values"), "{e}");
    }
}
