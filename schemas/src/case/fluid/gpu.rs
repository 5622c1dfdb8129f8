//! `backend = "gpu"`: what the GPU path of a fluid section refuses.

use super::{FluidConfig, FluidMethodName};
use crate::case::FieldError;

/// The largest f32 rounding of a position the GPU path accepts, in spacings: 1e-3 Δs is 5 % of
/// a step's largest move at c Δt/Δs ≈ 0.5 and u ≤ c/10 (S1-16), and allows tanks up to
/// 16 777 spacings from the origin (16.7 km at Δs = 1 m).
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

    /// The GPU path keeps absolute positions in f32 (24-bit significand): a coordinate x rounds
    /// by up to |x|·2⁻²⁴. Refused when that exceeds [`GPU_MAX_ROUNDING`] Δs anywhere in the
    /// tank or its headroom above an open top (one tank height): a slow particle far from the
    /// origin would then move by steps of the rounding instead of its velocity (cell index +
    /// f32 offset positions are not on the GPU yet).
    fn gpu_position_rounding(&self, key: &str) -> Result<(), FieldError> {
        let t = &self.tank;
        let headroom = if t.lid { 0.0 } else { t.max[2] - t.min[2] };
        let far = (0..3)
            .map(|a| {
                t.min[a]
                    .abs()
                    .max(t.max[a].abs() + if a == 2 { headroom } else { 0.0 })
            })
            .fold(0.0, f64::max);
        let rounding = far * f64::from(f32::EPSILON) / 2.0;
        if rounding > GPU_MAX_ROUNDING * self.spacing {
            return Err(FieldError::new(
                format!("{key}.backend"),
                format!(
                    "the GPU path keeps positions in f32: {far} m from the origin they round by {rounding:.2e} m = {:.1e} Δs, more than the {GPU_MAX_ROUNDING:e} Δs it allows; move the tank next to the origin (coordinates are free: shift every position of the case) or use backend = \"cpu\"",
                    rounding / self.spacing
                ),
            ));
        }
        Ok(())
    }
}
