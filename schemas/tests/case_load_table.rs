//! Tests of `schemas::case::load_table`.

use schemas::case::load_table::*;
use schemas::case::FieldError;
use std::path::Path;

fn table(text: &str) -> Result<LoadTable, FieldError> {
    LoadTable::parse(text, 3, "structure.s.load[0].table", Path::new("f.csv"))
}

fn at(t: &LoadTable, time: f64) -> Vec<f64> {
    let mut out = vec![0.0; 3];
    t.add_at(time, &mut out);
    out
}

#[test]
fn interpolates_linearly_and_holds_outside() {
    let t = table("# comment\nt, fx, fy, fz\n0, 0, 0, 0\n1, 2, -4, 6\n3, 2, 0, 0\n").expect("valid");
    assert_eq!(at(&t, -1.0), vec![0.0, 0.0, 0.0]);
    assert_eq!(at(&t, 0.25), vec![0.5, -1.0, 1.5]);
    assert_eq!(at(&t, 2.0), vec![2.0, -2.0, 3.0]);
    assert_eq!(at(&t, 10.0), vec![2.0, 0.0, 0.0]);
}

#[test]
fn a_header_is_allowed_only_first_and_rows_must_be_complete() {
    assert!(table("0,1,2,3\nt,fx,fy,fz\n").is_err());
    assert!(table("t,fx,fy,fz\n").is_err(), "no rows");
    assert!(table("0,1,2,nan\n").is_err(), "non-finite");
    let e = table("0,1,2,3\n1,1,2,3,4\n").unwrap_err();
    assert!(e.message.contains("f.csv line 2"), "{}", e.message);
}

#[test]
fn rows_keep_their_values_and_lines() {
    let t = table("# comment\nt, fx, fy, fz\n0, 1, 2, 3\n\n2, 4, 5, 6\n").expect("valid");
    assert_eq!((t.row(0), t.line(0)), (&[1.0, 2.0, 3.0][..], 3));
    assert_eq!((t.row(1), t.line(1)), (&[4.0, 5.0, 6.0][..], 5));
}
