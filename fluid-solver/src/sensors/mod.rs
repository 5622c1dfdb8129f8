//! What a case measures: its probes, sampled into one CSV, and the roughness of a probe's signal.
//!
//! - [`probes`]: water-height gauges, point pressures, surge fronts and wall sensors;
//! - [`wall_sensor`]: a wall-pressure disc as an experiment mounts one;
//! - [`view`]: the particles the sensors read, the device's without a whole copy on the GPU path;
//! - [`probe_signal`]: roughness measures of a probe's time series across methods.

pub mod probe_signal;
pub mod probes;
pub mod view;
pub mod wall_sensor;
