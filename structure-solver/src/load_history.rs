//! [`LoadHistory`]: how one prescribed load varies in time — constant, step, ramp or a table.

use schemas::case::load_table::LoadTable;

/// A load's time history; every variant adds its components at time `t` to a slice.
#[derive(Debug, Clone, PartialEq)]
pub enum LoadHistory {
    /// `value` at all times.
    Constant(Vec<f64>),
    /// 0 before `start`, `value` from `start` on (inclusive).
    Step { start: f64, value: Vec<f64> },
    /// 0 before `start`, linear to `value` at `end`, `value` after.
    Ramp { start: f64, end: f64, value: Vec<f64> },
    /// Interpolated from a CSV table.
    Table(LoadTable),
}

impl LoadHistory {
    /// Adds the load's components at time `t` to `out`.
    pub fn add_at(&self, t: f64, out: &mut [f64]) {
        let scaled = |value: &[f64], s: f64, out: &mut [f64]| {
            out.iter_mut().zip(value).for_each(|(o, v)| *o += s * v);
        };
        match self {
            LoadHistory::Constant(value) => scaled(value, 1.0, out),
            LoadHistory::Step { start, value } => {
                if t >= *start {
                    scaled(value, 1.0, out);
                }
            }
            LoadHistory::Ramp { start, end, value } => {
                let s = ((t - start) / (end - start)).clamp(0.0, 1.0);
                scaled(value, s, out);
            }
            LoadHistory::Table(table) => table.add_at(t, out),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(h: &LoadHistory, t: f64) -> f64 {
        let mut out = [0.0];
        h.add_at(t, &mut out);
        out[0]
    }

    #[test]
    fn step_and_ramp_switch_on_at_start() {
        let step = LoadHistory::Step {
            start: 1.0,
            value: vec![5.0],
        };
        assert_eq!(
            (at(&step, 0.999), at(&step, 1.0), at(&step, 7.0)),
            (0.0, 5.0, 5.0)
        );
        let ramp = LoadHistory::Ramp {
            start: 1.0,
            end: 3.0,
            value: vec![4.0],
        };
        assert_eq!(
            (at(&ramp, 0.0), at(&ramp, 2.0), at(&ramp, 3.0), at(&ramp, 9.0)),
            (0.0, 2.0, 4.0, 4.0)
        );
        assert_eq!(at(&LoadHistory::Constant(vec![-2.0]), 123.0), -2.0);
    }
}
