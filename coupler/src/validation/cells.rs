//! How a record's fields read in a Markdown table cell.

use schemas::markdown::table_cell;
use schemas::validation::Record;

/// Significant digits shown for values and bounds.
const DIGITS: i32 = 3;

/// `v` to three significant digits, plain between 1e-3 and 1e5, else in e-notation; no trailing zeros.
pub fn number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let exponent = v.abs().log10().floor() as i32;
    if (-3..5).contains(&exponent) {
        let decimals = (DIGITS - 1 - exponent).max(0) as usize;
        trim_zeros(&format!("{v:.decimals$}"))
    } else {
        let text = format!("{:.*e}", (DIGITS - 1) as usize, v);
        let (mantissa, exp) = text.split_once('e').unwrap_or((&text, "0"));
        format!("{}e{exp}", trim_zeros(mantissa))
    }
}

/// `text` without the trailing zeros of its decimals (and without a bare trailing point).
fn trim_zeros(text: &str) -> String {
    if !text.contains('.') {
        return text.to_string();
    }
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A number with its unit: "0.022", "2.3 %", "1.4e-14 N s".
pub fn quantity(v: f64, unit: &str) -> String {
    match unit {
        "" => number(v),
        unit => format!("{} {unit}", number(v)),
    }
}

/// The error cell: the value (or "not reproduced" for NaN) and the record's note.
pub fn error(r: &Record) -> String {
    let value = if r.value.is_nan() {
        "**not reproduced**".to_string()
    } else {
        quantity(r.value, &r.unit)
    };
    match &r.note {
        Some(note) => format!("{value} ({})", table_cell(note)),
        None => value,
    }
}

/// The bound cell: the bound and where it comes from, or that the value is reported only.
pub fn bound(r: &Record) -> String {
    let source = table_cell(&r.bound_source);
    match (r.bound, source.is_empty()) {
        (Some(b), true) => quantity(b, &r.unit),
        (Some(b), false) => format!("{} ({source})", quantity(b, &r.unit)),
        (None, true) => "– (reported, not asserted)".into(),
        (None, false) => format!("– (reported, not asserted; {source})"),
    }
}

/// Seconds as "0.42 s", "12.3 s", "4 min 12 s"; "–" when not stated (0).
pub fn run_time(seconds: f64) -> String {
    if seconds <= 0.0 || !seconds.is_finite() {
        "–".into()
    } else if seconds < 60.0 {
        format!("{} s", number(seconds))
    } else {
        let whole = seconds.round() as u64;
        format!("{} min {} s", whole / 60, whole % 60)
    }
}

/// A test named by its source, "crate/tests/file.rs::test": the file and the function's name.
/// None for a one-off run's command.
pub fn test_source(source: &str) -> Option<(&str, &str)> {
    if source.contains(char::is_whitespace) {
        return None;
    }
    let (file, path) = source.split_once("::")?;
    let name = path.rsplit("::").next()?;
    (file.ends_with(".rs") && !name.is_empty()).then_some((file, name))
}

/// The source cell: the CI test, or the test run with `--ignored` when `ignored` (linked from
/// docs/), or the one-off run, with date and machine.
pub fn source(r: &Record, ignored: bool) -> String {
    let when = format!("{}, {}", table_cell(&r.date), table_cell(&r.machine));
    match test_source(&r.source) {
        Some((file, name)) => {
            let short = file.rsplit('/').next().unwrap_or(file);
            let kind = match ignored {
                true => "test run with `--ignored`",
                false => "CI test",
            };
            format!("{kind} [`{short}::{name}`](../{file}) (run {when})")
        }
        None => format!(
            "one-off run, {when}: `{}`",
            table_cell(&r.source).replace('`', "'")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_three_significant_digits() {
        assert_eq!(number(0.022_34), "0.0223");
        assert_eq!(number(0.05), "0.05");
        assert_eq!(number(0.33), "0.33");
        assert_eq!(number(117.63), "118");
        assert_eq!(number(2.0), "2");
        assert_eq!(number(1.4e-14), "1.4e-14");
        assert_eq!(number(-2.3e-4), "-2.3e-4");
        assert_eq!(number(1.0e-3), "0.001");
        assert_eq!(number(123_456.0), "1.23e5");
        assert_eq!(number(0.0), "0");
    }

    #[test]
    fn cells_say_what_is_missing() {
        let r = Record {
            value: f64::NAN,
            note: Some("the 2-core machine cannot run it".into()),
            unit: "%".into(),
            ..Default::default()
        };
        assert_eq!(error(&r), "**not reproduced** (the 2-core machine cannot run it)");
        assert_eq!(bound(&r), "– (reported, not asserted)");
        let r = Record {
            bound: Some(3.0),
            bound_source: "the paper's | spread".into(),
            ..r
        };
        assert_eq!(bound(&r), "3 % (the paper's \\| spread)");
        assert_eq!(run_time(0.0), "–");
        assert_eq!(run_time(1.234), "1.23 s");
        assert_eq!(run_time(252.4), "4 min 12 s");
    }

    #[test]
    fn a_test_is_told_from_a_command() {
        assert_eq!(
            test_source("fluid-solver/tests/dam_break.rs::front_follows"),
            Some(("fluid-solver/tests/dam_break.rs", "front_follows"))
        );
        assert_eq!(
            test_source("coupler/src/laws/drag.rs::tests::uniform"),
            Some(("coupler/src/laws/drag.rs", "uniform"))
        );
        assert_eq!(
            test_source("cargo test --release -p fluid-solver --test all gpu_front::"),
            None
        );
        assert_eq!(test_source("fluid-solver run cases/x.toml"), None);
    }
}
