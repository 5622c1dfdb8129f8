//! Tests of `schemas::case::fluid::inflow_law`.

use schemas::case::fluid::InflowSeries;
use schemas::case::fluid::*;
use std::path::Path;

#[test]
fn the_ramp_rises_linearly_at_a_constant_velocity() {
    let law = InflowLaw::Ramp {
        velocity: 2.0,
        level: 0.3,
        initial_level: 0.1,
        rise_time: 0.4,
    };
    assert_eq!(law.level_at(-1.0), 0.1);
    assert!((law.level_at(0.2) - 0.2).abs() < 1e-15);
    assert_eq!((law.level_at(0.4), law.level_at(9.0)), (0.3, 0.3));
    assert_eq!((law.velocity_at(0.0), law.velocity_at(3.0)), (2.0, 2.0));
    assert_eq!((law.max_level(), law.max_velocity()), (0.3, 2.0));
}

#[test]
fn a_series_gives_its_rows() {
    let s = InflowSeries::parse("0, 0.1, 1\n1, 0.3, 3\n", "k", Path::new("f.csv")).expect("valid");
    let law = InflowLaw::Series(s);
    assert!((law.level_at(0.5) - 0.2).abs() < 1e-15);
    assert_eq!(law.velocity_at(0.5), 2.0);
    assert_eq!((law.max_level(), law.max_velocity()), (0.3, 3.0));
}
