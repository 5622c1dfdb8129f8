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

#[cfg(test)]
mod tests {
    use super::*;

    const KEY: &str = "fluid.river.inflow.series";
    const TEXT: &str = "# a surge\nt, level, velocity\n0, 0, 0\n1, 0.4, 2\n\n3, 0.1, 1\n";

    fn series(text: &str) -> Result<InflowSeries, FieldError> {
        InflowSeries::parse(text, KEY, Path::new("inflow.csv"))
    }

    fn refused(text: &str) -> String {
        let e = series(text).expect_err(text);
        assert_eq!(e.key, KEY);
        e.message
    }

    #[test]
    fn linear_between_rows_and_held_after_the_last() {
        let s = series(TEXT).expect("valid");
        for (t, h, u) in [
            (0.0, 0.0, 0.0),
            (0.25, 0.1, 0.5),
            (1.0, 0.4, 2.0),
            (2.0, 0.25, 1.5),
            (3.0, 0.1, 1.0),
            (10.0, 0.1, 1.0),
        ] {
            assert!((s.level_at(t) - h).abs() < 1e-15, "h({t}) = {}", s.level_at(t));
            assert!(
                (s.velocity_at(t) - u).abs() < 1e-15,
                "u({t}) = {}",
                s.velocity_at(t)
            );
        }
        assert_eq!((s.max_level(), s.max_velocity()), (0.4, 2.0));
        assert_eq!(s.path(), Path::new("inflow.csv"));
    }

    #[test]
    fn a_constant_series_gives_its_values_exactly() {
        let s = series("-1, 0.3, 1.0\n5, 0.3, 1.0\n").expect("valid");
        for t in [0.0, 0.1234567, 2.0, 5.0, 7.0] {
            assert_eq!((s.level_at(t), s.velocity_at(t)), (0.3, 1.0));
        }
    }

    #[test]
    fn bad_rows_are_refused_naming_the_file_the_line_and_the_column() {
        let e = refused("t, level, velocity\n0, 0.1, 1\n0, 0.2, 1\n");
        assert!(
            e.contains("inflow.csv line 3") && e.contains("times must increase"),
            "{e}"
        );
        let e = refused("0, 0.1, 1\n1, 0.2, 1\n0.5, 0.2, 1\n");
        assert!(e.contains("line 3") && e.contains("increase"), "{e}");
        let e = refused("0, 0.1, 1\n1, NaN, 1\n");
        assert!(e.contains("inflow.csv line 2") && e.contains("finite"), "{e}");
        let e = refused("t, level, velocity\n0, 0.1, 1\n");
        assert!(
            e.contains("inflow.csv") && e.contains("single row") && e.contains("at least 2"),
            "{e}"
        );
        let e = refused("0.5, 0.1, 1\n1, 0.1, 1\n");
        assert!(
            e.contains("inflow.csv line 1 (t = 0.5 s)") && e.contains("t ≤ 0"),
            "{e}"
        );
        let e = refused("0, 0.1, 1\n1, -0.1, 1\n");
        assert!(
            e.contains("inflow.csv line 2 (t = 1 s)") && e.contains("level -0.1 m") && e.contains("≥ 0"),
            "{e}"
        );
        let e = refused("# head\n0, 0.1, 1\n1, 0.2, 0\n");
        assert!(
            e.contains("inflow.csv line 3") && e.contains("velocity 0 m/s") && e.contains("backwards"),
            "{e}"
        );
        let e = refused("0, 0.0, -0.5\n1, 0.0, 1\n");
        assert!(
            e.contains("line 1") && e.contains("velocity -0.5 m/s") && e.contains("≥ 0 where it is 0"),
            "{e}"
        );
        let e = refused("0, 0.1, 1, 4\n");
        assert!(e.contains("inflow.csv line 1") && e.contains("columns"), "{e}");
        let e = refused("t, level, velocity\n");
        assert!(e.contains("no rows"), "{e}");
    }

    #[test]
    fn a_level_above_the_tank_is_refused_naming_its_row() {
        let s = series(TEXT).expect("valid");
        assert!(s.check_height(0.4, KEY).is_ok());
        let e = s.check_height(0.3, KEY).expect_err("above");
        assert_eq!(e.key, KEY);
        assert!(
            e.message.contains("inflow.csv line 4 (t = 1 s)")
                && e.message.contains("level 0.4 m")
                && e.message.contains("[0, 0.3]"),
            "{}",
            e.message
        );
    }

    #[test]
    fn reads_a_file_and_names_a_missing_one() {
        let path = std::env::temp_dir().join(format!("inflow_series_{}.csv", std::process::id()));
        std::fs::write(&path, TEXT).expect("temp file");
        let read = InflowSeries::read(&path, KEY);
        std::fs::remove_file(&path).expect("temp file");
        let read = read.expect("valid");
        assert_eq!((read.level_at(2.0), read.path()), (0.25, path.as_path()));
        let e = InflowSeries::read(Path::new("/nonexistent/inflow.csv"), KEY).expect_err("missing");
        assert!(
            e.message
                .contains("cannot read the inflow series /nonexistent/inflow.csv"),
            "{}",
            e.message
        );
    }
}
