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
