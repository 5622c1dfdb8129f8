//! The GPU path of the E-MPS step: wgpu compute shaders (WGSL) on a Vulkan device, chosen per run
//! by `backend = "gpu"` in the case or `fluid-solver run --backend gpu` (the CPU stays the
//! default). The particles live on the device; they cross to the host only when an output,
//! a probe row or a diagnostic is due.
//!
//! - [`device`]: adapter selection (Vulkan only) and the error when there is none;
//! - [`params`]: the constants every kernel reads (one uniform block);
//! - [`frame`]: positions on the device are kept from the tank's lower corner;
//! - [`buffers`]: the device arrays, their precision, upload and download;
//! - [`kernels`]: the WGSL modules (`shaders/`) as compute pipelines on one bind group;
//! - [`cell_sort`]: counting sort and prefix sum by cell;
//! - [`counter_pass`]: a pass that counts or reduces into a few words, read back;
//! - [`step`]: the E-MPS stages of [`crate::emps::step`] in the same order;
//! - [`bodies`]: resolved rigid bodies: placed from the host's pose, loads reduced on the device;
//! - [`solids`]: mesh solids and terrains: their sites for the detector;
//! - [`body_inside`]: the detector's "inside a body" check, box and mesh bodies;
//! - [`damping`]: damping zones, relaxed after each step;
//! - [`paddle`]: the wave maker's paddle, placed before each step by the prescribed motion;
//! - [`open_boundary`]: inflow and outflow: the strip's new rows appended, particles removed and
//!   the arrays compacted on the device;
//! - [`escape`]: fluid that left through an open top, removed on the device;
//! - [`isph`]: the ISPH step (`method = "isph"`) in place of E-MPS's stages, sharing the cell
//!   sort, the collision stage and the reduction;
//! - [`drag`]: the unresolved drag coupling: the flow sampled at the coupler's points and the
//!   point reactions spread over the fluid;
//! - [`gather`]: the particles around a filtered wall-pressure sensor or a local probe, copied
//!   back without the rest, and the light copy of all that a global probe reads;
//! - [`probe_reductions`]: what the surge fronts and the run-up gauge read, reduced on the device;
//! - [`reduce`]: the instability detector's scan and the step's totals, reduced on the device;
//! - [`driver`]: the solver's step on the device (detector, host copies).

pub mod bodies;
pub mod body_inside;
pub mod buffers;
pub mod cell_sort;
pub mod counter_pass;
pub mod damping;
pub mod device;
pub mod drag;
pub mod driver;
pub mod escape;
pub mod frame;
pub mod gather;
pub mod isph;
pub mod kernels;
pub mod open_boundary;
pub mod paddle;
pub mod params;
pub mod probe_reductions;
pub mod reduce;
pub mod solids;
pub mod step;

pub use device::{GpuDevice, NoAdapter};
pub use driver::DeviceSeconds;
pub use step::GpuEmps;
