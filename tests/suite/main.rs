//! The integration tests, one binary (one link, one process; fixtures shared through `common`).
//! Each module was once its own test file: run one with `cargo test --test suite NAME::`,
//! heavy ones with `-- --ignored`.

mod case_solvers;
mod cli;
mod closed_forms;
mod common;
mod contact_engine;
mod contact_measures;
mod dem_codes;
mod dem_laws;
mod domain_compliance;
mod external;
mod external_3d;
mod external_calculix;
mod external_friction;
mod fem3d_element;
mod fem3d_friction;
mod fem3d_hertz;
mod fem3d_mesh;
mod fem3d_surface;
mod fem_element;
mod fem_friction;
mod fem_gmsh_mesh;
mod fem_hard_cases;
mod fem_hertz;
mod fem_msh;
mod fuzz_case;
mod hostile_bounded;
mod hostile_cases;
mod hostile_cli;
mod hostile_commands;
mod hostile_extreme;
mod hostile_findings;
mod hostile_reads;
mod hostile_writes;
mod house;
mod impact;
mod mdr_reference;
mod path_walker;
mod plot_layout;
mod report_browser;
mod reports;
mod resolution;
mod scale;
mod solid_common;
mod tangential_laws;
