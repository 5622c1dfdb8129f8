//! Tests of `schemas::validation`.

use schemas::validation::*;
use std::time::UNIX_EPOCH;

fn sample() -> Record {
    Record {
        id: "emps-front-martin-moyce-l10".into(),
        capability: "E-MPS dam-break front".into(),
        reference: "Martin & Moyce (1952) experiment".into(),
        case: "cases/dam-break-koshizuka".into(),
        resolution: "E-MPS, Δs = L/10".into(),
        measure: "RMS of front position / L".into(),
        value: 0.05,
        bound: Some(0.1),
        bound_source: "the experiment's spread".into(),
        unit: String::new(),
        source: "fluid-solver/tests/dam_break.rs::front".into(),
        run_time_s: 1.5,
        date: String::new(),
        machine: String::new(),
        note: None,
    }
}

#[test]
fn a_record_is_written_with_date_and_machine_and_reads_back() {
    let dir = std::env::temp_dir().join(format!("validation-record-{}", std::process::id()));
    std::env::set_var(RECORDS_DIR_VAR, &dir);
    record(sample());
    std::env::remove_var(RECORDS_DIR_VAR);
    let back = read(&dir.join("emps-front-martin-moyce-l10.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.date.len(), 10, "{}", back.date);
    assert!(back.machine.contains("cores"), "{}", back.machine);
    assert_eq!(
        Record {
            date: String::new(),
            machine: String::new(),
            ..back
        },
        sample()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_comparison_not_reproduced_keeps_its_nan_and_note() {
    let dir = std::env::temp_dir().join(format!("validation-nan-{}", std::process::id()));
    let nan = Record {
        value: f64::NAN,
        bound: None,
        note: Some("not reproduced".into()),
        ..sample()
    };
    write(&dir, &nan).unwrap_or_else(|e| panic!("{e}"));
    let back = read(&dir.join("emps-front-martin-moyce-l10.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert!(back.value.is_nan());
    assert_eq!((back.bound, back.note.as_deref()), (None, Some("not reproduced")));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn dates_are_gregorian() {
    assert_eq!(civil_from_days(0), (1970, 1, 1));
    assert_eq!(civil_from_days(19_782), (2024, 2, 29));
    assert_eq!(
        utc_date(UNIX_EPOCH + std::time::Duration::from_secs(1_767_225_600)),
        "2026-01-01"
    );
}

#[test]
fn largest_abs_keeps_a_nan() {
    assert_eq!(largest_abs([1.0, -3.0, 2.0]), 3.0);
    assert_eq!(largest_abs([]), 0.0);
    assert!(largest_abs([1.0, f64::NAN, 2.0]).is_nan());
    assert!(largest_abs([f64::NAN, 5.0]).is_nan());
}

#[test]
fn largest_and_smallest_keep_a_nan_and_their_bound() {
    assert_eq!(largest([1.0, -3.0, 2.0], 0.0), 2.0);
    assert_eq!(largest([-1.0, -3.0], 0.0), 0.0);
    assert_eq!(smallest([1.0, -3.0, 2.0], f64::INFINITY), -3.0);
    assert_eq!(smallest([], 7.0), 7.0);
    assert!(largest([1.0, f64::NAN, 2.0], 0.0).is_nan());
    assert!(smallest([f64::NAN, 5.0], f64::INFINITY).is_nan());
}
