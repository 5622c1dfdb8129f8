//! `[report]`: the ladders `coupler report` runs for the work–precision table, and the families
//! of stiff and extreme runs `coupler report --stability` runs.
//!
//! ```toml
//! [report]
//! target_error = 1e-6                 # the summary names the cheapest setting reaching it
//! repeats = 3                         # timed runs after the warm-up (runs under a few seconds)
//! left_out = ["ISPH: not in the fluid solver yet"]
//!
//! [[report.ladder]]                   # one line of the work–precision plot
//! label = "implicit, cubic, IQN-ILS"
//! set = { "coupling.scheme" = "implicit", "coupling.samples" = 4 }
//! vary = ["coupling.window"]          # keys varied together; the first one labels the rungs
//! values = [0.02, 0.01]               # the CI-sized ladder (an array per rung for several keys)
//! full = [0.04, 0.02, 0.01, 0.005]    # the ladder of `--full`
//! order = 4                           # the order the scheme should have in the first key
//!
//! [[report.limit]]                   # a bound no sound run passes (else: failed silently)
//! participant = "s"
//! file = "point-m1.csv"
//! column = "ux"
//! max_abs = 2.0
//! reason = "energy conservation bounds |u1| by 1 m"
//!
//! [[report.stability]]                # a family: every combination of its axes is one run
//! family = "light bodies"
//! full_only = false                   # true: only with `--full`
//! [[report.stability.axis]]
//! name = "density ratio"
//! labels = ["1.0", "0.1"]
//! set = [{ "structure.s.body.0.mass" = 1.0 }, { "structure.s.body.0.mass" = 0.1 }]
//! ```
//!
//! A setting's key is the dotted path of a case key; a number in the path indexes an array of
//! tables (`structure.s.body.0.mass` is the first `[[structure.s.body]]`'s mass). The value
//! `"unset"` removes the key from the case (e.g. `"fluid.tank.sound_speed" = "unset"` for an ISPH
//! rung of an E-MPS case: ISPH refuses a sound speed).

use super::key_reference::AnyValue;
use super::{Case, FieldError};
use schemars::JsonSchema;
use serde::Deserialize;
use std::collections::BTreeMap;

/// Case keys (dotted paths) and the values they take.
pub type Settings = BTreeMap<String, toml::Value>;

/// `[report]`.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ReportConfig {
    /// The error the summary asks the cheapest setting for, in the reference's measure [error's
    /// unit]: [–] with `reference.relative`, else the compared column's unit.
    pub target_error: f64,
    /// Timed runs after the warm-up, for runs under a few seconds (the minimum is reported).
    #[serde(default = "default_repeats")]
    pub repeats: u32,
    /// The ladders of the work–precision table.
    #[serde(default)]
    pub ladder: Vec<Ladder>,
    /// The families of stiff and extreme runs of `coupler report --stability`.
    #[serde(default)]
    pub stability: Vec<Family>,
    /// Ladders or families this case would have but the solvers cannot run yet, each with why.
    #[serde(default)]
    pub left_out: Vec<String>,
    /// Bounds no sound run passes: a run that claims success beyond one failed silently.
    #[serde(default)]
    pub limit: Vec<Limit>,
    /// What the ladders show and why, printed under the case's summary (e.g. why the error
    /// does not fall as a parameter is refined).
    #[serde(default)]
    pub note: Option<String>,
}

/// `[[report.limit]]`: `|column| ≤ max_abs` in a participant's output file, and why.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Limit {
    /// The participant whose output file is read.
    pub participant: String,
    /// The output file, in the participant's output folder.
    pub file: String,
    /// The bounded column of `file`.
    pub column: String,
    /// The bound on the column's magnitude [column's unit].
    pub max_abs: f64,
    /// Why no sound run passes it (e.g. energy conservation bounds the displacement).
    pub reason: String,
}

fn default_repeats() -> u32 {
    3
}

/// `[[report.ladder]]`: one method or scheme, run at a sequence of one varied parameter.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Ladder {
    /// The ladder's line in the table and the plot.
    pub label: String,
    /// Settings of every rung: case keys (dotted paths) and their values.
    #[serde(default)]
    #[schemars(with = "BTreeMap<String, AnyValue>")]
    pub set: Settings,
    /// The case keys varied together; the first one labels the rungs.
    pub vary: Vec<String>,
    /// The rungs of the CI-sized ladder: a value per rung, or an array per rung for several
    /// keys.
    #[schemars(with = "Vec<AnyValue>")]
    pub values: Vec<toml::Value>,
    /// The rungs of `--full`; default: `values`.
    #[serde(default)]
    #[schemars(with = "Vec<AnyValue>")]
    pub full: Vec<toml::Value>,
    /// The order of convergence the method should have in the first varied key [–].
    #[serde(default)]
    pub order: Option<f64>,
}

/// `[[report.stability]]`.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Family {
    /// The family's name (`--family` picks it).
    pub family: String,
    /// Run only with `--full`.
    #[serde(default)]
    pub full_only: bool,
    /// Settings common to every run of the family.
    #[serde(default)]
    #[schemars(with = "BTreeMap<String, AnyValue>")]
    pub set: Settings,
    /// The axes: every combination of their points is one run.
    pub axis: Vec<Axis>,
}

/// `[[report.stability.axis]]`: one label and one set of settings per point of the axis.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Axis {
    /// The axis's name.
    pub name: String,
    /// One label per point.
    pub labels: Vec<String>,
    /// One table of settings per point: case keys (dotted paths) and their values.
    #[schemars(with = "Vec<BTreeMap<String, AnyValue>>")]
    pub set: Vec<Settings>,
}

/// One rung of a ladder: the varied parameter's value and every setting of the run.
#[derive(Debug, Clone, PartialEq)]
pub struct Rung {
    pub parameter: f64,
    pub settings: Settings,
}

impl Ladder {
    /// The rungs of the CI-sized ladder, or of the full one (`full`, when given).
    pub fn rungs(&self, full: bool) -> Result<Vec<Rung>, String> {
        let values = if full && !self.full.is_empty() {
            &self.full
        } else {
            &self.values
        };
        values
            .iter()
            .enumerate()
            .map(|(i, v)| {
                let parts: Vec<toml::Value> = match (v, self.vary.len()) {
                    (toml::Value::Array(a), n) if n > 1 => a.clone(),
                    (v, 1) => vec![v.clone()],
                    _ => Vec::new(),
                };
                if parts.len() != self.vary.len() {
                    return Err(format!(
                        "value {} must give {} value(s), one for each of {:?}",
                        i + 1,
                        self.vary.len(),
                        self.vary
                    ));
                }
                let parameter = number(&parts[0])
                    .ok_or_else(|| format!("value {}: `{}` must be a number", i + 1, parts[0]))?;
                let mut settings = self.set.clone();
                settings.extend(self.vary.iter().cloned().zip(parts));
                Ok(Rung { parameter, settings })
            })
            .collect()
    }
}

impl Family {
    /// Every combination of the axes: the label of each axis and the settings of the run.
    pub fn runs(&self) -> Vec<(Vec<String>, Settings)> {
        let mut runs = vec![(Vec::new(), self.set.clone())];
        for axis in &self.axis {
            runs = runs
                .into_iter()
                .flat_map(|(labels, settings)| {
                    axis.labels.iter().zip(&axis.set).map(move |(l, s)| {
                        let mut labels = labels.clone();
                        labels.push(l.clone());
                        let mut settings = settings.clone();
                        settings.extend(s.clone());
                        (labels, settings)
                    })
                })
                .collect();
        }
        runs
    }
}

/// A TOML number as f64.
pub fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(f) => Some(*f),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

impl ReportConfig {
    /// Checks every ladder rung (the changed case must be valid) and every family's keys.
    pub fn validate(&self, case: &Case) -> Result<(), FieldError> {
        super::error::check::positive("report.target_error", self.target_error)?;
        if !(1..=20).contains(&self.repeats) {
            return Err(FieldError::new(
                "report.repeats",
                format!("must be 1 … 20, got {}", self.repeats),
            ));
        }
        for (i, ladder) in self.ladder.iter().enumerate() {
            let key = format!("report.ladder[{i}]");
            if ladder.vary.is_empty() {
                return Err(FieldError::new(
                    format!("{key}.vary"),
                    "must name at least one case key",
                ));
            }
            if ladder.values.is_empty() {
                return Err(FieldError::new(
                    format!("{key}.values"),
                    "must hold at least one rung",
                ));
            }
            for full in [false, true] {
                let rungs = ladder.rungs(full).map_err(|m| {
                    FieldError::new(format!("{key}.{}", if full { "full" } else { "values" }), m)
                })?;
                for rung in rungs {
                    check_settings(case, &key, &rung.settings, true)?;
                }
            }
        }
        for (i, limit) in self.limit.iter().enumerate() {
            let key = format!("report.limit[{i}]");
            super::error::check::positive(&format!("{key}.max_abs"), limit.max_abs)?;
            if case.kind_of(&limit.participant).is_none() {
                return Err(FieldError::new(
                    format!("{key}.participant"),
                    format!("`{}` is not a participant of the case", limit.participant),
                ));
            }
        }
        for (i, family) in self.stability.iter().enumerate() {
            let key = format!("report.stability[{i}]");
            if family.axis.is_empty() {
                return Err(FieldError::new(
                    format!("{key}.axis"),
                    "a family needs at least one axis",
                ));
            }
            for (j, axis) in family.axis.iter().enumerate() {
                if axis.labels.is_empty() || axis.labels.len() != axis.set.len() {
                    return Err(FieldError::new(
                        format!("{key}.axis[{j}]"),
                        format!(
                            "needs one `set` table per label: {} label(s), {} table(s)",
                            axis.labels.len(),
                            axis.set.len()
                        ),
                    ));
                }
            }
            // A family may go beyond what the case check allows (that run is reported as refused),
            // so only the keys are checked here.
            for (_, settings) in family.runs() {
                check_settings(case, &key, &settings, false)?;
            }
        }
        Ok(())
    }
}

/// Checks that every key of `settings` has its parent table in the case, and when `valid`,
/// that the case with the settings applied is a valid case.
pub fn check_settings(case: &Case, key: &str, settings: &Settings, valid: bool) -> Result<(), FieldError> {
    let text = apply_settings(&case.text, settings).map_err(|m| FieldError::new(key, m))?;
    if valid {
        Case::parse(&case.path, text).map_err(|e| {
            FieldError::new(
                key,
                format!("with {}: `{}`: {}", describe(settings), e.key, e.message),
            )
        })?;
    }
    Ok(())
}

/// `key = value, …` for messages and labels.
pub fn describe(settings: &Settings) -> String {
    settings
        .iter()
        .map(|(k, v)| format!("{k} = {v}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A setting's value that removes its key from the case instead of setting it.
pub const UNSET: &str = "unset";

/// The case text with each setting applied and without `[report]` and `[reference]` (a run
/// needs neither). A key's parent tables must exist; the key itself may be new; a value of
/// [`UNSET`] removes the key.
pub fn apply_settings(text: &str, settings: &Settings) -> Result<String, String> {
    let mut table: toml::Table = text
        .parse()
        .map_err(|e| format!("the case does not parse: {e}"))?;
    table.remove("report");
    table.remove("reference");
    for (path, value) in settings {
        let parts: Vec<&str> = path.split('.').collect();
        let (last, parents) = parts.split_last().ok_or_else(|| "empty key".to_string())?;
        let mut node = &mut table;
        let mut walked = String::new();
        let mut i = 0;
        while i < parents.len() {
            let part = parents[i];
            walked = if walked.is_empty() {
                part.to_string()
            } else {
                format!("{walked}.{part}")
            };
            let missing = || format!("`{path}`: the case has no `{walked}`");
            let child = node.get_mut(part).ok_or_else(missing)?;
            node = match child {
                toml::Value::Table(t) => t,
                toml::Value::Array(a) => {
                    i += 1;
                    let index: usize = parents
                        .get(i)
                        .and_then(|s| s.parse().ok())
                        .ok_or_else(|| format!("`{path}`: `{walked}` is an array; give an index after it"))?;
                    walked = format!("{walked}.{index}");
                    match a.get_mut(index) {
                        Some(toml::Value::Table(t)) => t,
                        _ => return Err(format!("`{path}`: the case has no table `{walked}`")),
                    }
                }
                _ => return Err(format!("`{path}`: `{walked}` is not a table")),
            };
            i += 1;
        }
        if value.as_str() == Some(UNSET) {
            node.remove(*last);
        } else {
            node.insert(last.to_string(), value.clone());
        }
    }
    toml::to_string(&table).map_err(|e| format!("cannot write the changed case: {e}"))
}
