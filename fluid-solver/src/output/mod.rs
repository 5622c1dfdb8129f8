//! What a run writes for its user: ParaView frames of the particles and of the free surface,
//! and the progress lines and summary of the log.
//!
//! - [`vtu`]: particle frames (VTU) and their PVD series;
//! - [`surface_mesh`]: the free-surface mesh, and [`vtp`]: its frames (VTP);
//! - [`vtk_appended`]: the VTK XML layout with raw appended data both writers share;
//! - [`progress`]: progress lines and the run's summary;
//! - [`frame_files`]: a frame's files and series, and [`background`]: frames written on a
//!   thread of their own while the solver steps on.

pub mod background;
pub mod frame_files;
pub mod progress;
pub mod surface_mesh;
pub mod vtk_appended;
pub mod vtp;
pub mod vtu;
