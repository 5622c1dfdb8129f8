//! [`InflowLaw`]: what drives an inflow strip, its water level h(t) above the tank floor and its
//! velocity u(t) along +x, from the keys of `[fluid.NAME.inflow]` ([`super::InflowConfig::law`]).

use super::inflow_series::InflowSeries;

/// h(t) [m] and u(t) [m/s] of an inflow.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum InflowLaw {
    /// `velocity`, `level`, `initial_level`, `rise_time`: u = u_in constant, and h rising
    /// linearly, h(t) = h_0 + (h_max − h_0) · t / T_rise for 0 ≤ t < T_rise, h_max after (and at
    /// once when T_rise = 0).
    Ramp {
        /// u_in [m/s].
        velocity: f64,
        /// h_max [m].
        level: f64,
        /// h_0 = h(0) [m].
        initial_level: f64,
        /// T_rise [s].
        rise_time: f64,
    },
    /// `series`: both from a CSV file, linear between its rows.
    Series(InflowSeries),
}

impl InflowLaw {
    /// h(t) [m].
    pub fn level_at(&self, t: f64) -> f64 {
        match self {
            Self::Ramp {
                level,
                initial_level,
                rise_time,
                ..
            } => {
                if *rise_time > 0.0 && t < *rise_time {
                    initial_level + (level - initial_level) * (t.max(0.0) / rise_time)
                } else {
                    *level
                }
            }
            Self::Series(s) => s.level_at(t),
        }
    }

    /// u(t) [m/s].
    pub fn velocity_at(&self, t: f64) -> f64 {
        match self {
            Self::Ramp { velocity, .. } => *velocity,
            Self::Series(s) => s.velocity_at(t),
        }
    }

    /// The largest h(t) [m].
    pub fn max_level(&self) -> f64 {
        match self {
            Self::Ramp { level, .. } => *level,
            Self::Series(s) => s.max_level(),
        }
    }

    /// The largest u(t) [m/s].
    pub fn max_velocity(&self) -> f64 {
        match self {
            Self::Ramp { velocity, .. } => *velocity,
            Self::Series(s) => s.max_velocity(),
        }
    }
}
