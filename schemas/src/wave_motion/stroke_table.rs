//! [`StrokeTable`]: a paddle motion read from a CSV file of rows `t, X` (s, m), read by
//! [`LoadTable`] with one component (optional header line, `#` comments; its errors name the
//! file and line).
//!
//! Between rows the stroke L(t) is linear (the LoadTable's interpolation), so its velocity is the
//! slope of the row pair, constant over each interval: L'(t) = (X_{j+1} − X_j) / (t_{j+1} − t_j)
//! on [t_j, t_{j+1}). That keeps the two things the fluid sees consistent — the paddle's position
//! is exactly the integral of its velocity — where a smoothed derivative would not be. Before the
//! first row the paddle holds the first row's stroke, after the last the last one, with velocity 0.
//! The motion is X(t) = r(t) L(t) with the [`Ramp`] r, and X' = r' L + r L' (product rule). A
//! table whose first stroke is not 0 starts displaced at t = 0 unless a ramp brings it in.

use super::ramp::Ramp;
use crate::case::load_table::LoadTable;
use crate::case::FieldError;
use std::path::Path;

/// A piecewise-linear paddle stroke from a CSV table (module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct StrokeTable {
    table: LoadTable,
    /// The rows' times, increasing (at least one).
    times: Vec<f64>,
    /// `slopes[j]`: L' on [t_j, t_{j+1}), m/s.
    slopes: Vec<f64>,
    ramp: Ramp,
}

impl StrokeTable {
    /// Reads `path` (columns t, X); errors name `key`, the file and, for bad rows, the line.
    pub fn read(path: &Path, ramp: Ramp, key: &str) -> Result<Self, FieldError> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            FieldError::new(
                key,
                format!("cannot read the stroke table {}: {e}", path.display()),
            )
        })?;
        Self::parse(&text, ramp, key, path)
    }

    /// Parses CSV text (module doc); `path` is only used in error messages.
    pub fn parse(text: &str, ramp: Ramp, key: &str, path: &Path) -> Result<Self, FieldError> {
        let table = LoadTable::parse(text, 1, key, path)?;
        let times = table.times().to_vec();
        let at = |t: f64| {
            let mut out = [0.0];
            table.add_at(t, &mut out);
            out[0]
        };
        let slopes = times
            .windows(2)
            .map(|w| (at(w[1]) - at(w[0])) / (w[1] - w[0]))
            .collect();
        Ok(Self {
            table,
            times,
            slopes,
            ramp,
        })
    }

    /// The rows' times, increasing.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// The start.
    pub fn ramp(&self) -> Ramp {
        self.ramp
    }

    /// L(t): the table's stroke, linear between rows, held outside them, m.
    fn table_stroke(&self, t: f64) -> f64 {
        let mut out = [0.0];
        self.table.add_at(t, &mut out);
        out[0]
    }

    /// L'(t): the slope of the row pair whose interval [t_j, t_{j+1}) holds t; 0 outside the rows.
    fn table_velocity(&self, t: f64) -> f64 {
        let last = self.times.len() - 1;
        if t < self.times[0] || t >= self.times[last] {
            return 0.0;
        }
        self.slopes[self.times.partition_point(|&x| x <= t) - 1]
    }

    /// X(t) = r(t) L(t), m.
    pub fn stroke(&self, t: f64) -> f64 {
        self.ramp.factor(t) * self.table_stroke(t)
    }

    /// X'(t) = r'(t) L(t) + r(t) L'(t), m/s.
    pub fn velocity(&self, t: f64) -> f64 {
        self.ramp.apply(t, self.table_stroke(t), self.table_velocity(t)).1
    }

    /// The time from which the paddle stands still: the last row's or the ramp's end, s.
    pub fn duration(&self) -> f64 {
        self.times[self.times.len() - 1].max(self.ramp.duration())
    }

    /// The range of X over [0, t_end]. Within the ramp: X at the rows and at every zero of X'
    /// between them, on a grid of T_r / 64 (`extremes` in mod.rs); after it X is piecewise
    /// linear, so its extremes are at the rows and the ends.
    pub fn range(&self, t_end: f64) -> (f64, f64) {
        let t_end = t_end.max(0.0);
        let ramp_end = self.ramp.duration().min(t_end);
        let (mut lo, mut hi) = super::extremes(
            |t| self.stroke(t),
            |t| self.velocity(t),
            &self.times,
            ramp_end,
            self.ramp.duration() / 64.0,
        );
        let after = self.times.iter().copied().filter(|&t| t > ramp_end && t < t_end);
        for t in after.chain([t_end]) {
            let x = self.stroke(t);
            lo = lo.min(x);
            hi = hi.max(x);
        }
        (lo, hi)
    }
}
