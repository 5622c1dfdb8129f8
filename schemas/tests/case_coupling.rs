//! Tests of `schemas::case::coupling`.

use schemas::case::coupling::*;

fn parse(extra: &str) -> CouplingConfig {
    toml::from_str(&format!("window = 0.01\nscheme = \"implicit\"\n{extra}")).unwrap()
}

#[test]
fn resolved_bodies_default_to_iqn_ils_and_a_given_acceleration_stands() {
    let body = "[[body]]\nfluid = \"tank/box\"\nstructure = \"floater/box\"\n";
    assert_eq!(parse("").acceleration(), AccelerationKind::Aitken);
    assert_eq!(parse(body).acceleration(), AccelerationKind::IqnIls);
    let aitken = format!("acceleration = \"aitken\"\n{body}");
    assert_eq!(parse(&aitken).acceleration(), AccelerationKind::Aitken);
}

#[test]
fn the_ledger_tolerance_defaults_by_backend_and_a_given_one_is_kept() {
    let c = parse("");
    assert_eq!(c.balance_tolerance(false), CPU_BALANCE_TOLERANCE);
    assert_eq!(c.balance_tolerance(true), GPU_BALANCE_TOLERANCE);
    let c = parse("balance_tolerance = 1e-9");
    assert_eq!(c.balance_tolerance(false), 1e-9);
    assert_eq!(c.balance_tolerance(true), 1e-9);
}
