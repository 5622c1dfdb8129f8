//! [`InflowSeries`]: an inflow's water level and velocity over time, from a CSV file of rows
//! `t, level, velocity` (s, m, m/s) read by [`LoadTable`] with two components (optional header
//! line, `#` comments; its errors name the file and line: non-increasing times, NaN or infinite
//! values, rows of the wrong width).
//!
//! Between rows h(t) and u(t) are linear (the LoadTable's interpolation): on [t_j, t_{j+1}]
//! h(t) = h_j + (t − t_j)/(t_{j+1} − t_j) · (h_{j+1} − h_j), and likewise u(t); after the last row
//! both hold its values. The first row must be at t ≤ 0, so that both are given from the start.
//!
//! A strip cannot run backwards: u > 0 at every row whose level is > 0, and u ≥ 0 at a row whose
//! level is 0. Then u > 0 wherever h > 0 between rows too: on an interval where h > 0 somewhere,
//! one end has h > 0 (so u > 0 there) and the other u ≥ 0, and a linear u with those ends is > 0
//! inside. The levels must lie in [0, tank height] ([`InflowSeries::check_height`], once the tank
//! is known). Since both are piecewise linear their largest values are at rows.

use crate::case::load_table::LoadTable;
use crate::case::FieldError;
use std::path::{Path, PathBuf};

/// h(t) and u(t) of an inflow from a CSV series (module doc).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct InflowSeries {
    /// Columns level [m], velocity [m/s]; at least two rows, the first at t ≤ 0.
    table: LoadTable,
    /// The file it was read from, for error messages.
    path: PathBuf,
}

impl InflowSeries {
    /// Reads `path` (columns t, level, velocity); errors name `key`, the file and, for bad rows,
    /// the line.
    pub fn read(path: &Path, key: &str) -> Result<Self, FieldError> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            FieldError::new(
                key,
                format!("cannot read the inflow series {}: {e}", path.display()),
            )
        })?;
        Self::parse(&text, key, path)
    }

    /// Parses CSV text (module doc); `path` is only used in error messages.
    pub fn parse(text: &str, key: &str, path: &Path) -> Result<Self, FieldError> {
        let table = LoadTable::parse(text, 2, key, path)?;
        let series = Self {
            table,
            path: path.to_path_buf(),
        };
        let rows = series.table.times().len();
        // LoadTable refuses a table without rows
        if rows < 2 {
            return Err(FieldError::new(
                key,
                format!(
                    "{}: the inflow series has a single row; it needs at least 2 rows `t, level, velocity` (the level and velocity are linear between rows)",
                    path.display()
                ),
            ));
        }
        let t0 = series.table.times()[0];
        if t0 > 0.0 {
            return Err(series.bad_row(
                key,
                0,
                format!("the first time t = {t0} s is after the start: the first row must be at t ≤ 0 so that the level and velocity are given from t = 0"),
            ));
        }
        for i in 0..rows {
            let [level, velocity] = series.values(i);
            if level < 0.0 {
                return Err(series.bad_row(
                    key,
                    i,
                    format!("the level {level} m is below the tank floor: it must be ≥ 0"),
                ));
            }
            if velocity < 0.0 || (velocity == 0.0 && level > 0.0) {
                return Err(series.bad_row(
                    key,
                    i,
                    format!(
                        "the velocity {velocity} m/s at level {level} m: a strip cannot run backwards, so the velocity must be > 0 where the level is > 0 (and ≥ 0 where it is 0)"
                    ),
                ));
            }
        }
        Ok(series)
    }

    /// Refuses a level above the tank's `height` [m], naming its row.
    pub fn check_height(&self, height: f64, key: &str) -> Result<(), FieldError> {
        match (0..self.table.times().len()).find(|&i| self.values(i)[0] > height) {
            Some(i) => Err(self.bad_row(
                key,
                i,
                format!(
                    "the level {} m is above the domain: it must be in [0, {height}] (the tank height)",
                    self.values(i)[0]
                ),
            )),
            None => Ok(()),
        }
    }

    /// h(t) [m]: linear between rows, the last row's after it.
    pub fn level_at(&self, t: f64) -> f64 {
        self.at(t)[0]
    }

    /// u(t) [m/s]: linear between rows, the last row's after it.
    pub fn velocity_at(&self, t: f64) -> f64 {
        self.at(t)[1]
    }

    /// The largest level of the rows, the largest h(t) [m].
    pub fn max_level(&self) -> f64 {
        self.largest(0)
    }

    /// The largest velocity of the rows, the largest u(t) [m/s].
    pub fn max_velocity(&self) -> f64 {
        self.largest(1)
    }

    /// The file it was read from.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// (level, velocity) at `t`.
    fn at(&self, t: f64) -> [f64; 2] {
        let mut out = [0.0; 2];
        self.table.add_at(t, &mut out);
        out
    }

    /// (level, velocity) of row `i`.
    fn values(&self, i: usize) -> [f64; 2] {
        let r = self.table.row(i);
        [r[0], r[1]]
    }

    /// The largest value of column `c` (0: level, 1: velocity) over the rows.
    fn largest(&self, c: usize) -> f64 {
        crate::validation::largest(
            (0..self.table.times().len()).map(|i| self.values(i)[c]),
            f64::NEG_INFINITY,
        )
    }

    /// An error at row `i`, naming the file and its line.
    fn bad_row(&self, key: &str, i: usize, what: String) -> FieldError {
        FieldError::new(
            key,
            format!(
                "{} line {} (t = {} s): {what}",
                self.path.display(),
                self.table.line(i),
                self.table.times()[i]
            ),
        )
    }
}
