//! Every integration test of this package, one module per file, built as one test binary so
//! that CI compiles and links the package's tests once (`cargo test -p fluid-solver --test all` runs
//! them; `-- NAME::` picks one file's tests).

mod bodies_common;
mod closed_box;
mod common;
mod front_common;
mod front_record;
mod gpu_common;
mod hydrostatic_common;
mod isph_slab;
mod standing_wave;

mod artificial_viscosity;
mod bad_input;
mod bodies_fixed_hydrostatic;
mod bodies_inside_check;
mod bodies_momentum;
mod conservation;
mod dam_break;
mod dam_break_obstacle;
mod gpu_bodies;
mod gpu_dam_break;
mod gpu_detector;
mod gpu_front;
mod gpu_hydrostatic;
mod gpu_large;
mod gpu_pressure_stages;
mod gpu_refusals;
mod gpu_run;
mod gpu_skips;
mod hydrostatic;
mod inflow_outflow;
mod isph;
mod isph_bodies;
mod isph_dam_break;
mod isph_divergence;
mod isph_lattice_modes;
mod isph_momentum;
mod isph_two_level;
mod isph_wall_geometry;
mod isph_wall_signal;
mod lattice;
mod mesh_bodies;
mod open_top;
mod operators;
mod output;
mod participant;
mod probes;
mod scene_walls;
mod surface_mesh;
mod unresolved_fluid_side;
mod unresolved_momentum;
mod unresolved_shares_reuse;
mod wall_top;
mod walls;
mod wave_maker;
