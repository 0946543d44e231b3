//! The half contact surface y ≥ 0 of a 3D model mirrored into the whole plane: the layout of the
//! surface fields that `fem-3d` and the `fenicsx-3d` deck both report.
//!
//! Two identical spheres shifted along x are symmetric in the plane y = 0, so the models keep the
//! half y ≥ 0. The whole surface is the half's nodes in order, then the images of the nodes off
//! the plane (y → −y) in the same order; a node on the plane is its own image. Under the mirror
//! p, q_x and slip_x are even and q_y and slip_y odd; each image triangle has its orientation
//! reversed, so that all triangles face the same way.

/// The mirror map of a half surface.
#[derive(Clone, Debug, PartialEq)]
pub struct Mirror {
    /// The half's nodes that have an image (off the plane y = 0), in order.
    off_plane: Vec<usize>,
    /// The whole surface's index of each half node's image (itself on the plane).
    image: Vec<usize>,
}

impl Mirror {
    /// The mirror of a half surface whose nodes lie on the plane y = 0 where `on_plane` says so.
    pub fn new(on_plane: &[bool]) -> Self {
        let off_plane: Vec<usize> = (0..on_plane.len()).filter(|&j| !on_plane[j]).collect();
        let mut image: Vec<usize> = (0..on_plane.len()).collect();
        for (k, &j) in off_plane.iter().enumerate() {
            image[j] = on_plane.len() + k;
        }
        Self { off_plane, image }
    }

    /// An even nodal value (p, q_x, status) on the whole surface.
    pub fn even<T: Copy>(&self, half: &[T]) -> Vec<T> {
        half.iter()
            .copied()
            .chain(self.off_plane.iter().map(|&j| half[j]))
            .collect()
    }

    /// An in-plane vector whose y component is odd (the points, q, slip) on the whole surface.
    pub fn odd_y(&self, half: &[[f64; 2]]) -> Vec<[f64; 2]> {
        half.iter()
            .copied()
            .chain(self.off_plane.iter().map(|&j| [half[j][0], -half[j][1]]))
            .collect()
    }

    /// The half's triangles (indices of its nodes) and their images, as whole-surface indices.
    pub fn triangles(&self, half: &[[usize; 3]]) -> Vec<[usize; 3]> {
        let image = |&[a, b, c]: &[usize; 3]| [self.image[a], self.image[c], self.image[b]];
        half.iter().copied().chain(half.iter().map(image)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_off_the_plane_and_one_on_it_mirror_into_the_whole_plane() {
        // nodes 0 and 1 on the plane, 2 and 3 above it
        let mirror = Mirror::new(&[true, true, false, false]);
        let points = mirror.odd_y(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]);
        assert_eq!(points[4], [0.0, -1.0]);
        assert_eq!(points[5], [1.0, -1.0]);
        assert_eq!(mirror.even(&[1, 2, 3, 4]), [1, 2, 3, 4, 3, 4]);
        let triangles = mirror.triangles(&[[0, 1, 2], [1, 3, 2]]);
        assert_eq!(triangles, [[0, 1, 2], [1, 3, 2], [0, 4, 1], [1, 4, 5]]);
        // every triangle keeps its orientation (z of the edge cross product) on the whole plane
        let z = |[a, b, c]: [usize; 3]| {
            let (p, q, r) = (points[a], points[b], points[c]);
            (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
        };
        let signs: Vec<bool> = triangles.iter().map(|&t| z(t) > 0.0).collect();
        assert!(signs.iter().all(|&s| s == signs[0]), "{signs:?}");
    }
}
