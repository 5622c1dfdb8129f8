//! Tests of `schemas::wave_motion::stroke_table`.

use schemas::case::FieldError;
use schemas::wave_motion::ramp::Ramp;
use schemas::wave_motion::stroke_table::*;
use std::path::Path;

const KEY: &str = "fluid.wave_maker.table";
const TEXT: &str = "# a paddle\nt, x\n0, 0\n1, 0.2\n\n3, -0.1\n4, -0.1\n5, 0.05\n";

fn table(text: &str, ramp: Ramp) -> Result<StrokeTable, FieldError> {
    StrokeTable::parse(text, ramp, KEY, Path::new("paddle.csv"))
}

#[test]
fn linear_between_rows_held_outside_with_the_slopes_as_velocity() {
    let t = table(TEXT, Ramp::NONE).expect("valid");
    assert_eq!(
        t.times(),
        vec![0.0, 1.0, 3.0, 4.0, 5.0],
        "header, comment and blank line skipped"
    );
    assert!((t.stroke(0.5) - 0.1).abs() < 1e-15);
    assert!((t.stroke(2.0) - 0.05).abs() < 1e-15);
    assert_eq!((t.stroke(-1.0), t.velocity(-1.0)), (0.0, 0.0));
    assert_eq!((t.stroke(9.0), t.velocity(9.0)), (0.05, 0.0));
    for (time, slope) in [
        (0.0, 0.2),
        (0.99, 0.2),
        (1.0, -0.15),
        (2.5, -0.15),
        (3.5, 0.0),
        (4.2, 0.15),
    ] {
        assert!((t.velocity(time) - slope).abs() < 1e-15, "t = {time}");
    }
    assert_eq!(t.velocity(5.0), 0.0, "at rest from the last row on");
    assert_eq!(t.duration(), 5.0);
}

#[test]
fn the_stroke_is_the_integral_of_the_velocity() {
    // Midpoint rule on 600 000 intervals over [0, 6], none straddling a row or the ramp's end
    // (every row time is a multiple of the step): exact for the constant slopes; within the
    // ramp X''' = r''' L + 3 r'' L' stays below (π/2)³/2 · 0.2 + 3 (π/2)²/2 · 0.2 < 1.2 m/s³,
    // so the error is below Δt² / 24 · 6 s · 1.2 m/s³ = 3e-11 m.
    for ramp in [Ramp::NONE, Ramp::new(2.0).expect("valid")] {
        let t = table(TEXT, ramp).expect("valid");
        let n = 600_000;
        let dt = 6.0 / n as f64;
        let mut x = t.stroke(0.0);
        for i in 0..n {
            x += dt * t.velocity((i as f64 + 0.5) * dt);
            let time = (i + 1) as f64 * dt;
            assert!(
                (x - t.stroke(time)).abs() < 1e-10,
                "t = {time}: {x} vs {}",
                t.stroke(time)
            );
        }
    }
}

#[test]
fn the_ramp_brings_the_paddle_in_from_rest() {
    let t = table("0, 0.3\n2, 0.3\n", Ramp::new(1.0).expect("valid")).expect("valid");
    assert_eq!((t.stroke(0.0), t.velocity(0.0)), (0.0, 0.0));
    assert!((t.stroke(0.5) - 0.15).abs() < 1e-15);
    assert!(
        (t.velocity(0.5) - 0.3 * std::f64::consts::PI / 2.0).abs() < 1e-15,
        "r' L"
    );
    assert_eq!(t.stroke(1.5), 0.3);
    // Without the ramp it starts displaced.
    assert_eq!(
        table("0, 0.3\n2, 0.3\n", Ramp::NONE).expect("valid").stroke(0.0),
        0.3
    );
}

#[test]
fn range_covers_the_rows_and_the_ramp() {
    let t = table(TEXT, Ramp::NONE).expect("valid");
    assert_eq!(t.range(0.5), (0.0, 0.1));
    assert_eq!(t.range(10.0), (-0.1, 0.2));
    let ramped = table(TEXT, Ramp::new(1.5).expect("valid")).expect("valid");
    let (lo, hi) = ramped.range(10.0);
    assert_eq!(lo, -0.1);
    // The maximum is inside the ramp (r L rises while L does, then L falls faster than r
    // rises); against 10⁶ samples of [0, 1.5] (X'' bounded: a step's miss < 1e-12 m).
    let sampled = (0..=1_000_000).map(|i| ramped.stroke(1.5 * i as f64 / 1e6));
    let sampled = schemas::validation::largest(sampled, 0.0);
    assert!(hi < 0.2 && (hi - sampled).abs() < 1e-12, "{hi} vs {sampled}");
}

#[test]
fn errors_name_the_file_and_line() {
    let e = table("0, 0\n1, abc\n", Ramp::NONE).unwrap_err();
    assert_eq!(e.key, KEY);
    assert!(e.message.contains("paddle.csv line 2"), "{}", e.message);
    let e = table("0, 0\n0, 1\n", Ramp::NONE).unwrap_err();
    assert!(
        e.message.contains("line 2") && e.message.contains("increase"),
        "{}",
        e.message
    );
    assert!(table("t, x\n", Ramp::NONE).is_err(), "no rows");
    assert!(table("0, 0, 1\n", Ramp::NONE).is_err(), "two components");
    let missing = Path::new("/nonexistent/paddle.csv");
    let e = StrokeTable::read(missing, Ramp::NONE, KEY).unwrap_err();
    assert!(e.message.contains("/nonexistent/paddle.csv"), "{}", e.message);
}

#[test]
fn reads_a_file() {
    let path = std::env::temp_dir().join(format!("stroke_table_{}.csv", std::process::id()));
    std::fs::write(&path, TEXT).expect("temp file");
    let read = StrokeTable::read(&path, Ramp::NONE, KEY);
    std::fs::remove_file(&path).expect("temp file");
    assert_eq!(read.expect("valid"), table(TEXT, Ramp::NONE).expect("valid"));
}
