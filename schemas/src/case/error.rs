//! Errors of case files: every error names the file, the key and what is allowed.

use std::fmt;
use std::path::{Path, PathBuf};

/// A problem with one key of a case, before the file it came from is known.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    /// Dotted key path, e.g. `fluid.tank.spacing`.
    pub key: String,
    /// What is wrong and what is allowed, e.g. "must be > 0, got -1".
    pub message: String,
}

impl FieldError {
    /// An error at `key` with `message`.
    pub fn new(key: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            key: key.into(),
            message: message.into(),
        }
    }
}

/// A case file that cannot be used; names the file, the key and what is allowed.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseError {
    pub file: PathBuf,
    pub key: String,
    pub message: String,
}

impl CaseError {
    /// Attaches the case file to a field error.
    pub fn at(file: &Path, e: FieldError) -> Self {
        Self {
            file: file.to_path_buf(),
            key: e.key,
            message: e.message,
        }
    }
}

impl fmt::Display for CaseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.key.is_empty() {
            write!(f, "{}: {}", self.file.display(), self.message)
        } else {
            write!(f, "{}: `{}`: {}", self.file.display(), self.key, self.message)
        }
    }
}

impl std::error::Error for CaseError {}

/// `message` at byte `offset` of `text`: "line L, column C: message", then the line itself and a
/// caret under the column.
pub fn located(text: &str, offset: usize, message: &str) -> String {
    let offset = offset.min(text.len());
    let before = text.get(..offset).unwrap_or(text);
    let line_no = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let line = text[line_start..].lines().next().unwrap_or("");
    let column = before[line_start..].chars().count() + 1;
    let gutter = line_no.to_string().len();
    format!(
        "line {line_no}, column {column}: {message}\n {line_no} | {line}\n {:gutter$} | {:>column$}",
        "", "^"
    )
}

/// Checks helpers shared by every section's `validate`.
pub mod check {
    use super::FieldError;

    /// `value` must be finite and > 0.
    pub fn positive(key: &str, value: f64) -> Result<(), FieldError> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(FieldError::new(
                key,
                format!("must be a finite number > 0, got {}", short(value)),
            ))
        }
    }

    /// `value` must be finite and ≥ 0.
    pub fn non_negative(key: &str, value: f64) -> Result<(), FieldError> {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(FieldError::new(
                key,
                format!("must be a finite number ≥ 0, got {}", short(value)),
            ))
        }
    }

    /// Every component must be finite.
    pub fn finite(key: &str, values: &[f64]) -> Result<(), FieldError> {
        match values.iter().find(|v| !v.is_finite()) {
            None => Ok(()),
            Some(v) => Err(FieldError::new(key, format!("must be finite, got {v}"))),
        }
    }

    /// `value` must lie in `[lo, hi]`.
    pub fn within(key: &str, value: f64, lo: f64, hi: f64) -> Result<(), FieldError> {
        if value.is_finite() && (lo..=hi).contains(&value) {
            Ok(())
        } else {
            Err(FieldError::new(
                key,
                format!("must be in [{}, {}], got {}", short(lo), short(hi), short(value)),
            ))
        }
    }

    /// A number as a person writes it: `1e-15`, `0.5`, `1000`, `1e300`.
    pub fn short(v: f64) -> String {
        if v != 0.0 && (v.abs() < 1e-3 || v.abs() >= 1e6) {
            format!("{v:e}")
        } else {
            format!("{v}")
        }
    }
}
