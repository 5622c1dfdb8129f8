//! Tests of `schemas::link::names`.

use schemas::link::LinkError;
use schemas::link::*;

#[test]
fn names_carry_run_and_participant() {
    let n = ServiceNames::new("run-42", "fluid").unwrap();
    assert_eq!(n.down, "tsunami/run-42/fluid/down");
    assert_eq!(n.up_wake, "tsunami/run-42/fluid/up/wake");
    assert_eq!(n.for_side(Side::Participant).0, "tsunami/run-42/fluid/up");
}

#[test]
fn bad_names_are_refused() {
    let long = "x".repeat(MAX_NAME_LEN + 1);
    for (run, part) in [
        ("", "fluid"),
        ("a/b", "fluid"),
        ("run", "fl uid"),
        ("run", long.as_str()),
    ] {
        let err = ServiceNames::new(run, part).unwrap_err();
        assert!(
            matches!(err, LinkError::InvalidName(_)),
            "{run:?} {part:?}: {err}"
        );
    }
}
