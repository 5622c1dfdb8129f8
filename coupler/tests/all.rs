//! Every integration test of this package, one module per file, built as one test binary so
//! that CI compiles and links the package's tests once (`cargo test -p coupler --test all` runs
//! them; `-- NAME::` picks one file's tests).

mod drag_law;
mod validation_page;
