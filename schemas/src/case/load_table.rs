//! [`LoadTable`]: a load history read from a CSV file — columns `t, c1, …, cn`, optional header
//! line, `#` comments; linear interpolation between rows, the first/last row held outside.

use super::FieldError;
use std::path::Path;

/// Rows of time and `n` components, times strictly increasing.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LoadTable {
    times: Vec<f64>,
    /// Row-major, `components` values per row.
    values: Vec<f64>,
    components: usize,
    /// The file's line (from 1) of each row, for error messages.
    lines: Vec<usize>,
}

impl LoadTable {
    /// Reads `path` expecting `components` load columns after the time; errors name `key` and the file.
    pub fn read(path: &Path, components: usize, key: &str) -> Result<Self, FieldError> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            FieldError::new(key, format!("cannot read the load table {}: {e}", path.display()))
        })?;
        Self::parse(&text, components, key, path)
    }

    /// Parses CSV text (see the module doc); `path` is only used in error messages.
    pub fn parse(text: &str, components: usize, key: &str, path: &Path) -> Result<Self, FieldError> {
        let mut times: Vec<f64> = Vec::new();
        let mut values = Vec::new();
        let mut lines = Vec::new();
        let mut seen_row = false;
        let bad = |line: usize, what: String| {
            FieldError::new(key, format!("{} line {line}: {what}", path.display()))
        };
        for (i, line) in text.lines().enumerate() {
            let line_no = i + 1;
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            let numbers: Result<Vec<f64>, _> = cells.iter().map(|c| c.parse::<f64>()).collect();
            let Ok(numbers) = numbers else {
                let is_header = !seen_row && cells.iter().all(|c| c.parse::<f64>().is_err());
                if is_header {
                    seen_row = true;
                    continue;
                }
                return Err(bad(
                    line_no,
                    format!(
                        "expected {} numbers (t and {components} components), got `{line}`",
                        components + 1
                    ),
                ));
            };
            seen_row = true;
            if numbers.len() != components + 1 {
                return Err(bad(
                    line_no,
                    format!(
                        "expected {} columns (t and {components} components), got {}",
                        components + 1,
                        numbers.len()
                    ),
                ));
            }
            if let Some(v) = numbers.iter().find(|v| !v.is_finite()) {
                return Err(bad(line_no, format!("values must be finite, got {v}")));
            }
            if let Some(&last) = times.last() {
                if numbers[0] <= last {
                    return Err(bad(
                        line_no,
                        format!("times must increase, but {} follows {last}", numbers[0]),
                    ));
                }
            }
            times.push(numbers[0]);
            values.extend_from_slice(&numbers[1..]);
            lines.push(line_no);
        }
        if times.is_empty() {
            return Err(FieldError::new(
                key,
                format!("{}: the load table has no rows", path.display()),
            ));
        }
        Ok(Self {
            times,
            values,
            components,
            lines,
        })
    }

    /// The rows' times, strictly increasing (at least one).
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// The components of row `i` (from 0), as written.
    pub fn row(&self, i: usize) -> &[f64] {
        &self.values[i * self.components..(i + 1) * self.components]
    }

    /// The file's line (from 1) that holds row `i` (from 0).
    pub fn line(&self, i: usize) -> usize {
        self.lines[i]
    }

    /// Adds the interpolated components at time `t` to `out` (length `components`).
    pub fn add_at(&self, t: f64, out: &mut [f64]) {
        let last = self.times.len() - 1;
        let (i, w) = if t <= self.times[0] {
            (0, 0.0)
        } else if t >= self.times[last] {
            (last, 0.0)
        } else {
            let j = self.times.partition_point(|&x| x <= t) - 1;
            (j, (t - self.times[j]) / (self.times[j + 1] - self.times[j]))
        };
        let a = self.row(i);
        if w == 0.0 {
            out.iter_mut().zip(a).for_each(|(o, v)| *o += v);
        } else {
            let b = self.row(i + 1);
            out.iter_mut()
                .zip(a.iter().zip(b))
                .for_each(|(o, (x, y))| *o += x + w * (y - x));
        }
    }
}
