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

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn the_ramp_rises_linearly_at_a_constant_velocity() {
        let law = InflowLaw::Ramp {
            velocity: 2.0,
            level: 0.3,
            initial_level: 0.1,
            rise_time: 0.4,
        };
        assert_eq!(law.level_at(-1.0), 0.1);
        assert!((law.level_at(0.2) - 0.2).abs() < 1e-15);
        assert_eq!((law.level_at(0.4), law.level_at(9.0)), (0.3, 0.3));
        assert_eq!((law.velocity_at(0.0), law.velocity_at(3.0)), (2.0, 2.0));
        assert_eq!((law.max_level(), law.max_velocity()), (0.3, 2.0));
    }

    #[test]
    fn a_series_gives_its_rows() {
        let s = InflowSeries::parse("0, 0.1, 1\n1, 0.3, 3\n", "k", Path::new("f.csv")).expect("valid");
        let law = InflowLaw::Series(s);
        assert!((law.level_at(0.5) - 0.2).abs() < 1e-15);
        assert_eq!(law.velocity_at(0.5), 2.0);
        assert_eq!((law.max_level(), law.max_velocity()), (0.3, 3.0));
    }
}
