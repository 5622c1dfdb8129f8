//! Tests of `schemas::case::fluid::inflow_series`.

use schemas::case::fluid::*;
use schemas::case::FieldError;
use std::path::Path;

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
