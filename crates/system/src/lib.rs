//! # spherecontact-system: the harness's dealings with the operating system
//!
//! **Job.** Everything that touches files and programs, done once and by rule: [`text`] made safe
//! to show (control characters, secrets), files read with limits ([`input`], and
//! [`input::foreign`] for the files that come from elsewhere), outputs written atomically into a
//! claimed folder ([`io`]), programs run under a deadline with their output bounded and their
//! descendants reaped ([`process`], [`bounded_log`], [`descendants`], [`reap`]), their logs
//! excerpted and masked ([`excerpt`], [`mask`]), and the programs found ([`toolchain`]).
//!
//! **May depend on.** `spherecontact-model` (the limits and the progress a run reports).
//!
//! **Offers.** The mechanisms every solver of an external program and every command of the
//! verification job share: none of them opens a file or starts a program any other way.

pub mod bounded_log;
pub mod descendants;
pub mod excerpt;
pub mod input;
pub mod io;
pub mod mask;
pub mod permission;
pub mod process;
pub mod reap;
pub mod text;
pub mod toolchain;
