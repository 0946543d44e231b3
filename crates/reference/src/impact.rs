//! The exact quasi-static reference of an impact: the impact problem ([`problem`]: bodies with
//! density, velocities and spins, the sweep of one initial condition), a contact law answering one
//! increment at a time ([`law`]: MDR's spring bed, exact Mindlin–Deresiewicz, or a DEM law),
//! integrated with the rigid-body dynamics of both bodies ([`integrator`]) into the rebound of
//! each impact ([`outcome`]), and Hertz's closed forms of normal impact ([`closed_form`]). A case may also name solvers of
//! its own ([`own_solver`]) whose outcomes come as sweep tables ([`table`]).

pub mod closed_form;
pub mod integrator;
pub mod law;
pub mod outcome;
pub mod own_solver;
pub mod problem;
pub mod table;
