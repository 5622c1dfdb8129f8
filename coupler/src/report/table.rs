//! The work–precision table: one row per rung, appended to the CSV as each run finishes (so an
//! interrupted report keeps what it measured), and the Markdown table written from the rows.

use std::fmt::Write as _;
use std::io::Write;
use std::path::Path;

/// One measured rung.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub case: String,
    /// The ladder: method or scheme (one line of the plot).
    pub ladder: String,
    /// The varied key and its value on this rung.
    pub parameter: String,
    pub value: f64,
    /// Error in the reference's measure (NaN when the run failed).
    pub error: f64,
    /// Fastest wall time [s] and its CPU time [s].
    pub wall: f64,
    pub cpu: f64,
    /// Timed runs and their spread ((slowest − fastest) / fastest).
    pub runs: u32,
    pub spread: f64,
    /// Coupling windows, or solver steps of a one-solver case.
    pub steps: f64,
    /// Fluid particles × fluid steps (0 without a fluid).
    pub particle_steps: f64,
    /// Peak resident memory of all processes [MB].
    pub peak_mb: f64,
    /// Solver sweeps per coupling window (0 for a one-solver case).
    pub sweeps: f64,
    /// `ok`, or why the rung has no error.
    pub status: String,
}

pub const HEADER: &str =
    "case,ladder,parameter,value,error,wall_s,cpu_s,runs,spread,steps,particle_steps,peak_mb,sweeps_per_window,status";

/// A CSV field, quoted when it holds a comma or a quote.
fn field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\"").replace('\n', " "))
    } else {
        s.to_string()
    }
}

impl Row {
    pub fn csv(&self) -> String {
        format!(
            "{},{},{},{},{:.6e},{:.4},{:.4},{},{:.4},{},{:.6e},{:.1},{:.3},{}",
            field(&self.case),
            field(&self.ladder),
            field(&self.parameter),
            self.value,
            self.error,
            self.wall,
            self.cpu,
            self.runs,
            self.spread,
            self.steps,
            self.particle_steps,
            self.peak_mb,
            self.sweeps,
            field(&self.status)
        )
    }

    /// Parses a line written by [`Row::csv`].
    pub fn parse(line: &str) -> Option<Row> {
        let f = split_csv(line);
        if f.len() != 14 {
            return None;
        }
        let n = |i: usize| f[i].parse::<f64>().ok();
        Some(Row {
            case: f[0].clone(),
            ladder: f[1].clone(),
            parameter: f[2].clone(),
            value: n(3)?,
            error: n(4)?,
            wall: n(5)?,
            cpu: n(6)?,
            runs: f[7].parse().ok()?,
            spread: n(8)?,
            steps: n(9)?,
            particle_steps: n(10)?,
            peak_mb: n(11)?,
            sweeps: n(12)?,
            status: f[13].clone(),
        })
    }
}

/// Splits one CSV line, honouring quoted fields.
pub fn split_csv(line: &str) -> Vec<String> {
    let mut fields = Vec::new();
    let mut current = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                current.push('"');
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(std::mem::take(&mut current)),
            (c, _) => current.push(c),
        }
    }
    fields.push(current);
    fields
}

/// The CSV file of a report, a row appended (and flushed) as each run finishes.
pub struct CsvRows {
    file: std::fs::File,
}

impl CsvRows {
    pub fn create(path: &Path) -> Result<CsvRows, String> {
        let mut file =
            std::fs::File::create(path).map_err(|e| format!("cannot create {}: {e}", path.display()))?;
        writeln!(file, "{HEADER}").map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        Ok(CsvRows { file })
    }

    pub fn push(&mut self, row: &Row) -> Result<(), String> {
        writeln!(self.file, "{}", row.csv())
            .and_then(|_| self.file.flush())
            .map_err(|e| format!("cannot write a report row: {e}"))
    }
}

/// Reads a report CSV back.
pub fn read_rows(path: &Path) -> Vec<Row> {
    std::fs::read_to_string(path)
        .unwrap_or_default()
        .lines()
        .skip(1)
        .filter_map(Row::parse)
        .collect()
}

/// A number in short scientific form for tables.
pub fn sci(v: f64) -> String {
    if v.is_nan() {
        "–".into()
    } else {
        format!("{v:.2e}")
    }
}

/// The Markdown table of one case's rows.
pub fn markdown(rows: &[&Row]) -> String {
    let mut s = String::from(
        "| ladder | parameter | error | wall [s] | CPU [s] | runs (spread) | steps | particle-steps | peak memory [MB] | sweeps/window | status |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} = {} | {} | {:.3} | {:.3} | {} ({:.0} %) | {} | {} | {:.0} | {} | {} |",
            r.ladder,
            r.parameter,
            r.value,
            sci(r.error),
            r.wall,
            r.cpu,
            r.runs,
            100.0 * r.spread,
            r.steps,
            if r.particle_steps > 0.0 {
                sci(r.particle_steps)
            } else {
                "–".into()
            },
            r.peak_mb,
            if r.sweeps > 0.0 {
                format!("{:.2}", r.sweeps)
            } else {
                "–".into()
            },
            r.status
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_round_trip_through_csv() {
        let row = Row {
            case: "osc".into(),
            ladder: "implicit, cubic, \"IQN\"".into(),
            parameter: "coupling.window".into(),
            value: 0.01,
            error: 1.5e-7,
            wall: 0.2,
            cpu: 0.3,
            runs: 3,
            spread: 0.05,
            steps: 100.0,
            particle_steps: 0.0,
            peak_mb: 12.5,
            sweeps: 4.9,
            status: "ok".into(),
        };
        let back = Row::parse(&row.csv()).unwrap();
        assert_eq!(back.ladder, row.ladder);
        assert_eq!(back.value, 0.01);
        assert_eq!(back.status, "ok");
    }
}
