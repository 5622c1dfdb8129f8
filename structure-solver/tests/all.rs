//! Every integration test of this package, one module per file, built as one test binary so
//! that CI compiles and links the package's tests once (`cargo test -p structure-solver --test all` runs
//! them; `-- NAME::` picks one file's tests).

mod bad_input;
mod frame_accuracy_warning;
mod frame_common;
mod frame_condensation;
mod frame_condensed_system;
mod frame_config_errors;
mod frame_contact;
mod frame_damping;
mod frame_energy;
mod frame_energy_check;
mod frame_equilibrium;
mod frame_fracture;
mod frame_geometry;
mod frame_kept_values;
mod frame_kernels;
mod frame_large_rotation;
mod frame_modal;
mod frame_one_solve_step;
mod frame_plastic_collapse;
mod frame_static;
mod frame_step_load;
mod frame_stress_states;
mod frame_yield_functions;
mod load_history;
mod mesh_inertia;
mod participant_adapter;
mod rigid_body;
mod standalone_binary;
mod substep_count;
mod two_mass_oscillator;
mod washout_support;
