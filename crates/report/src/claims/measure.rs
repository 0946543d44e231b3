//! Measurements on a map of the surface fields at one path position — the transverse traction
//! q_y against q_x (pointwise and averaged over boxes) and its sign over the four quadrants, the
//! stick zone's semi-axes, where the largest |q| lies, how far p and |q| are from axisymmetric —
//! read through the layout-independent [`FieldView`].

use crate::figures::surface::{FieldView, HalfAxis, Layout};
use spherecontact_solvers::fit::square_root_edge;

/// Boxes per contact radius for the box-averaged traction: squares of side c/5 hold several
/// samples of either discretisation at the resolutions the reports use (BEM panels c/29 to c/58,
/// fem-3d nodes c/10 to c/14 apart), so the largest box average is read from a comparable
/// support on both. The pointwise maximum of q_y is a one-sample peak at the stick edge, where q_y
/// changes sign over a sample: on fem-3d's corner multipliers it moved from 0.056 to 0.066 of
/// max|q_x| under refinement of the mesh and the increments, while its c/5 box averages stayed
/// within 0.0445–0.0455 (BEM 128²: 0.043).
pub const BOXES_PER_RADIUS: f64 = 5.0;

/// p and |q| are compared along x and along y out to this fraction of the contact radius: at the
/// contact edge p falls as a square root, which a mesh's linear interpolation samples differently
/// along two axes (by up to p0 √(2h/c), 45 % of p0 at h = c/10), so the last tenth would measure
/// the mesh, not the field (as the pressure profile claim, which reads 0.1 c < r < 0.9 c).
pub const AXIS_READ: f64 = 0.9;

/// ∫ q_y dA over one quadrant, and over its stick and slip parts [N].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct QuadrantSums {
    /// Over the quadrant's contact.
    pub total: f64,
    /// Over its stick samples.
    pub stick: f64,
    /// Over its slip samples.
    pub slip: f64,
}

/// The largest |q| and where it lies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Peak {
    /// max |q| [Pa].
    pub value: f64,
    /// Its sample's position (x, y) [m].
    pub point: [f64; 2],
    /// The stick zone's edge in that direction [m] (the ellipse through the semi-axes), if fitted.
    pub edge: Option<f64>,
}

impl Peak {
    /// The peak's distance from the centre [m].
    pub fn radius(&self) -> f64 {
        self.point[0].hypot(self.point[1])
    }
}

/// What a map of p, q and stick/slip shows at one position.
#[derive(Clone, Debug, PartialEq)]
pub struct MapMeasures {
    /// The sample spacing h [m]: the resolution of every position below.
    pub spacing: f64,
    /// The largest |q_x| over the contact [Pa].
    pub qx_max: f64,
    /// The largest |q_y| over the contact [Pa].
    pub qy_max: f64,
    /// max|q̄_y| / max|q̄_x| on the values the contact rule determines: the hat averages of a map
    /// on triangles (a mesh's multipliers overshoot at single nodes at the stick edge), a grid's
    /// panel values ([`spherecontact_solvers::map_measure::transverse_ratio`], what the checks read); `None`
    /// without q_x.
    pub recovered_ratio: Option<f64>,
    /// The largest |area-weighted average| of q_x and of q_y over square boxes of side
    /// c/[`BOXES_PER_RADIUS`] on a grid with a corner at the centre [Pa].
    pub box_max: [f64; 2],
    /// ∫ q_y dA over the quadrants (x > 0, y > 0), (x < 0, y > 0), (x < 0, y < 0), (x > 0, y < 0).
    pub quadrants: [QuadrantSums; 4],
    /// The stick zone's semi-axes along x and y [m], each the mean of the two half-axes' edges.
    pub stick_axes: Option<[f64; 2]>,
    /// The stick zone's semi-axes along x and y [m] from its area-weighted second moments (the
    /// ellipse with the same moments, [`spherecontact_solvers::map_measure::stick_semi_axes`], what the checks
    /// read): integrals over the samples, less sensitive than an edge fit to where the discrete
    /// edge falls.
    pub stick_moments: Option<[f64; 2]>,
    /// The largest |q|.
    pub peak: Option<Peak>,
    /// The largest difference of |q| read along x and along y at the same r ≤ [`AXIS_READ`] c [Pa].
    pub axis_difference: f64,
    /// True when the samples read along x and along y sit alike (a square grid's centre row and
    /// column), so that sampling cannot differ between the axes; false on a mesh.
    pub axes_alike: bool,
    /// The largest p over the contact [Pa].
    pub pressure_max: f64,
    /// The largest difference of p read along x and along y at the same r ≤ [`AXIS_READ`] c [Pa].
    pub pressure_axis_difference: f64,
    /// The largest |q| − |q_x| [Pa]: what the transverse component adds to the magnitude.
    pub transverse_share: f64,
    /// The departure from an axisymmetric reference traction (MD's), if given: RMS over the
    /// contact of the transverse part q_y and of the parallel part q_x − q_md(r) [Pa].
    pub departure: Option<[f64; 2]>,
}

/// An axisymmetric traction q(r) along x read from a profile (MD's, from MDR), linearly
/// interpolated between its samples, zero beyond them.
#[derive(Clone, Debug, PartialEq)]
pub struct RadialProfile(Vec<(f64, f64)>);

impl RadialProfile {
    /// The profile of q_x in `view` along x; `None` without traction.
    pub fn of(view: &FieldView) -> Option<Self> {
        let samples: Option<Vec<(f64, f64)>> = view
            .along(HalfAxis::X)
            .iter()
            .map(|p| Some((p.r, view.at(p, |i| view.traction(i).map(|q| q[0]))?)))
            .collect();
        samples.filter(|s| s.len() >= 2).map(Self)
    }

    /// q(r) [Pa].
    pub fn at(&self, r: f64) -> f64 {
        let k = self.0.partition_point(|s| s.0 <= r);
        match (k.checked_sub(1).map(|j| self.0[j]), self.0.get(k)) {
            (Some(a), Some(b)) => a.1 + (b.1 - a.1) * (r - a.0) / (b.0 - a.0),
            (Some(a), None) if r == a.0 => a.1,
            _ => 0.0,
        }
    }

    /// The largest |q| and its radius (r [m], q [Pa]).
    pub fn peak(&self) -> (f64, f64) {
        self.0
            .iter()
            .copied()
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            .unwrap_or((0.0, 0.0))
    }
}

impl MapMeasures {
    /// The measures of a map with traction and stick/slip, with friction coefficient `friction`,
    /// contact radius `contact_radius` [m] (the boxes' scale) and, if given, MD's traction `md`
    /// to measure the departure from; `None` for a profile, a field without traction or status,
    /// or one whose model takes the traction along x (its q_y = 0 is assumed, not measured).
    pub fn of(
        view: &FieldView,
        friction: f64,
        contact_radius: f64,
        md: Option<&RadialProfile>,
    ) -> Option<Self> {
        let areas = view.areas()?;
        if !view.has_traction() || view.stick(0).is_none() || !view.resolves_transverse() {
            return None;
        }
        let contact: Vec<usize> = (0..view.len()).filter(|&i| view.in_contact(i)).collect();
        let traction = |i: usize| view.traction(i).unwrap_or([0.0, 0.0]);
        let largest = |f: &dyn Fn(usize) -> f64| contact.iter().map(|&i| f(i)).fold(0.0, f64::max);
        let mut quadrants = [QuadrantSums::default(); 4];
        for &i in &contact {
            let [x, y] = view.point(i);
            let Some(k) = quadrant(x, y) else { continue };
            let force = traction(i)[1] * areas[i];
            quadrants[k].total += force;
            if view.stick(i) == Some(true) {
                quadrants[k].stick += force;
            } else {
                quadrants[k].slip += force;
            }
        }
        let stick_axes = stick_axes(view, friction);
        let reach = AXIS_READ * contact_radius;
        let peak = contact
            .iter()
            .copied()
            .max_by(|&a, &b| magnitude(traction(a)).total_cmp(&magnitude(traction(b))))
            .map(|i| {
                let point = view.point(i);
                Peak {
                    value: magnitude(traction(i)),
                    point,
                    edge: stick_axes.map(|[ax, ay]| ellipse_radius(ax, ay, point)),
                }
            });
        Some(Self {
            spacing: view.spacing(),
            qx_max: largest(&|i| traction(i)[0].abs()),
            qy_max: largest(&|i| traction(i)[1].abs()),
            recovered_ratio: spherecontact_solvers::map_measure::transverse_ratio(view.field()),
            box_max: box_maxima(view, &areas, &contact, contact_radius / BOXES_PER_RADIUS),
            quadrants,
            stick_axes,
            peak,
            axis_difference: axis_difference(view, reach, &|i| Some(magnitude(view.traction(i)?))),
            axes_alike: !matches!(view.layout(), Layout::Triangles(_)),
            pressure_max: largest(&|i| view.pressure(i)),
            pressure_axis_difference: axis_difference(view, reach, &|i| Some(view.pressure(i))),
            stick_moments: spherecontact_solvers::map_measure::stick_semi_axes(view.field()),
            transverse_share: largest(&|i| magnitude(traction(i)) - traction(i)[0].abs()),
            departure: md.and_then(|md| departure(view, &|r| md.at(r))),
        })
    }

    /// True when q_y is odd in x and in y: opposite signs in neighbouring quadrants, equal
    /// magnitudes within `tolerance` of the largest.
    pub fn is_odd_in_x_and_y(&self, tolerance: f64) -> bool {
        let t: Vec<f64> = self.quadrants.iter().map(|q| q.total).collect();
        let scale = t.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        scale > 0.0
            && t.iter().enumerate().all(|(k, &v)| {
                let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                (v - sign * t[0]).abs() <= tolerance * scale
            })
    }
}

/// |q|.
fn magnitude(q: [f64; 2]) -> f64 {
    q[0].hypot(q[1])
}

/// The quadrant of (x, y), counter-clockwise from x > 0, y > 0; `None` on an axis.
fn quadrant(x: f64, y: f64) -> Option<usize> {
    match (x.partial_cmp(&0.0)?, y.partial_cmp(&0.0)?) {
        (std::cmp::Ordering::Greater, std::cmp::Ordering::Greater) => Some(0),
        (std::cmp::Ordering::Less, std::cmp::Ordering::Greater) => Some(1),
        (std::cmp::Ordering::Less, std::cmp::Ordering::Less) => Some(2),
        (std::cmp::Ordering::Greater, std::cmp::Ordering::Less) => Some(3),
        _ => None,
    }
}

/// The radius of the ellipse with semi-axes `ax`, `ay` in the direction of `point`.
fn ellipse_radius(ax: f64, ay: f64, point: [f64; 2]) -> f64 {
    let angle = point[1].atan2(point[0]);
    ax * ay / ((ay * angle.cos()).powi(2) + (ax * angle.sin()).powi(2)).sqrt()
}

/// The stick zone's edge on each half-axis from the stick deficit μp − |q| (zero where the
/// samples slip), which vanishes like a square root at the edge in Cattaneo's solution (see
/// [`square_root_edge`]); the semi-axes are the means of ±x and of ±y.
fn stick_axes(view: &FieldView, friction: f64) -> Option<[f64; 2]> {
    let edge = |axis: HalfAxis| {
        let samples: Vec<(f64, f64)> = view
            .along(axis)
            .iter()
            .map(|probe| {
                let sticks = view.stick(view.nearest(probe)) == Some(true);
                let deficit = view.at(probe, |i| {
                    let q = view.traction(i)?;
                    Some(friction * view.pressure(i) - magnitude(q))
                });
                (probe.r, if sticks { deficit.unwrap_or(0.0) } else { 0.0 })
            })
            .take_while(|&(_, d)| d > 0.0)
            .collect();
        square_root_edge(&samples)
    };
    let x = 0.5 * (edge(HalfAxis::X)? + edge(HalfAxis::MinusX)?);
    let y = 0.5 * (edge(HalfAxis::Y)? + edge(HalfAxis::MinusY)?);
    Some([x, y])
}

/// The largest difference of a sample quantity (|q|, p) read along +x and along +y at the same
/// distance (the samples of a grid's centre row and column sit at the same distances; a mesh's
/// probes step alike).
fn axis_difference(view: &FieldView, reach: f64, value: &dyn Fn(usize) -> Option<f64>) -> f64 {
    let profile = |axis| {
        view.along(axis)
            .iter()
            .filter(|p| p.r <= reach)
            .map(|p| (p.r, view.at(p, value)))
            .collect::<Vec<_>>()
    };
    profile(HalfAxis::X)
        .iter()
        .zip(profile(HalfAxis::Y))
        .filter_map(|(a, b)| Some((a.1? - b.1?).abs()).filter(|_| (a.0 - b.0).abs() < 1e-12))
        .fold(0.0, f64::max)
}

/// The largest |area-weighted average| of q_x and of q_y over the contact samples of square
/// boxes of side `side` [m] on the grid with a corner at the origin (0 without a positive side).
fn box_maxima(view: &FieldView, areas: &[f64], contact: &[usize], side: f64) -> [f64; 2] {
    if !side.is_finite() || side <= 0.0 {
        return [0.0, 0.0];
    }
    let mut boxes: std::collections::BTreeMap<(i64, i64), [f64; 3]> = Default::default();
    for &i in contact {
        let [x, y] = view.point(i);
        let key = ((x / side).floor() as i64, (y / side).floor() as i64);
        let q = view.traction(i).unwrap_or([0.0; 2]);
        let b = boxes.entry(key).or_insert([0.0; 3]);
        b[0] += q[0] * areas[i];
        b[1] += q[1] * areas[i];
        b[2] += areas[i];
    }
    boxes.values().filter(|b| b[2] > 0.0).fold([0.0, 0.0], |m, b| {
        [m[0].max((b[0] / b[2]).abs()), m[1].max((b[1] / b[2]).abs())]
    })
}

/// The departure of a map's traction from an axisymmetric traction q_md(r) along x (MD's):
/// the area-weighted RMS over the contact of the transverse part q_y and of the parallel part
/// q_x − q_md(r) [Pa].
fn departure(view: &FieldView, md: &dyn Fn(f64) -> f64) -> Option<[f64; 2]> {
    let areas = view.areas()?;
    let (mut transverse, mut parallel, mut area) = (0.0, 0.0, 0.0);
    for i in (0..view.len()).filter(|&i| view.in_contact(i)) {
        let q = view.traction(i)?;
        let [x, y] = view.point(i);
        transverse += q[1] * q[1] * areas[i];
        parallel += (q[0] - md(x.hypot(y))).powi(2) * areas[i];
        area += areas[i];
    }
    (area > 0.0).then(|| [(transverse / area).sqrt(), (parallel / area).sqrt()])
}

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_model::history::{Layout, SurfaceField, TangentialComponents};

    /// A grid with Cattaneo's traction (q_x only, stick disc of radius a, contact radius c) plus
    /// a transverse part ε·x·y inside the contact.
    fn cattaneo_grid(epsilon: f64) -> (SurfaceField, f64, f64) {
        let (n, h, c, a, mu) = (64usize, 1.0 / 28.0, 1.0, 0.5, 0.2);
        let points: Vec<[f64; 2]> = (0..n * n)
            .map(|k| [((k % n) as f64 - 32.0) * h, ((k / n) as f64 - 32.0) * h])
            .collect();
        let root = |s: f64, r: f64| (s * s - r * r).max(0.0).sqrt();
        let pressure: Vec<f64> = points.iter().map(|p| root(c, p[0].hypot(p[1]))).collect();
        let traction = points
            .iter()
            .map(|p| {
                let r = p[0].hypot(p[1]);
                let q = mu * (root(c, r) - root(a, r));
                [q, if r < c { epsilon * p[0] * p[1] } else { 0.0 }]
            })
            .collect();
        let stick = points.iter().map(|p| p[0].hypot(p[1]) < a).collect();
        let field = SurfaceField {
            position: 5,
            points,
            pressure,
            traction: Some(traction),
            stick: Some(stick),
            slip: None,
            components: TangentialComponents::InPlane,
            layout: Layout::Grid { spacing: h },
        };
        (field, a, h)
    }

    #[test]
    fn cattaneo_field_has_a_round_stick_zone_and_its_peak_on_the_edge() {
        let (field, a, h) = cattaneo_grid(0.0);
        let view = FieldView::of(&field);
        let m = MapMeasures::of(&view, 0.2, 1.0, None).expect("a map");
        let [ax, ay] = m.stick_axes.expect("a stick zone");
        // The deficit is exactly Cattaneo's √ form: the fit finds the edge to well under a sample.
        assert!(
            (ax - a).abs() < 0.05 * h && (ay - a).abs() < 0.05 * h,
            "{ax} {ay} vs {a}"
        );
        let peak = m.peak.unwrap();
        assert!(
            (peak.radius() - peak.edge.unwrap()).abs() <= h,
            "the cusp at r = a"
        );
        assert_eq!(m.qy_max, 0.0);
        assert_eq!(
            m.axis_difference, 0.0,
            "a grid reads the same along x and along y"
        );
        assert!(!m.is_odd_in_x_and_y(1e-9), "no q_y: no pattern");
    }

    #[test]
    fn a_transverse_part_odd_in_x_and_y_is_found_with_its_sign() {
        let (field, _, _) = cattaneo_grid(-0.01);
        let view = FieldView::of(&field);
        let m = MapMeasures::of(&view, 0.2, 1.0, None).expect("a map");
        assert!(m.is_odd_in_x_and_y(1e-9));
        assert!(
            m.quadrants[0].total < 0.0 && m.quadrants[1].total > 0.0,
            "q_y = −0.01 x y"
        );
        assert!(m.qy_max > 0.0 && m.transverse_share > 0.0);
        // A grid's panel value is its own average: the recovered ratio is the samples' ratio.
        assert_eq!(m.recovered_ratio, Some(m.qy_max / m.qx_max));
        // Against its own q_x as MD's: the whole departure is transverse.
        let root = |s: f64, r: f64| (s * s - r * r).max(0.0).sqrt();
        let [transverse, parallel] = departure(&view, &|r| 0.2 * (root(1.0, r) - root(0.5, r))).unwrap();
        assert!(transverse > 0.0 && parallel < 1e-15, "{transverse} {parallel}");
    }

    #[test]
    fn a_radial_profile_interpolates_linearly_and_vanishes_beyond() {
        let profile = RadialProfile(vec![(0.0, 1.0), (1.0, 3.0), (2.0, 0.0)]);
        assert_eq!(profile.at(0.5), 2.0);
        assert_eq!(profile.at(2.0), 0.0);
        assert_eq!(profile.at(5.0), 0.0);
        assert_eq!(profile.peak(), (1.0, 3.0));
    }
}
