//! The meridian mesh of one body, and the in-crate graded mesh generator.
//!
//! Frame: each body in its own meridian half-plane (r, z), r ≥ 0 the distance from the axis,
//! z the height above the contact plane; the body touches the plane at its pole (0, 0) and lies
//! in z ≥ 0. A sphere of radius R has its centre at (0, R) and surface z_s(r) = R − √(R² − r²);
//! a flat (R = ∞) has z_s = 0.
//!
//! The generated domain is either a sphere's cap of height H (the points within H of the
//! contact plane; H = R is the hemisphere), held on its flat cut face z = H, or the part of the
//! body within distance D of the pole, held on the arc |x| = D (for a flat, whose far field must
//! be cut somewhere). Rings of
//! nodes centred on the pole pass through surface points r_k; their spacing is the pole size h0
//! up to the fine radius (the contact zone) and grows linearly beyond it, and each ring gets as
//! many nodes as keep its arc spacing close to the radial one. Neighbouring rings are joined by
//! a strip of triangles; midside nodes then make them 6-node triangles, those on the sphere's
//! surface and on the far arc placed on the curve.

use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;

use spherecontact_model::domain::Grip;

/// A body's meridian mesh of 6-node triangles with its boundary node sets.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Node coordinates (r, z) [m].
    pub nodes: Vec<[f64; 2]>,
    /// Elements: corners counter-clockwise, then midsides of edges 0–1, 1–2, 2–0.
    pub triangles: Vec<[usize; 6]>,
    /// Nodes on the symmetry axis r = 0 (u_r = 0).
    pub axis: Vec<usize>,
    /// Nodes of the far boundary (the gripped face), displaced rigidly.
    pub far: Vec<usize>,
    /// The contact surface: quadratic edges (start, middle, end), ordered by r from the pole.
    pub surface: Vec<[usize; 3]>,
    /// The grip a mesh file was made for (its far face's physical tag); `None` for a generated
    /// mesh, which serves any grip.
    pub grip: Option<Grip>,
}

impl Mesh {
    /// Surface nodes ordered by r from the pole (each once).
    pub fn surface_nodes(&self) -> Vec<usize> {
        let mut nodes: Vec<usize> = self.surface.iter().flat_map(|e| [e[0], e[1]]).collect();
        if let Some(last) = self.surface.last() {
            nodes.push(last[2]);
        }
        nodes
    }

    /// The pole element size: the radial extent of the first surface edge.
    pub fn pole_size(&self) -> f64 {
        self.surface
            .first()
            .map(|e| self.nodes[e[2]][0] - self.nodes[e[0]][0])
            .unwrap_or(0.0)
    }
}

/// What the graded generator builds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grading {
    /// Body radius R [m]; `f64::INFINITY` for a flat.
    pub radius: f64,
    /// The extent of the meshed body.
    pub domain: Domain,
    /// Element size h0 at the pole and throughout the fine zone [m].
    pub pole_size: f64,
    /// Surface radius of the uniformly fine zone [m].
    pub fine_radius: f64,
    /// Growth of the element size per unit distance beyond the fine zone (h = h0 + g (r − r_f)).
    pub growth: f64,
}

/// The extent of the meshed body and its far (gripped) boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Domain {
    /// The points within distance D ≤ R of the pole; far boundary: the arc |x| = D.
    Lens(f64),
    /// A sphere's cap of height H ≤ R (H = R: the hemisphere); far boundary: the flat cut face
    /// z = H.
    Cap(f64),
}

/// Why a mesh cannot be built or read.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// Parameters out of range.
    #[error("mesh parameters: {0}")]
    Parameters(String),
    /// An element with non-positive Jacobian.
    #[error("element {0} is inverted or degenerate")]
    Inverted(usize),
    /// A mesh file that cannot be used.
    #[error("mesh file: {0}")]
    File(String),
}

impl Grading {
    /// Surface height z_s(r) of the body above the contact plane.
    pub fn surface_height(&self, r: f64) -> f64 {
        surface_height(self.radius, r)
    }

    /// The largest distance from the pole: D, or √(2RH) for a cap (its rim; √2 R for the
    /// hemisphere's equator).
    pub fn extent(&self) -> f64 {
        match self.domain {
            Domain::Lens(d) => d,
            Domain::Cap(height) => (2.0 * self.radius * height).sqrt(),
        }
    }

    fn check(&self) -> Result<(), MeshError> {
        let extent = self.extent();
        let fits = match self.domain {
            Domain::Lens(d) => d <= self.radius,
            Domain::Cap(height) => {
                self.radius.is_finite() && height > 2.0 * self.pole_size && height <= self.radius
            }
        };
        let ok = self.pole_size > 0.0
            && extent > 2.0 * self.pole_size
            && fits
            && self.fine_radius >= 0.0
            && self.growth > 0.0
            && [self.pole_size, extent, self.fine_radius, self.growth]
                .iter()
                .all(|v| v.is_finite());
        ok.then_some(()).ok_or_else(|| {
            MeshError::Parameters(format!(
                "need 0 < 2 h0 < D ≤ R (a cap only of a sphere, 2 h0 < H ≤ R), finite, growth > 0; got \
                 h0 = {:e} m, extent {extent:e} m, R = {:e} m, growth {}",
                self.pole_size, self.radius, self.growth
            ))
        })
    }

    /// Element size at surface radius r.
    fn size(&self, r: f64) -> f64 {
        self.pole_size + self.growth * (r - self.fine_radius).max(0.0)
    }

    /// Angle from the r axis of the surface point at distance d from the pole. On a sphere a
    /// chord d from the pole subtends 2 asin(d/2R) at the centre; its angle to the tangent
    /// plane is half that.
    fn surface_angle(&self, d: f64) -> f64 {
        if self.radius.is_finite() {
            (d / (2.0 * self.radius)).asin()
        } else {
            0.0
        }
    }

    /// The height of the cut face: H for a cap, none for a lens.
    fn cut(&self) -> f64 {
        match self.domain {
            Domain::Cap(height) => height,
            Domain::Lens(_) => f64::INFINITY,
        }
    }

    /// Angle from the r axis where the ring at distance d ends: on the axis (d ≤ H), or on the
    /// cut face z = H beyond it.
    fn end_angle(&self, d: f64) -> f64 {
        if d > self.cut() {
            (self.cut() / d).asin()
        } else {
            FRAC_PI_2
        }
    }

    /// The midside node of the surface edge p–q: at the mean radius in the fine zone, so that
    /// the two bodies of a pair share their candidate node radii; beyond it at the arc's mid
    /// angle, which keeps the large edges near a sphere's equator (where z_s(r) is steep) well
    /// shaped.
    fn surface_midpoint(&self, p: [f64; 2], q: [f64; 2]) -> [f64; 2] {
        let r = 0.5 * (p[0] + q[0]);
        if p[0].max(q[0]) <= self.fine_radius || !self.radius.is_finite() {
            return [r, self.surface_height(r)];
        }
        let angle = |x: [f64; 2]| x[0].atan2(self.radius - x[1]);
        let theta = 0.5 * (angle(p) + angle(q));
        [self.radius * theta.sin(), self.radius * (1.0 - theta.cos())]
    }

    /// Surface radius of the ring at distance d from the pole.
    fn ring_radius(&self, d: f64) -> f64 {
        d * self.surface_angle(d).cos()
    }

    /// The ring distances d_k from the pole: d_0 = 0 (the pole itself), last = the extent.
    /// A cap has a ring at exactly d = H (where the axis meets the cut face) and ends at its rim.
    fn rings(&self) -> Vec<f64> {
        let extent = self.extent();
        let mut marks = vec![extent];
        if let Domain::Cap(height) = self.domain {
            if height < extent {
                marks.insert(0, height);
            }
        }
        let mut rings = vec![0.0];
        let mut r = 0.0;
        for mark in marks {
            loop {
                r += self.size(r);
                let d = r.hypot(self.surface_height(r));
                if d >= mark - 0.3 * self.size(r) {
                    rings.push(mark);
                    r = self.ring_radius(mark);
                    break;
                }
                rings.push(d);
            }
        }
        rings
    }
}

/// Surface height z_s(r) = R − √(R² − r²) of a body of radius R (0 for a flat).
pub fn surface_height(radius: f64, r: f64) -> f64 {
    if radius.is_finite() {
        // R − √(R² − r²) = r² / (R + √(R² − r²)), without cancellation.
        r * r / (radius + (radius * radius - r * r).max(0.0).sqrt())
    } else {
        0.0
    }
}

/// Builds the graded mesh described by `grading`.
pub fn graded(grading: &Grading) -> Result<Mesh, MeshError> {
    grading.check()?;
    let rings = grading.rings();
    let mut builder = Builder::default();
    let mut previous = builder.ring(grading, 0.0, 0);
    for (k, &d) in rings.iter().enumerate().skip(1) {
        let h = grading
            .size(grading.ring_radius(d))
            .min(d - rings[k - 1])
            .max(1e-300);
        let arc = d * (grading.end_angle(d) - grading.surface_angle(d));
        let segments = if arc > 1e-12 * d {
            ((arc / h).round() as usize).max(1)
        } else {
            0
        };
        let ring = builder.ring(grading, d, segments);
        builder.strip(&previous, &ring);
        previous = ring;
    }
    builder.finish(grading, &previous)
}

/// Linear triangles and ring bookkeeping before midside nodes are added.
#[derive(Default)]
struct Builder {
    nodes: Vec<[f64; 2]>,
    corners: Vec<[usize; 3]>,
    surface: Vec<usize>,
}

impl Builder {
    /// Adds a ring at distance d with `segments` arcs from the surface to the axis (or the
    /// equatorial face); returns its node indices, surface first.
    fn ring(&mut self, g: &Grading, d: f64, segments: usize) -> Vec<usize> {
        let (start, end) = (g.surface_angle(d), g.end_angle(d));
        let ids: Vec<usize> = (0..=segments)
            .map(|j| {
                let phi = start + (end - start) * j as f64 / segments.max(1) as f64;
                let point = if let (0, Domain::Cap(height), true) = (j, g.domain, d >= g.extent()) {
                    // The rim, exactly on the cut face (its surface height R − √(R² − r²) is
                    // ill-conditioned there: at H = R the root of a difference near zero).
                    [(height * (2.0 * g.radius - height)).sqrt(), height]
                } else if j == 0 {
                    let r = g.ring_radius(d);
                    [r, g.surface_height(r)]
                } else if j == segments && d > g.cut() {
                    [(d * d - g.cut() * g.cut()).sqrt(), g.cut()]
                } else if j == segments {
                    [0.0, d]
                } else {
                    [d * phi.cos(), d * phi.sin()]
                };
                self.nodes.push(point);
                self.nodes.len() - 1
            })
            .collect();
        let ids = if segments == 0 { ids[..1].to_vec() } else { ids };
        self.surface.push(ids[0]);
        ids
    }

    /// Joins two rings by triangles, advancing along whichever ring is behind in arc
    /// parameter (the classic strip triangulation between two polylines), unless that triangle
    /// would fold over its neighbours and the other would not: where the rings end on different
    /// boundaries (the axis and a cap's cut face) their parameters no longer match in space.
    fn strip(&mut self, inner: &[usize], outer: &[usize]) {
        let t = |ring: &[usize], i: usize| i as f64 / (ring.len() - 1).max(1) as f64;
        // Rings run from the surface towards the axis: an unfolded strip triangle, written
        // (inner, outer, next), turns clockwise in (r, z).
        let unfolded = |[a, b, c]: [usize; 3]| {
            let (p, q, s) = (self.nodes[a], self.nodes[b], self.nodes[c]);
            (q[0] - p[0]) * (s[1] - p[1]) - (s[0] - p[0]) * (q[1] - p[1]) > 0.0
        };
        let (mut i, mut j) = (0, 0);
        while i + 1 < inner.len() || j + 1 < outer.len() {
            let along_inner = (i + 1 < inner.len()).then(|| [inner[i], outer[j], inner[i + 1]]);
            let along_outer = (j + 1 < outer.len()).then(|| [inner[i], outer[j], outer[j + 1]]);
            let advance_inner = match (along_inner, along_outer) {
                (Some(a), Some(b)) => {
                    let behind = t(inner, i + 1) <= t(outer, j + 1);
                    let (ok_a, ok_b) = (unfolded(a), unfolded(b));
                    if behind {
                        ok_a || !ok_b
                    } else {
                        !ok_b && ok_a
                    }
                }
                (Some(_), None) => true,
                _ => false,
            };
            let tri = if advance_inner {
                i += 1;
                [inner[i - 1], outer[j], inner[i]]
            } else {
                j += 1;
                [inner[i], outer[j - 1], outer[j]]
            };
            self.corners.push(self.counter_clockwise(tri));
        }
    }

    fn counter_clockwise(&self, [a, b, c]: [usize; 3]) -> [usize; 3] {
        let (p, q, s) = (self.nodes[a], self.nodes[b], self.nodes[c]);
        let area = (q[0] - p[0]) * (s[1] - p[1]) - (s[0] - p[0]) * (q[1] - p[1]);
        if area > 0.0 {
            [a, b, c]
        } else {
            [a, c, b]
        }
    }

    /// Adds midside nodes and boundary sets.
    fn finish(self, g: &Grading, far_ring: &[usize]) -> Result<Mesh, MeshError> {
        let Builder {
            mut nodes,
            corners,
            surface,
        } = self;
        let on_surface: HashMap<usize, usize> = surface.iter().enumerate().map(|(k, &n)| (n, k)).collect();
        let on_far: std::collections::HashSet<usize> = far_ring.iter().copied().collect();
        let mut midside: HashMap<(usize, usize), usize> = HashMap::new();
        let mut triangles = Vec::with_capacity(corners.len());
        for c in &corners {
            let mut t = [c[0], c[1], c[2], 0, 0, 0];
            for (e, (a, b)) in [(c[0], c[1]), (c[1], c[2]), (c[2], c[0])].into_iter().enumerate() {
                let key = (a.min(b), a.max(b));
                t[3 + e] = *midside.entry(key).or_insert_with(|| {
                    let (p, q) = (nodes[a], nodes[b]);
                    let point = if on_surface.contains_key(&a) && on_surface.contains_key(&b) {
                        g.surface_midpoint(p, q)
                    } else if let (Domain::Lens(d), true) =
                        (g.domain, on_far.contains(&a) && on_far.contains(&b))
                    {
                        let phi = 0.5 * (p[1].atan2(p[0]) + q[1].atan2(q[0]));
                        [d * phi.cos(), d * phi.sin()]
                    } else {
                        [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]
                    };
                    nodes.push(point);
                    nodes.len() - 1
                });
            }
            triangles.push(t);
        }
        let mid = |a: usize, b: usize| midside[&(a.min(b), a.max(b))];
        let surface_edges = surface
            .windows(2)
            .map(|w| [w[0], mid(w[0], w[1]), w[1]])
            .collect();
        let far_nodes: Vec<usize> = match g.domain {
            Domain::Lens(_) => far_ring
                .iter()
                .copied()
                .chain(far_ring.windows(2).map(|w| mid(w[0], w[1])))
                .collect(),
            Domain::Cap(height) => (0..nodes.len())
                .filter(|&n| (nodes[n][1] - height).abs() <= 1e-12 * g.radius)
                .collect(),
        };
        let axis = (0..nodes.len()).filter(|&n| nodes[n][0] == 0.0).collect();
        let mesh = Mesh {
            nodes,
            triangles,
            axis,
            far: far_nodes,
            surface: surface_edges,
            grip: None,
        };
        validate(&mesh)?;
        Ok(mesh)
    }
}

/// Rejects meshes with an inverted or degenerate element.
pub fn validate(mesh: &Mesh) -> Result<(), MeshError> {
    for (e, t) in mesh.triangles.iter().enumerate() {
        let x = t.map(|n| mesh.nodes[n]);
        let ok = spherecontact_model::quadrature::triangle_degree4()
            .iter()
            .chain(&spherecontact_model::quadrature::triangle_degree2())
            .all(|p| crate::fem::element::tri6::map(&x, p.at).is_some());
        if !ok {
            return Err(MeshError::Inverted(e));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Meridian area by the isoparametric map (curved edges included).
    fn meridian_area(mesh: &Mesh) -> f64 {
        mesh.triangles
            .iter()
            .flat_map(|t| {
                let x = t.map(|n| mesh.nodes[n]);
                spherecontact_model::quadrature::triangle_degree4()
                    .into_iter()
                    .map(move |p| crate::fem::element::tri6::map(&x, p.at).unwrap().det * p.weight)
            })
            .sum()
    }

    fn sphere() -> Grading {
        Grading {
            radius: 0.1,
            domain: Domain::Lens(0.1),
            pole_size: 1e-4,
            fine_radius: 1e-3,
            growth: 0.3,
        }
    }

    #[test]
    fn graded_mesh_covers_the_lens_and_is_valid() {
        let mesh = graded(&sphere()).unwrap();
        let area = meridian_area(&mesh);
        // Lens: circular sector of the pole-centred disc from 30° to 90° (area R²π/6) plus the
        // segment of the sphere between the pole and the 60° surface point (R²(π/3 − sin 60°)/2).
        let r = 0.1f64;
        let exact = r * r * std::f64::consts::PI / 6.0
            + 0.5 * r * r * (std::f64::consts::PI / 3.0 - (3.0f64).sqrt() / 2.0);
        // Quadratic arcs: the far arc's and surface's geometric error is O(h⁴) per unit length.
        assert!((area - exact).abs() / exact < 1e-4, "area {area} vs {exact}");
        assert!((mesh.pole_size() - 1e-4).abs() < 1e-12);
        let s = mesh.surface_nodes();
        assert_eq!(s[0], 0);
        assert!(s.windows(2).all(|w| mesh.nodes[w[1]][0] > mesh.nodes[w[0]][0]));
        for n in &s {
            let [r, z] = mesh.nodes[*n];
            assert!((z - surface_height(0.1, r)).abs() < 1e-15);
        }
    }

    #[test]
    fn hemisphere_mesh_has_the_quarter_disc_area_and_a_flat_far_face() {
        let g = Grading {
            domain: Domain::Cap(0.1),
            ..sphere()
        };
        let mesh = graded(&g).unwrap();
        let exact = std::f64::consts::FRAC_PI_4 * 0.01;
        let err = (meridian_area(&mesh) - exact).abs() / exact;
        assert!(err < 1e-4, "area error {err}");
        assert!(mesh.far.iter().all(|&n| (mesh.nodes[n][1] - 0.1).abs() < 1e-15));
        assert!(
            mesh.far.contains(&mesh.surface.last().unwrap()[2]),
            "equator is far"
        );
    }

    #[test]
    fn cap_mesh_has_the_segment_area_a_flat_cut_face_and_ends_at_the_rim() {
        // Shallow to deep: where the rings end on the cut face and on the axis, the strip
        // triangulation must not fold (a fold adds area).
        for h in [0.01f64, 0.02, 0.05, 0.08] {
            cap_is_exact(0.1, h);
        }
    }

    fn cap_is_exact(r: f64, h: f64) {
        let mesh = graded(&Grading {
            domain: Domain::Cap(h),
            ..sphere()
        })
        .unwrap();
        // ∫₀^H √(R² − (z − R)²) dz, with t = z − R: [t √(R² − t²)/2 + R² asin(t/R)/2] from −R to H − R.
        let primitive = |t: f64| 0.5 * t * (r * r - t * t).sqrt() + 0.5 * r * r * (t / r).asin();
        let exact = primitive(h - r) - primitive(-r);
        let err = (meridian_area(&mesh) - exact).abs() / exact;
        // Quadratic arcs and a straight cut: geometric error O(h⁴) per unit length.
        assert!(err < 1e-4, "H = {h}: area error {err}");
        assert!(mesh.far.iter().all(|&n| (mesh.nodes[n][1] - h).abs() < 1e-15));
        let rim = mesh.nodes[mesh.surface.last().unwrap()[2]];
        assert!((rim[0] - (h * (2.0 * r - h)).sqrt()).abs() < 1e-12 && (rim[1] - h).abs() < 1e-15);
        assert!(
            mesh.far.iter().any(|&n| mesh.nodes[n][0] == 0.0),
            "the axis meets the cut face"
        );
    }

    #[test]
    fn rejects_a_domain_larger_than_the_body() {
        let g = Grading {
            domain: Domain::Lens(0.2),
            ..sphere()
        };
        assert!(graded(&g).is_err());
        let g = Grading {
            radius: f64::INFINITY,
            domain: Domain::Cap(0.1),
            ..sphere()
        };
        assert!(graded(&g).is_err());
        let g = Grading {
            domain: Domain::Cap(0.15),
            ..sphere()
        };
        assert!(graded(&g).is_err(), "a cap higher than the radius");
    }
}
