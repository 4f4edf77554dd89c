//! Wall times, kept apart from the data that reproduce to the byte: the
//! file-name conventions are `paper::catalogue`'s (only `cargo xtask figures
//! --timings` measures and rewrites the files ending in [`SUFFIX`]), the
//! machine's row `fc_paper_figures::machine`'s.

pub use fc_paper_figures::machine::{cpu_seconds, csv as machine_csv};
/// The median of a non-empty sample (the library's; kept here for the
/// figure files that time their runs).
#[allow(unused_imports, reason = "for the figure files that time their runs")]
pub use fc_study::median;
pub use paper::catalogue::{MACHINE, RUN, SUFFIX};
