//! Meshes of one body.
//!
//! | module | mesh |
//! |---|---|
//! | [`meridian`] | the meridian (r, z) half-plane of an axisymmetric body: 6-node triangles, the in-crate graded generator |
//! | [`msh`] | gmsh MSH 4.1 reader of meridian meshes |

pub mod meridian;
pub mod msh;
