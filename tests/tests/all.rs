//! Every integration test of this package, one module per file, built as one test binary so
//! that CI compiles and links the package's tests once (`cargo test -p stack-tests --test all` runs
//! them; `-- NAME::` picks one file's tests).

mod abnormal_endings;
mod bad_cases;
mod body_on_wall;
mod bridge_deck;
mod bridge_washout;
mod closed_streams;
mod coupling_instability;
mod doc_links;
mod drag_coupling;
mod every_case_checks;
mod faults;
mod floating_at_rest;
mod floating_box;
mod gpu_bridge_washout;
mod gpu_drag_column;
mod gpu_floating;
mod gpu_prism;
mod help;
mod isph_floating;
mod oscillator;
mod output_estimate;
mod prism_cases;
#[cfg(feature = "mpi")]
mod ranked_fluid;
mod recording_cut;
mod replay;
mod report;
mod resume;
mod single_solver;
mod test_helpers_stay_out_of_the_install;
