//! Element kinds.
//!
//! | module | element |
//! |---|---|
//! | [`tri6`] | 6-node triangle of the meridian plane, axisymmetric (Fourier mode n = 0), r-weighted stiffness |

pub mod tri6;
