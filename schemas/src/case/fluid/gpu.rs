//! `backend = "gpu"`: what the GPU path of a fluid section refuses.

use super::{FluidConfig, FluidMethodName};
use crate::case::FieldError;

/// The largest f32 rounding of a position the GPU path accepts, in spacings: 1e-3 Δs is 5 % of
/// a step's largest move at c Δt/Δs ≈ 0.5 and u ≤ c/10 (S1-16), and allows tanks up to
/// 16 777 spacings long anywhere (positions are kept from the tank's lower corner: 16.7 km at
/// Δs = 1 m).
pub const GPU_MAX_ROUNDING: f64 = 1e-3;

impl FluidConfig {
    /// Refuses what the GPU path (`backend = "gpu"`) does not run yet, naming the feature: a run
    /// never goes on with a mix that silently differs from the CPU's. `key` is the section's
    /// dotted path; the error is at its `backend` key.
    pub fn gpu_support(&self, key: &str) -> Result<(), FieldError> {
        let refuse = |feature: &str| {
            Err(FieldError::new(
                format!("{key}.backend"),
                format!("the GPU path does not run {feature} yet; use backend = \"cpu\" (the default) for this case"),
            ))
        };
        if self.method != FluidMethodName::Emps {
            return refuse("method = \"isph\" (only E-MPS is on the GPU)");
        }
        // inflow and outflow boundaries run on the device, the strip's rule on the host's copy
        // of it (fluid-solver's gpu/open_boundary.rs)
        // a wave maker's paddle (piston or flap) is placed on the device by the motion the host
        // evaluates each step (fluid-solver's gpu/paddle.rs)
        // filtered wall-pressure sensors read, after every step in their window, the device's
        // particles around their disc, gathered without the rest (fluid-solver's gpu/gather.rs)
        self.gpu_position_rounding(key)
    }

    /// The point the GPU path measures positions from: the tank's lower corner. The device keeps
    /// `x − origin` in f32, so a tank anywhere (georeferenced coordinates included) rounds as one
    /// at the origin.
    pub fn gpu_frame_origin(&self) -> [f64; 3] {
        self.gpu_extent().0
    }

    /// The box the GPU path's positions stay in: the tank, and one tank height above an open
    /// top.
    fn gpu_extent(&self) -> ([f64; 3], [f64; 3]) {
        let t = &self.tank;
        let headroom = if t.lid { 0.0 } else { t.max[2] - t.min[2] };
        let mut hi = t.max;
        hi[2] += headroom;
        (t.min, hi)
    }

    /// The GPU path keeps positions relative to [`FluidConfig::gpu_frame_origin`] in f32
    /// (24-bit significand): a coordinate d from it rounds by up to |d|·2⁻²⁴. Refused when that
    /// exceeds [`GPU_MAX_ROUNDING`] Δs anywhere in the tank or its headroom, i.e. for a tank
    /// longer than 16 777 spacings along an axis: a slow particle at its far end would then move
    /// by steps of the rounding instead of its velocity (cell index + f32 offset positions, which
    /// would lift this, are not on the GPU yet).
    fn gpu_position_rounding(&self, key: &str) -> Result<(), FieldError> {
        let (lo, hi) = self.gpu_extent();
        let far = crate::validation::largest((0..3).map(|a| hi[a] - lo[a]), 0.0);
        let rounding = far * f64::from(f32::EPSILON) / 2.0;
        if rounding > GPU_MAX_ROUNDING * self.spacing {
            return Err(FieldError::new(
                format!("{key}.backend"),
                format!(
                    "the GPU path keeps positions in f32 from the tank's lower corner: {far} m from it (the tank's largest extent, with one tank height above an open top) they round by {rounding:.2e} m = {:.1e} Δs, more than the {GPU_MAX_ROUNDING:e} Δs it allows; use a coarser spacing, a smaller tank (at most {:.0} spacings along an axis), or backend = \"cpu\"",
                    rounding / self.spacing,
                    GPU_MAX_ROUNDING / (f64::from(f32::EPSILON) / 2.0)
                ),
            ));
        }
        Ok(())
    }
}
