//! Tests of `schemas::wave_motion`.

use flap::{FlapHinge, FlapMotion};
use goring::GoringSolitary;
use ramp::Ramp;
use regular::RegularWaves;
use schemas::wave_motion::*;
use stroke_table::StrokeTable;

const G: f64 = 9.81;

#[test]
fn the_enum_dispatches_to_each_motion() {
    let solitary = GoringSolitary::new(0.1, 0.5, G).expect("valid");
    let regular = RegularWaves::new(0.05, 1.0, 0.5, G, Ramp::new(2.0).expect("valid")).expect("valid");
    let table =
        StrokeTable::parse("0,0\n1,0.1\n", Ramp::NONE, "k", std::path::Path::new("f.csv")).expect("valid");
    let t = 1.7;
    let m = PistonMotion::Solitary(solitary);
    assert_eq!(
        (m.stroke(t), m.velocity(t)),
        (solitary.stroke(t), solitary.velocity(t))
    );
    assert_eq!(m.range(t), solitary.range(t));
    assert_eq!(m.duration(), Some(solitary.duration()));
    let m = PistonMotion::Regular(regular);
    assert_eq!(
        (m.stroke(t), m.velocity(t)),
        (regular.stroke(t), regular.velocity(t))
    );
    assert_eq!(m.duration(), None);
    let m = PistonMotion::Table(table.clone());
    assert_eq!(
        (m.stroke(0.5), m.velocity(0.5)),
        (table.stroke(0.5), table.velocity(0.5))
    );
    assert_eq!(m.range(3.0), (0.0, 0.1));
    assert_eq!(m.duration(), Some(1.0));
    let piston = WaveMakerMotion::Piston(PistonMotion::Solitary(solitary));
    assert_eq!(
        (piston.stroke(t), piston.velocity(t), piston.range(t)),
        (solitary.stroke(t), solitary.velocity(t), solitary.range(t))
    );
    let hinge = FlapHinge::new(-0.1, 0.0, 0.5).expect("valid");
    let flap = FlapMotion::solitary(0.1, G, hinge).expect("valid");
    let m = WaveMakerMotion::Flap(flap.clone());
    assert_eq!(
        (m.stroke(t), m.velocity(t), m.range(t)),
        (flap.stroke(t), flap.velocity(t), flap.range(t))
    );
}

#[test]
fn extremes_finds_interior_turning_points_and_respects_breaks() {
    // x = sin t on [0, 10]: extremes ±1 at π/2 and 3π/2 (and 5π/2).
    let (lo, hi) = extremes(f64::sin, f64::cos, &[], 10.0, 0.1);
    assert!((lo + 1.0).abs() < 1e-15 && (hi - 1.0).abs() < 1e-15, "{lo} {hi}");
    // A tent with a kink at 1 (v jumps from +1 to −1): the maximum is the break itself.
    let tent = |t: f64| 1.0 - (t - 1.0).abs();
    let slope = |t: f64| if t < 1.0 { 1.0 } else { -1.0 };
    assert_eq!(extremes(tent, slope, &[1.0], 1.5, 0.01), (0.0, 1.0));
    // t_end ≤ 0: the range of the point 0.
    assert_eq!(extremes(f64::cos, |t| -t.sin(), &[], -1.0, 0.1), (1.0, 1.0));
}
