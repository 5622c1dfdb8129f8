//! `backend = "gpu"`: what the GPU path of a fluid section refuses.

use super::{FluidConfig, FluidMethodName, PressureGradient, ProbeKind, Shifting};
use crate::case::FieldError;

/// The largest f32 rounding of a position the GPU path accepts, in spacings: 1e-3 Δs is 5 % of
/// a step's largest move at c Δt/Δs ≈ 0.5 and u ≤ c/10 (S1-16), and allows tanks up to
/// 16 777 spacings long anywhere (positions are kept from the tank's lower corner: 16.7 km at
/// Δs = 1 m) in plain f32; longer tanks keep wide positions ([`FluidConfig::gpu_quantum`]).
pub const GPU_MAX_ROUNDING: f64 = 1e-3;

/// The largest rounding of a wide position's high part the GPU path accepts, in spacings: what
/// it moves is only where a particle is tested against planes, boxes, damping zones and solid
/// sites (pair distances keep f32's relative precision), and 0.02 Δs is 1/25 of the half spacing
/// those tests leave between a plane and the nearest lattice site.
pub const GPU_MAX_WIDE_ROUNDING: f64 = 0.02;

/// The quantum of wide positions for points up to `far` m from the device frame's origin at
/// `spacing` ([`FluidConfig::gpu_quantum`]); `None` where plain f32 keeps [`GPU_MAX_ROUNDING`].
pub fn gpu_wide_quantum(far: f64, spacing: f64) -> Option<f64> {
    if far * f64::from(f32::EPSILON) / 2.0 <= GPU_MAX_ROUNDING * spacing {
        return None;
    }
    Some(2f64.powi((2.0 * far / 2f64.powi(24)).log2().ceil() as i32))
}

impl FluidConfig {
    /// Refuses what the GPU path (`backend = "gpu"`) does not run yet, naming the feature: a run
    /// never goes on with a mix that silently differs from the CPU's. `key` is the section's
    /// dotted path; the error is at its `backend` key.
    pub fn gpu_support(&self, key: &str) -> Result<(), FieldError> {
        if self.method == FluidMethodName::Isph {
            self.gpu_isph_support(key)?;
        }
        // inflow and outflow boundaries run on the device, the strip's rule on the host's copy
        // of it (fluid-solver's gpu/open_boundary.rs)
        // a wave maker's paddle (piston or flap) is placed on the device by the motion the host
        // evaluates each step (fluid-solver's gpu/paddle.rs)
        // filtered wall-pressure sensors read, after every step in their window, the device's
        // particles around their disc, gathered without the rest (fluid-solver's gpu/gather.rs)
        self.gpu_position_rounding(key)
    }

    /// Refuses what ISPH on the GPU does not run yet: it runs the default discretisation
    /// (`pressure_gradient = "conservative"`, with or without the kernel correction) in tanks whose
    /// solids are fixed (fluid-solver's `gpu/isph.rs`).
    fn gpu_isph_support(&self, key: &str) -> Result<(), FieldError> {
        let refuse = |feature: &str| {
            Err(FieldError::new(
                format!("{key}.backend"),
                format!("the GPU path does not run {feature} with method = \"isph\" yet; use backend = \"cpu\" (the default) or method = \"emps\" for this case"),
            ))
        };
        let s = self.isph_settings();
        if s.pressure_gradient != PressureGradient::Conservative {
            return refuse("isph.pressure_gradient other than \"conservative\" (the default)");
        }
        if s.shifting != Shifting::Off {
            return refuse("isph.shifting = \"lind\"");
        }
        if !self.body.is_empty() {
            return refuse("resolved bodies (`body` tables)");
        }
        if self.wave_maker.is_some() {
            return refuse("a wave maker");
        }
        if self.inflow.is_some() || self.outflow.is_some() {
            return refuse("inflow and outflow boundaries");
        }
        if self.probe.iter().any(|p| p.kind == ProbeKind::WallPressure) {
            return refuse("wall-pressure sensors (kind = \"wall-pressure\")");
        }
        Ok(())
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

    /// The quantum of the high parts of the GPU path's wide positions, `None` for a tank whose
    /// plain f32 positions keep [`GPU_MAX_ROUNDING`] (at most 16 777 spacings along each axis,
    /// its headroom included). Past that each position is kept as hi + lo (fluid-solver's
    /// `gpu/frame.rs`): hi on a grid of this quantum, the smallest power of two with
    /// 2²⁴ quanta over twice the extent (room for particles that leave it), lo within half a
    /// quantum of 0, so neighbours' differences keep f32's relative precision anywhere.
    pub fn gpu_quantum(&self) -> Option<f64> {
        gpu_wide_quantum(self.gpu_largest_extent(), self.spacing)
    }

    /// The tank's largest extent, with one tank height above an open top [m].
    fn gpu_largest_extent(&self) -> f64 {
        let (lo, hi) = self.gpu_extent();
        crate::validation::largest((0..3).map(|a| hi[a] - lo[a]), 0.0)
    }

    /// Wide positions keep pair distances exact to f32 anywhere; what the high part's rounding
    /// (half a quantum) still moves is where a particle is tested against planes, boxes, zones
    /// and sites, and its cell (whose edge the solver widens by a quantum so no pair is lost).
    /// Refused when that exceeds [`GPU_MAX_WIDE_ROUNDING`] Δs: a tank of about 2–4 × 10⁵
    /// spacings along an axis, depending on where the power of two falls.
    fn gpu_position_rounding(&self, key: &str) -> Result<(), FieldError> {
        let Some(quantum) = self.gpu_quantum() else {
            return Ok(());
        };
        let rounding = 0.5 * quantum;
        if rounding > GPU_MAX_WIDE_ROUNDING * self.spacing {
            let far = self.gpu_largest_extent();
            return Err(FieldError::new(
                format!("{key}.backend"),
                format!(
                    "the GPU path keeps positions as two f32 parts from the tank's lower corner; over {far} m (the tank's largest extent, with one tank height above an open top) the high part rounds by {rounding:.2e} m = {:.1e} Δs, more than the {GPU_MAX_WIDE_ROUNDING:e} Δs it allows for plane and cell tests; use a coarser spacing, a smaller tank (at most {} spacings along an axis here), or backend = \"cpu\"",
                    rounding / self.spacing,
                    self.gpu_wide_spacings()
                ),
            ));
        }
        Ok(())
    }

    /// The most spacings along an axis whose quantum keeps [`GPU_MAX_WIDE_ROUNDING`] at this
    /// spacing.
    fn gpu_wide_spacings(&self) -> u64 {
        let quantum = 2f64.powi((2.0 * GPU_MAX_WIDE_ROUNDING * self.spacing).log2().floor() as i32);
        (quantum * 2f64.powi(23) / self.spacing) as u64
    }
}
