//! Meshes of one body.
//!
//! | module | mesh |
//! |---|---|
//! | [`meridian`] | the meridian (r, z) half-plane of an axisymmetric body: 6-node triangles, the in-crate graded generator |
//! | [`groups`] | the one gmsh MSH 4.1 reader of solid meshes (nodes, body elements of one type, faces of each physical surface) |
//! | [`msh`] | gmsh MSH 4.1 reader of meridian meshes |
//! | [`solid`] | a 3D body of 10-node tetrahedra with its boundary groups, read from gmsh MSH 4.1 |

pub mod geo;
pub mod solid_geo;

pub mod groups;
pub mod meridian;
pub mod msh;
pub mod solid;
