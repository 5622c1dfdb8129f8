//! `[reference]`: what a case's result is compared against, and how the error is measured.
//!
//! ```toml
//! [reference]
//! against = "exact"                       # "exact" | "experiment" | "finer-run" | "resolved-run"
//! solution = "constant"                   # exact: "constant" (value) | "two-mass-oscillator"
//! value = -4.031e-4                       # the exact value (solution = "constant")
//! participant = "beam"                    # whose output file is compared (none: the run's own, e.g. ledger.csv)
//! file = "node-5.csv"                     # a CSV with a header line, `t` first
//! column = "z"
//! from = 0.6                              # compare rows with from ≤ t ≤ until
//! measure = "max"                         # "max" | "rms" of the differences | "integral" of them
//! relative = true                         # divide by the reference's largest magnitude
//! source = "Timoshenko: PL³/3EI + PL/κGA"
//! ```
//!
//! Experimental data (`against = "experiment"`) are a CSV in the case folder (`data`, lines
//! starting with `#` are comments, then a header line) whose `data_time` and `data_value`
//! columns, times `time_scale` and `value_scale`, give the model's time and value. A finer run
//! (`against = "finer-run"`) is the same case with the settings of `set` (e.g. a smaller
//! spacing); its output is interpolated in time at the compared run's rows. A resolved run
//! (`against = "resolved-run"`) is another case file of the same scene (`case`, relative to the
//! case folder: e.g. a prism made of body particles for a prism coupled by a drag law) run with
//! the settings of `set`, and compared the same way. A file's time is its `t` or `time` column
//! (else its first).

use super::error::check;
use super::key_reference::AnyValue;
use super::report::{check_settings, Settings};
use super::{Case, FieldError, Kind};
use schemars::JsonSchema;
use serde::Deserialize;
use std::path::PathBuf;

/// What the error is measured against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Against {
    /// A closed-form solution.
    Exact,
    /// Measured data in the case folder, with its source.
    Experiment,
    /// The same case run finer (the settings of `set`).
    FinerRun,
    /// Another case file of the same scene with the structure resolved (`case`, with `set`).
    ResolvedRun,
}

/// Closed-form solutions the report knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Solution {
    /// One value, held over the compared rows (a static deflection, a hydrostatic pressure).
    Constant,
    /// The two-mass oscillator u1 = ½(cos 2πt + cos 6πt), u2 = ½(cos 2πt − cos 6πt), compared
    /// at every window end in the recording (largest error of both masses).
    TwoMassOscillator,
}

/// How the differences over the compared rows become one number.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Measure {
    /// Largest absolute difference.
    Max,
    /// Root mean square of the differences.
    Rms,
    /// |∫ (computed − reference) dt| over the compared rows (trapezoids at the run's rows), e.g.
    /// an impulse error; relative: divided by |∫ reference dt|.
    Integral,
}

/// `[reference]`.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ReferenceConfig {
    /// What the error is measured against.
    pub against: Against,
    /// How the differences over the compared rows become one number.
    pub measure: Measure,
    /// Divide the error by the reference's largest magnitude over the compared rows.
    #[serde(default)]
    pub relative: bool,
    /// Where the reference comes from (formula, paper, data set).
    pub source: String,
    /// `against = "exact"`: which solution.
    #[serde(default)]
    pub solution: Option<Solution>,
    /// `solution = "constant"`: the exact value [column's unit].
    #[serde(default)]
    pub value: Option<f64>,
    /// `solution = "two-mass-oscillator"`: the participants holding m1 and m2 (their first point).
    #[serde(default)]
    pub participants: Vec<String>,
    /// The participant whose output file is compared; none: the coupled run's own file
    /// (`ledger.csv`).
    #[serde(default)]
    pub participant: Option<String>,
    /// The output file, in the participant's output folder.
    #[serde(default)]
    pub file: Option<String>,
    /// The compared column of `file`.
    #[serde(default)]
    pub column: Option<String>,
    /// Rows with `t ≥ from` are compared [s].
    #[serde(default)]
    pub from: Option<f64>,
    /// Rows with `t ≤ until` are compared [s].
    #[serde(default)]
    pub until: Option<f64>,
    /// `against = "experiment"`: the data file, relative to the case folder.
    #[serde(default)]
    pub data: Option<PathBuf>,
    /// `against = "experiment"`: the time column of `data`.
    #[serde(default)]
    pub data_time: Option<String>,
    /// `against = "experiment"`: the value column of `data`.
    #[serde(default)]
    pub data_value: Option<String>,
    /// Model time = data time × `time_scale` [–].
    #[serde(default = "one")]
    pub time_scale: f64,
    /// Model value = data value × `value_scale` [–].
    #[serde(default = "one")]
    pub value_scale: f64,
    /// `against = "finer-run"`: the settings that make the run finer; `"resolved-run"`: the
    /// settings of the resolved run.
    #[serde(default)]
    #[schemars(with = "std::collections::BTreeMap<String, AnyValue>")]
    pub set: Settings,
    /// `against = "resolved-run"`: the resolved case file, relative to the case folder.
    #[serde(default)]
    pub case: Option<PathBuf>,
}

fn one() -> f64 {
    1.0
}

impl ReferenceConfig {
    /// Checks the section against the case: every field its kind needs, participants that
    /// exist, data that can be read.
    pub fn validate(&self, case: &Case) -> Result<(), FieldError> {
        let k = |f: &str| format!("reference.{f}");
        let need = |name: &str, present: bool| match present {
            true => Ok(()),
            false => Err(FieldError::new(
                k(name),
                format!("is needed with against = \"{}\"", self.against_name()),
            )),
        };
        if self.source.trim().is_empty() {
            return Err(FieldError::new(
                k("source"),
                "must say where the reference comes from",
            ));
        }
        check::positive(&k("time_scale"), self.time_scale)?;
        check::positive(&k("value_scale"), self.value_scale)?;
        if let (Some(a), Some(b)) = (self.from, self.until) {
            if a > b {
                return Err(FieldError::new(
                    k("until"),
                    format!("must be ≥ from ({a}), got {b}"),
                ));
            }
        }
        let oscillator = self.solution == Some(Solution::TwoMassOscillator);
        if oscillator {
            if self.participants.len() != 2 {
                return Err(FieldError::new(
                    k("participants"),
                    "the two-mass oscillator needs the two structure participants holding m1 and m2",
                ));
            }
            for (i, p) in self.participants.iter().enumerate() {
                if case.kind_of(p) != Some(Kind::Structure) {
                    return Err(FieldError::new(
                        format!("reference.participants[{i}]"),
                        format!("`{p}` is not a structure participant of the case"),
                    ));
                }
            }
            if case.coupling.is_none() {
                return Err(FieldError::new(
                    k("solution"),
                    "two-mass-oscillator reads the coupled run's recording: the case needs [coupling]",
                ));
            }
        } else {
            if case.coupling.is_none() {
                need("participant", self.participant.is_some())?;
            }
            need("file", self.file.as_deref().is_some_and(|f| !f.is_empty()))?;
            need("column", self.column.as_deref().is_some_and(|c| !c.is_empty()))?;
            if let Some(p) = &self.participant {
                if case.kind_of(p).is_none() {
                    return Err(FieldError::new(
                        k("participant"),
                        format!("`{p}` is not a participant of the case"),
                    ));
                }
            }
        }
        match self.against {
            Against::Exact => {
                need("solution", self.solution.is_some())?;
                if self.solution == Some(Solution::Constant) {
                    need("value", self.value.is_some())?;
                    check::finite(&k("value"), &[self.value.unwrap_or_default()])?;
                }
            }
            Against::Experiment => {
                need("data", self.data.is_some())?;
                need("data_time", self.data_time.is_some())?;
                need("data_value", self.data_value.is_some())?;
                let path = case.resolve(self.data.as_deref().unwrap_or_else(|| std::path::Path::new("")));
                let (t, v) = (
                    self.data_time.as_deref().unwrap_or(""),
                    self.data_value.as_deref().unwrap_or(""),
                );
                let points = read_data(&path, t, v).map_err(|m| FieldError::new(k("data"), m))?;
                if points.len() < 2 {
                    return Err(FieldError::new(
                        k("data"),
                        format!("{} holds fewer than 2 points", path.display()),
                    ));
                }
            }
            Against::FinerRun => {
                if self.set.is_empty() {
                    return Err(FieldError::new(
                        k("set"),
                        "must name the settings of the finer run",
                    ));
                }
                check_settings(case, &k("set"), &self.set, true)?;
            }
            Against::ResolvedRun => {
                let resolved = self.resolved_case(case)?;
                check_settings(&resolved, &k("set"), &self.set, true)?;
            }
        }
        if self.against != Against::ResolvedRun && self.case.is_some() {
            return Err(FieldError::new(
                k("case"),
                "belongs to against = \"resolved-run\" only",
            ));
        }
        if self.against != Against::Exact && self.solution.is_some() {
            return Err(FieldError::new(
                k("solution"),
                "belongs to against = \"exact\" only",
            ));
        }
        Ok(())
    }

    /// `against = "resolved-run"`: the resolved case, loaded.
    pub fn resolved_case(&self, case: &Case) -> Result<Case, FieldError> {
        let file = self.case.as_deref().ok_or_else(|| {
            FieldError::new(
                "reference.case",
                "is needed with against = \"resolved-run\": the resolved case file",
            )
        })?;
        let path = case.resolve(file);
        Case::load(&path).map_err(|e| FieldError::new("reference.case", e.to_string()))
    }

    fn against_name(&self) -> &'static str {
        match self.against {
            Against::Exact => "exact",
            Against::Experiment => "experiment",
            Against::FinerRun => "finer-run",
            Against::ResolvedRun => "resolved-run",
        }
    }
}

/// The `(time, value)` pairs of columns `time` and `value` of a data CSV (`#` lines are
/// comments, the first other line is the header).
pub fn read_data(path: &std::path::Path, time: &str, value: &str) -> Result<Vec<(f64, f64)>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut lines = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'));
    let header: Vec<&str> = lines
        .next()
        .unwrap_or_default()
        .split(',')
        .map(str::trim)
        .collect();
    let col = |name: &str| {
        header.iter().position(|h| *h == name).ok_or_else(|| {
            format!(
                "{} has no column `{name}`; its columns are {header:?}",
                path.display()
            )
        })
    };
    let (ti, vi) = (col(time)?, col(value)?);
    lines
        .enumerate()
        .map(|(n, line)| {
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            let num = |i: usize| fields.get(i).and_then(|f| f.parse::<f64>().ok());
            match (num(ti), num(vi)) {
                (Some(t), Some(v)) => Ok((t, v)),
                _ => Err(format!(
                    "{}: data line {} is not two numbers: `{line}`",
                    path.display(),
                    n + 1
                )),
            }
        })
        .collect()
}
