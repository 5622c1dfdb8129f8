//! The time step of a fluid section against its method's stability limits, and the velocity
//! and sound-speed scales (S1-16) those limits use.

use super::FluidConfig;
use crate::case::FieldError;

/// Mach number used for the default sound speed (S1-16: `c = u_max / 0.2`).
pub const MACH: f64 = 0.2;

/// Largest acoustic Courant number `c Δt / Δs`. The E-MPS update is symplectic Euler on a
/// lattice whose equation of state makes it a spring chain with wave speed c; its highest
/// mode has ω = 2c/Δs and symplectic Euler is stable only for ωΔt < 2, i.e. cΔt/Δs < 1.
pub const MAX_ACOUSTIC_COURANT: f64 = 1.0;

/// Largest viscous number `ν Δt / Δs²`: explicit diffusion in d = 3 is stable for
/// `ν Δt / Δs² ≤ 1/(2d)`.
pub const MAX_VISCOUS_NUMBER: f64 = 1.0 / 6.0;

/// Largest advective Courant number `u_max Δt / Δs` of ISPH: a particle at u_max moves at most
/// 0.4 Δs per step, so a step's neighbour lists stay valid for its whole length and the
/// instability detector's 0.5 Δs per step is not reached by the predicted flow itself. The
/// check holds it for the case's velocity scale; the solver cuts a step where the fluid at its
/// start is faster than that (`fluid_solver::isph::step_length`).
pub const MAX_ADVECTIVE_COURANT: f64 = 0.4;

impl FluidConfig {
    /// The largest Δt ISPH accepts for this section: the advective limit `0.4 Δs / u` (u of
    /// [`FluidConfig::advective_velocity`]) and, with the viscous term on, the viscous limit
    /// `Δs² / (6ν)`, whichever is shorter.
    pub fn isph_time_step_limit(&self) -> f64 {
        let advective = self.advective_time_step_limit();
        if self.viscosity_term {
            advective.min(self.viscous_time_step_limit())
        } else {
            advective
        }
    }

    /// ISPH's advective limit on Δt: `0.4 Δs / u`, u of [`FluidConfig::advective_velocity`].
    fn advective_time_step_limit(&self) -> f64 {
        MAX_ADVECTIVE_COURANT * self.spacing / self.advective_velocity()
    }

    /// The viscous limit on Δt: `Δs² / (6ν)` (viscous number ν Δt/Δs² ≤ 1/6).
    fn viscous_time_step_limit(&self) -> f64 {
        MAX_VISCOUS_NUMBER * self.spacing * self.spacing / self.viscosity
    }

    /// ISPH: refuses a Δt above the advective (u Δt/Δs ≤ 0.4, u of
    /// [`FluidConfig::advective_velocity`]) or viscous (ν Δt/Δs² ≤ 1/6)
    /// limit; there is no acoustic limit.
    pub(super) fn validate_isph_time_step(&self, key: &str) -> Result<(), FieldError> {
        let u = self.advective_velocity();
        let courant = u * self.time_step / self.spacing;
        if courant > MAX_ADVECTIVE_COURANT || courant.is_nan() {
            return Err(FieldError::new(
                format!("{key}.time_step"),
                format!(
                    "Δt = {} s is too long for ISPH: the advective Courant number u·Δt/Δs = {courant:.3} (u = {u:.3} m/s, the case's max_velocity or u_in + 2√(gH)) must be ≤ {MAX_ADVECTIVE_COURANT}; use time_step ≤ {:.3e} s",
                    self.time_step,
                    self.advective_time_step_limit()
                ),
            ));
        }
        self.validate_viscous_number(key)
    }

    /// Refuses a Δt above the acoustic (c Δt/Δs ≤ 1) or viscous (ν Δt/Δs² ≤ 1/6) limit.
    pub(super) fn validate_time_step(&self, key: &str) -> Result<(), FieldError> {
        let c = self.sound_speed();
        if !(c.is_finite() && c > 0.0) {
            return Err(FieldError::new(
                format!("{key}.sound_speed"),
                format!(
                    "the default c = u_max/0.2 is {c} (no gravity or no water height): set sound_speed > 0"
                ),
            ));
        }
        let courant = c * self.time_step / self.spacing;
        if courant > MAX_ACOUSTIC_COURANT {
            return Err(FieldError::new(
                format!("{key}.time_step"),
                format!(
                    "Δt = {} s is unstable: the acoustic Courant number c·Δt/Δs = {courant:.3} (c = {c:.3} m/s) must be ≤ {MAX_ACOUSTIC_COURANT}; use time_step ≤ {:.3e} s",
                    self.time_step,
                    MAX_ACOUSTIC_COURANT * self.spacing / c
                ),
            ));
        }
        self.validate_viscous_number(key)
    }

    /// Refuses a Δt above the viscous limit ν Δt/Δs² ≤ 1/6 (when the viscous term is on).
    fn validate_viscous_number(&self, key: &str) -> Result<(), FieldError> {
        if self.viscosity_term {
            let vn = self.viscosity * self.time_step / (self.spacing * self.spacing);
            if vn > MAX_VISCOUS_NUMBER {
                return Err(FieldError::new(
                    format!("{key}.time_step"),
                    format!(
                        "Δt = {} s is unstable: the viscous number ν·Δt/Δs² = {vn:.3} must be ≤ 1/6; use time_step ≤ {:.3e} s",
                        self.time_step,
                        self.viscous_time_step_limit()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// u_max of S1-16: the case's `max_velocity`, else √(u_in² + 2gH) with H the highest block
    /// top or inflow level above the floor (u_in = 0 without an inflow; a series' largest u and h).
    pub fn max_velocity(&self) -> f64 {
        self.max_velocity.unwrap_or_else(|| {
            let (u_in, inflow_top) = self.inflow_extremes();
            let top = self.block.iter().map(|b| b.max[2]).fold(inflow_top, f64::max);
            (u_in * u_in + 2.0 * self.gravity_magnitude() * (top - self.tank.min[2])).sqrt()
        })
    }

    /// The velocity scale of ISPH's advective Courant check: the case's `max_velocity`, else
    /// `u_in + 2√(gH)` with H as in [`FluidConfig::max_velocity`]: the front of a dam break on a
    /// dry bed runs at 2√(gH) (Ritter 1892), √2 times the free-fall speed √(2gH) of S1-16 (an
    /// ISPH dam break checked against √(2gH) at Courant 0.4 moved its front 0.57 Δs a step and
    /// tripped the instability detector's 0.5 Δs).
    pub fn advective_velocity(&self) -> f64 {
        self.max_velocity.unwrap_or_else(|| {
            let (u_in, inflow_top) = self.inflow_extremes();
            let top = self.block.iter().map(|b| b.max[2]).fold(inflow_top, f64::max);
            u_in + 2.0 * (self.gravity_magnitude() * (top - self.tank.min[2])).sqrt()
        })
    }

    /// (u_in, the inflow's top z) for the velocity scales: the largest velocity and level of
    /// the inflow's law, (0, the tank floor) without an inflow.
    fn inflow_extremes(&self) -> (f64, f64) {
        let floor = self.tank.min[2];
        self.inflow
            .as_ref()
            .and_then(|i| i.law())
            .map_or((0.0, floor), |law| (law.max_velocity(), floor + law.max_level()))
    }

    /// c of S1-16: the case's `sound_speed`, else `u_max / 0.2`.
    pub fn sound_speed(&self) -> f64 {
        self.sound_speed.unwrap_or_else(|| self.max_velocity() / MACH)
    }
}
