//! What a case may ask for: the ranges of its physical values and the resources of its run.
//!
//! The ranges keep every derived quantity (E*, R*, G*, the Hertz force, radius and pressure, the
//! stiffnesses) a normal floating-point number far from overflow, and hold the loading to the
//! small-displacement setting that every model here assumes. The resource limits make every
//! valid case solve in bounded memory on an ordinary machine: no limit here is hit by a case that
//! means something physically.

use crate::resolution::PoleLimits;

/// The largest case or reference file read [bytes] (4 MiB): parsing costs about 30 bytes of
/// memory per byte of TOML, and a case that lists a million positions is under 3 MiB.
pub const MAX_INPUT_BYTES: u64 = 4 << 20;

/// The largest stored-results file (`[[stored_results]]`, a History CSV) [bytes] (256 MiB): the
/// longest path ([`MAX_INCREMENTS`] increments) written with all nine columns at 17 significant
/// digits is about 200 MB. The file is read row by row into the steps (about 100 bytes each), so
/// this bounds the time of the read and the longest row held at once, not the memory of the steps.
pub const MAX_STORED_RESULTS_BYTES: u64 = 256 << 20;

/// The longest case name [characters].
pub const MAX_NAME_CHARS: usize = 64;

/// The radius of a sphere [m]: a nanoparticle to a boulder (or `inf` for a flat).
pub const RADIUS_RANGE: [f64; 2] = [1e-9, 1e3];

/// Young's modulus [Pa]: a soft gel (kPa) to diamond (1.2e12 Pa), with a decade to spare.
pub const YOUNG_RANGE: [f64; 2] = [1e3, 1e13];

/// The largest Coulomb coefficient: measured dry-friction coefficients lie between about 0.05
/// and 2; 10 leaves room for adhesive, high-friction studies.
pub const MAX_FRICTION: f64 = 10.0;

/// The most increments a path may have in all: each step keeps a row of every solver's history
/// (about 100 bytes) and `run` builds the JSON text of a history in memory (about 300 bytes a
/// row), so this bounds the memory of the histories: 0.43 GB peak for `run` of one solver on
/// 10⁶ increments (measured, MDR and hertz-mindlin-spring).
pub const MAX_INCREMENTS: usize = 1_000_000;

/// The most path positions at which solvers keep surface fields: a BEM field at 64² panels costs
/// about 1 MB of memory and 0.75 MB of JSON, at the largest grid (`MAX_BEM_GRID`) 64 times that;
/// 16 positions hold every position of the shipped cases. Measured (`run --solver bem`): 100 000
/// reversals, fields at the focus only, peak 75 MB (it passed 20 GB when every position kept
/// its field).
pub const MAX_FIELD_POSITIONS: usize = 16;

/// The largest BEM grid [panels a side]: 512² panels cost about 0.1 GB for the solve (FFT
/// kernels on the doubled grid), 4 times the finest rung of the BEM's own ladder.
pub const MAX_BEM_GRID: usize = 512;

/// The most springs of an MDR bed (three `f64` each: 24 MB), 62 times its default.
pub const MAX_MDR_SPRINGS: usize = 1_000_000;

/// The finest mesh [pole elements per largest contact radius]: 4 times the finest rung of the
/// FEM ladder (c/80). A meridian mesh uniform at size h over 1.5 c_max around the pole has about
/// 8.2 (c_max/h)² triangles: 0.84 million at c_max/320, a few seconds for gmsh. The in-crate
/// FEM's memory grows as (c_max/h)² log(c_max/h) (the factor's fill): a frictional fem-axisym
/// run on the paper's spheres passes [`MEMORY_BUDGET`] near c_max/200 (estimated 2.0 GB at
/// c_max/160, 8.7 GB at c_max/320, of which 4.5 GB the n = 1 factor) and is refused beyond,
/// before it factors ([`crate::memory`]); the decks are separate programs under their own
/// timeouts.
pub const MAX_ELEMENTS_PER_CONTACT_RADIUS: f64 = 320.0;

/// The pole element sizes a meridian mesh may take (fem-axisym, mdr-domain, the axisymmetric
/// decks, `mesh`): c_max/320 ([`MAX_ELEMENTS_PER_CONTACT_RADIUS`], under a million triangles) to
/// c_max/2 (the contact spans at least two pole elements).
pub const MERIDIAN_POLE: PoleLimits = PoleLimits {
    finest: MAX_ELEMENTS_PER_CONTACT_RADIUS,
    coarsest: 2.0,
};

/// The pole element sizes a solid (3D) mesh may take (fem-3d, fenicsx-3d): c_max/14, the finest
/// rung of fem-3d's ladder (the element count grows as (c/h)³, a tetrahedral mesh at c/14 is
/// about 2.7 times the default c/10), to c_max/2.
pub const SOLID_POLE: PoleLimits = PoleLimits {
    finest: 14.0,
    coarsest: 2.0,
};

/// The most memory one in-crate solver's model may take [bytes] (3 GiB), estimated before it
/// allocates its factors ([`crate::memory`]): solvers run side by side (`bench`, CI jobs, the
/// external decks, other users of a shared machine), so each keeps to a few GB of an ordinary
/// 16–24 GB machine. A model over it is refused with the estimate, the budget and the
/// resolutions that fit, as that solver's failure (the other solvers of the run go on).
pub const MEMORY_BUDGET: u64 = 3 << 30;

/// The characters of a plain name, as shown in messages.
pub const NAME_CHARACTERS: &str = "A–Z a–z 0–9 . _ -, starting with a letter or digit";

/// True for a plain name: 1 to [`MAX_NAME_CHARS`] ASCII letters, digits, `.`, `_` and `-`,
/// starting with a letter or digit. Such a name is safe as a file or folder name (no separator,
/// no `..`, no leading `-` or `.`) and inside generated decks (no quote, no newline).
pub fn is_plain_name(name: &str) -> bool {
    let allowed = |c: char| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-');
    name.len() <= MAX_NAME_CHARS
        && name.starts_with(|c: char| c.is_ascii_alphanumeric())
        && name.chars().all(allowed)
}

/// The most MPI ranks a case or the command line may ask of a deck that runs under MPI
/// (`fenicsx-3d`): a cluster node's worth; beyond, run the deck by hand as
/// docs/external-decks.md shows.
pub const MAX_RANKS: u32 = 1024;

/// The largest log of one output stream (stdout or stderr) of a program the harness runs
/// [bytes] (16 MiB): the decks and DEM codes print a line or two per increment (about 100 bytes),
/// so a run of 10⁵ increments fits whole; beyond, the head (start-up, version, configuration) and
/// the tail (where a failure shows) are what a reader needs. The rest is counted and dropped
/// (the log says how much), so a program that prints gigabytes fills neither the disk nor the
/// harness's memory (`external::bounded_log`).
pub const MAX_PROGRAM_LOG_BYTES: u64 = 16 << 20;

/// The end of a stream a program log keeps after its head [bytes] (64 KiB, some 800 lines): the
/// only part of the stream the harness holds in memory while the program runs.
pub const PROGRAM_LOG_TAIL_BYTES: usize = 64 << 10;

/// The most characters of one line of a program's output that a message or a report shows
/// (300): compiler diagnostics, Python tracebacks and MPI errors run under 200 characters a
/// line; a longer line is data (a flood, an array, a binary dump) that no one reads in a table
/// cell, a JUnit message or a CI log. A longer line is cut, and says how much was cut
/// (`external::excerpt`); the whole line stays in the program's log.
pub const MAX_SHOWN_LINE_CHARS: usize = 300;

/// The most bytes of a program's output that one message shows (4 KiB): the 12 lines a failure
/// shows at most ([`MAX_SHOWN_LINES`]) of [`MAX_SHOWN_LINE_CHARS`] ASCII characters fit (3.6 KB); a
/// failure's message is repeated in each of its checks' rows, in JUnit, `summary.txt`,
/// `run.json` and both reports, so this bounds what a failing program adds to each of them: 4 KiB
/// a row, where 128 KiB of its output went before. Lines are dropped from the first on until the
/// rest fits.
pub const MAX_SHOWN_OUTPUT_BYTES: usize = 4 << 10;

/// The most lines of a program's output that one message shows (12): the end of its output in a
/// failure's message, a Python traceback's last frames and its error, a compiler's or an MPI
/// launcher's last error with its context.
pub const MAX_SHOWN_LINES: usize = 12;

/// The largest History CSV a command solver may write [bytes] (256 MiB): one row per step, at
/// most [`MAX_INCREMENTS`] + 1 rows of nine cells written with round-trip precision (at most
/// 24 characters each, with separators under 256 bytes a row). Read as a stream, never whole.
pub const MAX_HISTORY_BYTES: u64 = 256 << 20;

/// The largest impact sweep table read back (a case's own impact solver's, stored or written by
/// its program) [bytes]: a sweep has at most 200 points of nine cells, about 40 kB written in
/// full; 1 MiB leaves room for padding, never for a flood.
pub const MAX_SWEEP_TABLE_BYTES: u64 = 1 << 20;

/// The largest `metadata.json` a command solver may write [bytes] (1 MiB): a version, a model,
/// a resolution and warnings in a few lines; read whole.
pub const MAX_METADATA_BYTES: u64 = 1 << 20;

/// The largest per-step CSV of a deck (`steps.csv`, `surface.csv`, the 3D deck's
/// `triangles.csv`) read back [bytes] (256 MiB). Each is read whole and parsed: reading back
/// fenicsx-axisym's run of `cases/paper-fig7.toml` at c_max/40 (1101 steps, 101 candidate nodes:
/// surface.csv 13 MB, 117 bytes a node and step; steps.csv 82 kB) peaked at 134 MB, about ten
/// times the file, so this keeps a read-back within [`MEMORY_BUDGET`]. That path at the finest
/// pole size (c_max/320, eight times the candidates) writes about 105 MB; a steps.csv of
/// [`MAX_INCREMENTS`] steps about 75 MB.
pub const MAX_DECK_TABLE_BYTES: u64 = 256 << 20;

/// The largest `timing.csv` of a deck [bytes] (64 KiB): its own clock, a few `phase,seconds`
/// lines (45 to 164 bytes measured: FreeFEM, dolfinx, the 3D deck).
pub const MAX_DECK_CLOCK_BYTES: u64 = 64 << 10;

/// The largest `deck.stdout` of a CalculiX deck read back [bytes] (64 MiB), searched whole for
/// ccx's `*ERROR` lines (ccx exits with code 0 after some errors): ccx prints about 10 kB a step
/// (measured: 39 kB for the four steps of `cases/ccx-axisym.toml`, 25 kB for the three of
/// `cases/ccx-3d.toml`), so this holds some 6000 steps; a run of the harness's own logs at most
/// [`MAX_PROGRAM_LOG_BYTES`].
pub const MAX_DECK_LOG_BYTES: u64 = 64 << 20;

/// The largest CalculiX result file (`job.dat`, `job.frd`) read back [bytes] (1 GiB). Read whole:
/// the `.frd` holds a line of about 90 bytes per node in every output block (DISP, CONTACT):
/// 9.4 MB for `cases/ccx-axisym.toml` (21 526 nodes at c_max/20, four blocks of each; the read
/// peaked at 30 MB, 2.6 times the file above the process's own 5 MB), 5.4 MB for
/// `cases/ccx-3d.toml`. The nodes grow as (c_max/h)² on the meridian: that case at c_max/160
/// writes about 600 MB; 1 GiB keeps a read-back within [`MEMORY_BUDGET`].
pub const MAX_CCX_RESULTS_BYTES: u64 = 1 << 30;

/// The largest field file a deck leaves at a path position (`field_*.vtu`, `field_*.xdmf` and the
/// `.h5` an XDMF names) [bytes] (1 GiB): meshio reads them in its own process under its time
/// limit (`scripts/read_fields.py`), the harness only checks them. FreeFEM's VTU is 1.0 MB and
/// dolfinx's HDF5 2.7 MB on `cases/paper-fig7.toml` at c_max/40; both grow as (c_max/h)²: about
/// 170 MB at the finest pole size, c_max/320.
pub const MAX_FIELD_FILE_BYTES: u64 = 1 << 30;

/// The largest XDMF file [bytes] (1 MiB), read whole for the HDF5 files it names before meshio
/// opens it: dolfinx's is an index of the `.h5` file's data sets, 3.4 kB whatever the mesh
/// (`cases/paper-fig7.toml`, 1.6 kB for the 3D deck).
pub const MAX_XDMF_BYTES: u64 = 1 << 20;

/// The largest gmsh mesh read from a deck's or a run's folder (`mesh.msh`, `mesh_p1_mm.msh`,
/// `body.msh`) [bytes] (256 MiB), read whole and parsed: the quadratic meridian mesh of
/// `cases/paper-fig7.toml` at c_max/40 is 1.5 MB (11 000 triangles), and its triangles grow as
/// (c_max/h)²: about 100 MB at c_max/320, the finest allowed. The solid meshes are graded:
/// `body.msh` 1.2 MB at c_max/5, 4.3 MB at c_max/14, the finest.
pub const MAX_MESH_BYTES: u64 = 256 << 20;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_names() {
        for name in ["paper-fig7", "hard-grazing", "a", "v1.2_b"] {
            assert!(is_plain_name(name), "{name}");
        }
        let long = "x".repeat(MAX_NAME_CHARS + 1);
        for name in [
            "",
            "..",
            ".hidden",
            "-rf",
            "a/b",
            "x/../../e",
            "a b",
            "é",
            "a\nb",
            &long,
        ] {
            assert!(!is_plain_name(name), "{name:?}");
        }
    }
}
