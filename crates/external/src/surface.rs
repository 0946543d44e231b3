//! The contact line's nodal state that an axisymmetric deck writes at every computed step
//! (`surface.csv`: the candidate contact nodes, P2 vertices and mid-edge nodes, by r), and what is
//! measured from it.
//!
//! The decks apply contact by nodal quadrature, so each candidate node carries a ring force
//! 2π ω_i p_i with ω_i = ∫ N_i r ds its weight. The measures are those of `fem-axisym`, from the
//! same ring forces (one recovery for every axisymmetric model, [`spherecontact_solvers::fem::axisym::pressure`]): the
//! contact radius from a quadratic fit of p² at the edge, p0 from an even fit of the nodal
//! pressures on 0 < r ≤ c/2 (the axis node has ω = 0: its force says nothing about the pressure
//! there, and its penalty value is 1–3 % off). The stick radius is every solver's measure
//! ([`spherecontact_solvers::fit::stick`]): c √(stick area / contact area), the areas counted in the nodes' rings
//! ω_i, so it never exceeds c and is resolved to a node spacing.
//!
//! Units: the file is in mm, MPa; [`Node`] is SI.

use super::readback;
use spherecontact_model::history::{Layout, SurfaceField, TangentialComponents};
use spherecontact_solvers::fit::profile as pressure;

/// The columns of `surface.csv`, in order.
pub const SURFACE_COLUMNS: [&str; 8] = [
    "step",
    "r_mm",
    "weight_mm2",
    "gap_mm",
    "p_MPa",
    "qx_MPa",
    "stick",
    "slip_mm",
];

/// One candidate contact node at one step, SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node {
    /// Radius r [m].
    pub r: f64,
    /// Nodal quadrature weight ω = ∫ N r ds [m²] (per radian; zero on the axis).
    pub weight: f64,
    /// Height of the deformed surface above the contact plane [m] (negative: penetration).
    pub gap: f64,
    /// Contact pressure [Pa].
    pub pressure: f64,
    /// Tangential traction q_x on the x axis [Pa], signed so that ∫ q_x dA = Q.
    pub traction_x: f64,
    /// In contact and sticking.
    pub stick: bool,
    /// Relative displacement of the two surfaces along x on the x axis [m].
    pub slip: f64,
}

/// The candidate nodes of one computed step, by r.
#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    /// The path step.
    pub step: usize,
    /// The nodes, by r from the pole.
    pub nodes: Vec<Node>,
}

/// What is measured on the contact line at one step.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Measures {
    /// Contact radius [m] (0 out of contact).
    pub contact_radius: Option<f64>,
    /// Peak pressure p0 [Pa].
    pub peak_pressure: Option<f64>,
    /// Nodal pressures, the axis node's replaced by p0 [Pa].
    pub pressure: Vec<f64>,
}

impl Surface {
    /// Contact radius, p0 and the recovered nodal pressures (see the module doc).
    pub fn measures(&self) -> Measures {
        let radii: Vec<f64> = self.nodes.iter().map(|n| n.r).collect();
        let rings: Vec<f64> = self
            .nodes
            .iter()
            .map(|n| std::f64::consts::TAU * n.weight)
            .collect();
        let forces: Vec<f64> = self
            .nodes
            .iter()
            .zip(&rings)
            .map(|(n, w)| n.pressure * w)
            .collect();
        let profile = pressure::recover(&radii, &rings, &forces);
        Measures {
            contact_radius: profile.radius,
            peak_pressure: profile.peak,
            pressure: profile.pressure,
        }
    }

    /// Whether the outermost candidate carries pressure: the contact may reach beyond the
    /// candidate zone, and the step's answer is not that of the model.
    pub fn edge_loaded(&self) -> bool {
        self.nodes.last().is_some_and(|n| n.pressure > 0.0)
    }

    /// The stick radius of contact radius `contact_radius` by the measure of every solver
    /// ([`spherecontact_solvers::fit::stick::stick_radius`]: c √(stick area / contact area), the nodes' rings
    /// weighted by ω).
    pub fn stick_radius(&self, contact_radius: f64) -> f64 {
        let weights: Vec<f64> = self.nodes.iter().map(|n| n.weight).collect();
        let pressure: Vec<f64> = self.nodes.iter().map(|n| n.pressure).collect();
        let stick: Vec<bool> = self.nodes.iter().map(|n| n.stick).collect();
        spherecontact_solvers::fit::stick::stick_radius(contact_radius, &weights, &pressure, &stick)
    }

    /// Q by the nodal rule, 2π Σ ω q_x [N]: the same sum the deck reports, for a consistency
    /// check of the two files.
    pub fn tangential_force(&self) -> f64 {
        std::f64::consts::TAU * self.nodes.iter().map(|n| n.weight * n.traction_x).sum::<f64>()
    }

    /// The surface field at path position `position`: p (recovered, see [`Surface::measures`])
    /// and, when the tangential mode was solved, q_x, the stick/slip status and the slip.
    pub fn field(&self, position: usize, pressure: Vec<f64>, tangential: bool) -> SurfaceField {
        SurfaceField {
            position,
            points: self.nodes.iter().map(|n| [n.r, 0.0]).collect(),
            pressure,
            traction: tangential.then(|| self.nodes.iter().map(|n| [n.traction_x, 0.0]).collect()),
            stick: tangential.then(|| self.nodes.iter().map(|n| n.stick).collect()),
            slip: tangential.then(|| self.nodes.iter().map(|n| [n.slip, 0.0]).collect()),
            components: TangentialComponents::AlongX,
            layout: Layout::Profile,
        }
    }
}

/// Reads `surface.csv` from `text`: one block of candidate nodes per computed step, the steps
/// `steps` in order, every block with the same radii.
///
/// Fails, naming the line and column, on a wrong header, a value that is not a finite number, a
/// step that is not the one expected, blocks of different sizes, or missing blocks (a truncated
/// run).
pub fn parse_surface(text: &str, steps: &[usize]) -> Result<Vec<Surface>, String> {
    let mut surfaces: Vec<Surface> = Vec::with_capacity(steps.len());
    for row in readback::records(text, "surface.csv", &SURFACE_COLUMNS)? {
        let (step, node) = parse_node(&row)?;
        if surfaces.last().is_none_or(|s| s.step != step) {
            let expected = steps.get(surfaces.len()).copied();
            if expected != Some(step) {
                return Err(row.cell_error(0, not_the_next_step(expected)));
            }
            surfaces.push(Surface {
                step,
                nodes: Vec::new(),
            });
        }
        if let Some(current) = surfaces.last_mut() {
            current.nodes.push(node);
        }
    }
    let count = surfaces.first().map_or(0, |s| s.nodes.len());
    let short = surfaces.iter().position(|s| s.nodes.len() != count);
    if surfaces.len() != steps.len() || short == Some(surfaces.len() - 1) {
        return Err(format!(
            "surface.csv holds {} complete steps, expected {} (truncated output: the deck stopped early)",
            short.unwrap_or(surfaces.len()),
            steps.len()
        ));
    }
    if let Some(i) = short {
        return Err(format!(
            "surface.csv: step {} has {} nodes, the first step {count}",
            surfaces[i].step,
            surfaces[i].nodes.len()
        ));
    }
    Ok(surfaces)
}

/// What a step cell that does not continue the blocks is, with the step `expected` next.
pub(crate) fn not_the_next_step(expected: Option<usize>) -> String {
    match expected {
        Some(step) => format!("not the next computed step (allowed: {step} or the current step)"),
        None => "a step past the last computed one (allowed: the computed steps in order)".into(),
    }
}

fn parse_node(row: &readback::Row) -> Result<(usize, Node), String> {
    let number = |i: usize, scale: f64| row.finite(i, scale);
    Ok((
        row.whole(0, "a step index")?,
        Node {
            r: number(1, 1e-3)?,
            weight: number(2, 1e-6)?,
            gap: number(3, 1e-3)?,
            pressure: number(4, 1e6)?,
            traction_x: number(5, 1e6)?,
            stick: row.choice(6, &[("0", false), ("1", true)])?,
            slip: number(7, 1e-3)?,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "step,r_mm,weight_mm2,gap_mm,p_MPa,qx_MPa,stick,slip_mm";

    /// Hertz-like nodal data: c = 0.5 mm, p0 = 400 MPa, nodes every 0.025 mm to 0.7 mm,
    /// trapezoid weights r Δr; sticking inside r < 0.3 mm, slipping beyond (q = μ p).
    fn block(step: usize) -> String {
        let mut text = String::new();
        for i in 0..=28 {
            let r = 0.025 * f64::from(i);
            let p = 400.0 * (1.0 - (r / 0.5_f64).powi(2)).max(0.0).sqrt();
            let stick = u8::from(p > 0.0 && r < 0.3);
            let q = if stick == 1 { 0.1 * p } else { 0.2 * p };
            text.push_str(&format!("{step},{r},{},-1e-7,{p},{q},{stick},0\n", r * 0.025));
        }
        text
    }

    #[test]
    fn blocks_are_read_and_measured() {
        let text = format!("{HEADER}\n{}{}", block(3), block(7));
        let surfaces = parse_surface(&text, &[3, 7]).unwrap();
        assert_eq!(surfaces.len(), 2);
        assert_eq!(surfaces[1].step, 7);
        let m = surfaces[0].measures();
        // Exact Hertz nodal pressures: the edge fit of p² is exact, p0 within the fit's 2e-4.
        assert!((m.contact_radius.unwrap() - 0.5e-3).abs() < 1e-9, "{m:?}");
        assert!((m.peak_pressure.unwrap() / 400e6 - 1.0).abs() < 2e-4, "{m:?}");
        // Rings ω = r Δr (Δr = 0.025 mm) of the nodes i Δr: sticking i ≤ 11, loaded i ≤ 19, so
        // the areas are in the ratio Σ i: 66/190, and b = c √(66/190), between the last sticking
        // node (0.275 mm) and the innermost slipping one (0.3 mm).
        let stick = surfaces[0].stick_radius(m.contact_radius.unwrap());
        assert!(
            (stick - 0.5e-3 * (66.0_f64 / 190.0).sqrt()).abs() < 1e-12,
            "{stick}"
        );
        assert!(stick > 0.275e-3 && stick < 0.3e-3, "{stick}");
        assert!(!surfaces[0].edge_loaded());
        let field = surfaces[0].field(2, m.pressure, true);
        assert_eq!(field.points.len(), 29);
        assert!(field.stick.unwrap()[0] && field.traction.unwrap()[0][0] == 40e6);
    }

    #[test]
    fn full_stick_gives_c_and_gross_sliding_zero() {
        let mut surface = parse_surface(&format!("{HEADER}\n{}", block(0)), &[0])
            .unwrap()
            .remove(0);
        for n in &mut surface.nodes {
            n.stick = n.pressure > 0.0;
        }
        assert_eq!(surface.stick_radius(0.5e-3), 0.5e-3);
        for n in &mut surface.nodes {
            n.stick = false;
        }
        assert_eq!(surface.stick_radius(0.5e-3), 0.0);
    }

    #[test]
    fn truncated_wrong_or_nan_output_is_an_error() {
        let text = format!("{HEADER}\n{}{}", block(3), block(7));
        let cut = &text[..text.len() - 40];
        let e = parse_surface(cut, &[3, 7]).unwrap_err();
        assert!(e.contains("truncated"), "{e}");
        let e = parse_surface(&text, &[3, 8]).unwrap_err();
        assert!(
            e.starts_with("surface.csv:31: column `step`: not the next computed step (allowed: 8"),
            "{e}"
        );
        let e = parse_surface(&text.replacen("-1e-7", "nan", 1), &[3, 7]).unwrap_err();
        assert!(
            e.starts_with("surface.csv:2: column `gap_mm`: not a finite number"),
            "{e}"
        );
        assert!(!e.contains("nan"), "{e}");
        let e = parse_surface(&text.replacen(",1,0\n", ",SECRET,0\n", 1), &[3, 7]).unwrap_err();
        assert!(
            e.starts_with("surface.csv:2: column `stick`: not an allowed value (allowed: 0, 1)"),
            "{e}"
        );
        assert!(!e.contains("SECRET"), "{e}");
        let e = parse_surface("a,b\n", &[3]).unwrap_err();
        assert!(
            e.starts_with("surface.csv:1: header: column 1 is not `step`"),
            "{e}"
        );
        let e = parse_surface(&text, &[3]).unwrap_err();
        assert!(e.contains("a step past the last computed one"), "{e}");
    }
}
