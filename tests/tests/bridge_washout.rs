//! Issue 5: the bridge-washout scene at its CI size (`cases/bridge-washout-small`: the inflow
//! bore runs up the river, hits the deck, and the deck's bearings let go by S1-22), through the
//! real processes. Two runs of the same scene, which differ only in F_d:
//! - F_d = 100 MN, below the bore's uplift: the deck is held, and does not move, until the window
//!   in which the upward force the fluid sends first exceeds F_d, and is released in that window
//!   (the "releases exactly when the upward force first exceeds F_d"); then the flow
//!   carries it downstream while it rests on its piers (the walls' contact holds it up: with
//!   ρ_g = 3000 kg/m³ it is three times heavier than the water it displaces);
//! - F_d = 1000 MN as in the case file (Table II's value), above any force the bore reaches
//!   here: never released.

use schemas::validation::{record, Record};
use stack_tests::{case_from, coupler_run, csv_rows, out_dir, stderr};
use std::path::Path;
use std::time::Instant;

/// The case's coupling window [s] and particle spacing [m].
const WINDOW: f64 = 2.4e-2;
const SPACING: f64 = 4.0;
/// The deck's centre at rest on its bearings (z: its underside on the pier tops at 12 m).
const DECK_X: f64 = 106.0;
const DECK_Z: f64 = 14.0;
const PIER_TOP: f64 = 12.0;
const HALF_DEPTH: f64 = 2.0;

/// (window end time, upward force the structure received) per window of the ledger.
fn uplift(out: &Path) -> Vec<(f64, f64)> {
    let text = std::fs::read_to_string(out.join("ledger.csv")).unwrap_or_default();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let column = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("no {name} column"))
    };
    let (t, fz) = (column("time"), column("bridge_fz"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap_or(f64::NAN)).collect();
            (v[t], v[fz])
        })
        .collect()
}

/// Runs the small bridge scene with bearings of `release_force` [N].
fn run(test: &str, release_force: &str) -> std::path::PathBuf {
    let dir = out_dir(test);
    let case = case_from("bridge-washout-small", &dir, &[("release_force", release_force)]);
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    assert!(run.status.success(), "{}", stderr(&run));
    out
}

#[test]
fn the_deck_is_released_in_the_window_its_uplift_first_exceeds_f_d_and_carried_off_on_its_piers() {
    let f_d = 1.0e8;
    let started = Instant::now();
    let out = run("bridge-washout-released", "1.0e8");
    let run_time_s = started.elapsed().as_secs_f64();
    let windows = uplift(&out);
    let (first, peak) = windows
        .iter()
        .find(|(_, fz)| *fz > f_d)
        .copied()
        .unwrap_or_else(|| panic!("the uplift never exceeds F_d = {f_d} N"));
    let releases = csv_rows(&out.join("bridge/releases.csv"));
    let released_at = releases.first().map(|r| r[1]).unwrap_or(f64::NAN);
    println!(
        "uplift first above F_d = 100 MN in the window ending at t = {first:.3} s ({:.0} MN); released at t = {released_at:.4} s",
        peak / 1e6
    );
    record(Record {
        id: "bridge-washout-small-release-window".into(),
        capability: "washout of a bridge deck (S1-22) through the coupled stack".into(),
        reference: "S1-22: the bearings let go when the upward force first exceeds F_d (here 100 MN)".into(),
        case: "cases/bridge-washout-small with release_force = 1.0e8 N".into(),
        resolution: "E-MPS, Δs = 4 m, window = Δt = 2.4e-2 s, explicit coupling".into(),
        measure: "end of the window where the uplift first exceeds F_d − release time".into(),
        value: first - released_at,
        bound: Some(WINDOW),
        bound_source: "the release must fall in that window: [0, one window)".into(),
        unit: "s".into(),
        source: "tests/tests/bridge_washout.rs::the_deck_is_released_in_the_window_its_uplift_first_exceeds_f_d_and_carried_off_on_its_piers"
            .into(),
        run_time_s,
        note: Some(format!(
            "uplift first above F_d in the window ending at t = {first:.3} s, released at {released_at:.4} s"
        )),
        ..Default::default()
    });
    assert!(
        released_at > first - WINDOW && released_at <= first + 1e-9,
        "released at t = {released_at}, but the uplift first exceeds F_d in the window ending at {first}"
    );

    // columns t, x, y, z, qw, qx, qy, qz, vx, vy, vz, wx, wy, wz, held
    let history = csv_rows(&out.join("bridge/body-deck.csv"));
    for r in &history {
        let (t, x, z, held) = (r[0], r[1], r[3], r[14]);
        if t < released_at {
            assert!(
                held == 1.0 && x == DECK_X && z == DECK_Z,
                "t = {t}: held {held}, x = {x}, z = {z}"
            );
        } else {
            assert_eq!(held, 0.0, "t = {t}: still held after the release");
        }
        // While its underside is over the piers (they are 12 m long along the flow, the deck is
        // 12 m wide), it rests on them: it sinks into their top layer by less than half a spacing.
        if (x - DECK_X).abs() < 0.5 * SPACING {
            let underside = z - HALF_DEPTH;
            assert!(
                underside > PIER_TOP - 0.5 * SPACING,
                "t = {t}: the deck's underside is at {underside} m, through the pier tops at {PIER_TOP} m"
            );
        }
    }
    let last = history.last().cloned().unwrap_or_default();
    println!(
        "end: deck centre at x = {:.2} m, z = {:.2} m, moving at {:.2} m/s downstream",
        last[1], last[3], last[8]
    );
    assert!(
        last[1] > DECK_X + SPACING,
        "the deck has moved only to x = {} m",
        last[1]
    );
}

#[test]
fn with_table_two_f_d_the_deck_is_never_released() {
    let out = run("bridge-washout-held", "1.0e9");
    let peak = uplift(&out)
        .iter()
        .map(|w| w.1)
        .fold(f64::MIN, schemas::validation::max_or_nan);
    println!("largest uplift {:.0} MN, F_d = 1000 MN", peak / 1e6);
    assert!(peak > 0.0 && peak < 1.0e9, "largest uplift {peak} N");
    let releases = csv_rows(&out.join("bridge/releases.csv"));
    assert!(releases.iter().all(|r| r[1].is_nan()), "released: {releases:?}");
    let history = csv_rows(&out.join("bridge/body-deck.csv"));
    assert!(history.len() > 20);
    assert!(
        history
            .iter()
            .all(|r| r[14] == 1.0 && r[1] == DECK_X && r[3] == DECK_Z),
        "the held deck moved"
    );
}
