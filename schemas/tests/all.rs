//! Every integration test of this package, one module per file, built as one test binary so
//! that CI compiles and links the package's tests once (`cargo test -p schemas --test all` runs
//! them; `-- NAME::` picks one file's tests).

mod atomic_file;
mod case_coupling;
mod case_fluid_inflow_law;
mod case_fluid_inflow_series;
mod case_inputs;
mod case_key_reference;
mod case_load_table;
mod case_reference;
mod case_report;
mod case_warnings;
mod checkpoint;
mod every_fluid_case_takes_isph;
mod geometry_ascii_grid;
mod geometry_geotiff;
mod geometry_height_grid;
mod geometry_lattice;
mod geometry_lattice_fill;
mod geometry_mass_properties;
mod geometry_mesh_checks;
mod geometry_mesh_file;
mod geometry_site_set;
mod geometry_triangle_mesh;
mod link;
mod link_codec;
mod link_handshake;
mod link_liveness;
mod link_names;
mod markdown;
mod recording;
mod recording_fuzz;
mod scene_files;
mod validation;
mod wave_motion;
mod wave_motion_flap;
mod wave_motion_goring;
mod wave_motion_ramp;
mod wave_motion_regular;
mod wave_motion_solitary_wave;
mod wave_motion_stroke_table;
mod waveform;
