//! Element kinds.
//!
//! | module | element |
//! |---|---|
//! | [`tri6`] | 6-node triangle of the meridian plane, axisymmetric (Fourier mode n = 0), r-weighted stiffness |
//! | [`tet10`] | 10-node tetrahedron of 3D elasticity (gmsh's node order), its stiffness and strain |
//! | [`face6`] | the 6-node triangular face of a tetrahedron and its contact rule (sub-triangulated pressure) |

pub mod face6;
pub mod tet10;
pub mod tri6;
