//! Every integration test of this package, one module per file, built as one test binary so
//! that CI compiles and links the package's tests once (`cargo test -p schemas --test all` runs
//! them; `-- NAME::` picks one file's tests).

mod case_reference;
mod case_warnings;
mod every_fluid_case_takes_isph;
mod link;
mod recording_fuzz;
mod scene_files;
