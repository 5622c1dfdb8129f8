//! ISPH's step shortened where the flow outruns the case's Δt.
//!
//! The case check accepts a Δt with `u Δt/Δs ≤ 0.4` for the case's velocity scale u (the
//! dam-break front's 2√(gH), [`schemas::case::fluid::FluidConfig::advective_velocity`]). Where
//! water strikes a wall it runs up faster than that: at the largest Δt the check accepts, the
//! L/20 Koshizuka & Oka dam break's run-up at the far wall reached 4.24 m/s, 1.25 × 2√(gH), and
//! moved a particle 0.501 spacings in one step (the instability detector's limit is 0.5). So each
//! step is at most `0.4 Δs / u_max` long, u_max the fastest fluid particle's speed at the step's
//! start, and never shorter than Δt / [`MAX_SHORTENING`]: a flow that needs more than that is
//! left to the detector, which names the particle and the Δt that would hold. A step cut short
//! this way is one of the method's short steps (its pressure is a whole step's, its share of the
//! velocity change is Δt_cut/Δt: [`pressure_step`]).

use crate::particles::kind::FLUID;
use crate::particles::Particles;
use rayon::prelude::*;
use schemas::case::fluid::MAX_ADVECTIVE_COURANT;

/// The most a step is divided by to keep the advective Courant number at or below 0.4.
pub const MAX_SHORTENING: f64 = 8.0;

/// ISPH's advective limit on each step's length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdvectiveLimit {
    /// The case's Δt: the longest step.
    pub time_step: f64,
    /// `0.4 Δs`: the farthest a particle may move in one step.
    pub reach: f64,
}

impl AdvectiveLimit {
    /// The limit for particles of spacing `spacing` stepped at most by `time_step`.
    pub fn new(spacing: f64, time_step: f64) -> AdvectiveLimit {
        AdvectiveLimit {
            time_step,
            reach: MAX_ADVECTIVE_COURANT * spacing,
        }
    }

    /// The longest step from the present velocities: `min(Δt, max(0.4 Δs / u_max, Δt / 8))`, and
    /// u_max when that is shorter than Δt.
    pub fn longest_step(&self, p: &Particles) -> (f64, Option<f64>) {
        self.longest_step_at(fastest_fluid(p))
    }

    /// [`Self::longest_step`] with the fastest fluid particle's speed `fastest` [m/s] given (the
    /// GPU path reduces it on the device).
    pub fn longest_step_at(&self, fastest: f64) -> (f64, Option<f64>) {
        if fastest * self.time_step <= self.reach {
            return (self.time_step, None);
        }
        let step = (self.reach / fastest).max(self.time_step / MAX_SHORTENING);
        (step, Some(fastest))
    }
}

/// Relative difference below which two step lengths count as the same (rounding of the landing
/// times).
const SAME_LENGTH: f64 = 1e-9;

/// The length of the step whose pressure a step of `dt` takes (`IsphStep::short_step`), for a
/// case's `time_step`: Δt for a step the advective limit cut (`cut`); else `dt` itself (a whole
/// step) when it is the case's Δt, at the run's start (`last` none), or when it is no shorter than
/// the step whose pressure the step before took (`last`); else that step, at most Δt.
///
/// A whole step's projection removes the divergence the particles carry into it, which the steps
/// before made (a short step removes only its share of it) and which does not shrink with this
/// step, so a step much shorter than that would draw a pressure ∝ 1/Δt (a landing step of
/// 1e-4 Δt wrote 5.6 MPa where the flow's was 1.1 kPa): such a step takes the pressure of a step as
/// long as that one and its share of the velocity change. Steps between landing times closer than
/// Δt (outputs, probes or coupling windows) are then whole steps of their own length; before, each
/// took a share of a whole step and left the rest of the divergence (the MARIN CI twin at
/// Δt = 3.4e-3 s with probes every 1.2e-3 s read P1 +71 % of the experiment, +8 % at Δt =
/// 1.2e-3 s). Cut steps stay shares of Δt: as whole steps, the thrown block of
/// `tests/isph_step_length.rs` sent a run-up jet at 5.43 m/s (thrown at 2.97) 0.500 Δs in one
/// step at its impact, and the detector stopped it.
pub fn pressure_step(dt: f64, time_step: f64, cut: bool, last: Option<f64>) -> f64 {
    if cut {
        return time_step;
    }
    let Some(last) = last else {
        return dt;
    };
    let before = last.min(time_step);
    if dt >= time_step * (1.0 - SAME_LENGTH) || before <= dt * (1.0 + SAME_LENGTH) {
        dt
    } else {
        before
    }
}

/// The largest speed |u| among the fluid particles (0 without fluid).
pub fn fastest_fluid(p: &Particles) -> f64 {
    (&p.vx, &p.vy, &p.vz, &p.kind)
        .into_par_iter()
        .with_min_len(4096)
        .filter(|t| *t.3 == FLUID)
        .map(|(u, v, w, _)| u * u + v * v + w * w)
        .reduce(|| 0.0, f64::max)
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::kind::Kind;

    fn one_fluid_particle(speed: f64) -> Particles {
        let mut p = Particles::default();
        p.push_moving([0.0; 3], [speed, 0.0, 0.0], Kind::Fluid, 0);
        p.push_moving([1.0; 3], [100.0, 0.0, 0.0], Kind::Wall, 1);
        p
    }

    #[test]
    fn a_step_is_cut_only_where_the_fluid_outruns_it() {
        let limit = AdvectiveLimit::new(0.01, 1e-3);
        // 0.4 Δs / Δt = 4 m/s; the wall's speed does not count
        assert_eq!(limit.longest_step(&one_fluid_particle(4.0)), (1e-3, None));
        let (step, fastest) = limit.longest_step(&one_fluid_particle(5.0));
        assert!((step - 0.8e-3).abs() < 1e-15 && fastest == Some(5.0));
        let (step, _) = limit.longest_step(&one_fluid_particle(1e3));
        assert_eq!(step, 1e-3 / MAX_SHORTENING);
    }
}
