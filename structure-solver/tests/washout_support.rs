//! Washout supports (S1-22): a body is held until the upward applied force exceeds F_d, then
//! moves freely for good.

use schemas::case::Case;
use schemas::validation::{record, Record};
use std::path::Path;
use std::time::Instant;
use structure_solver::{ExternalLoads, Structure};

/// A 1 kg body under gravity, held by a support with threshold `release_force`, and an upward
/// ramp load F(t) = 1000 t N (so F = 10 k N at the start of substep k of 0.01 s).
fn held_body(release_force: f64) -> (Structure, impl Fn(f64) -> Result<ExternalLoads, String>) {
    let text = format!(
        r#"
[case]
name = "washout"
end_time = 1.5

[structure.s]
max_step = 0.01
gravity = [0, 0, -9.8]

[[structure.s.body]]
name = "deck"
mass = 1.0
centre = [0, 0, 5]
inertia = {{ box = [1, 1, 1] }}

[[structure.s.support]]
body = "deck"
release_force = {release_force}
"#
    );
    let case = Case::parse(Path::new("washout.toml"), text).expect("valid test case");
    let s = Structure::from_config(&case.structure["s"], "structure.s").expect("test case builds");
    let loads = |t: f64| {
        let mut l = ExternalLoads::zeros(0, 1, 0);
        l.body_force[2] = 1000.0 * t;
        Ok(l)
    };
    (s, loads)
}

#[test]
fn releases_in_the_step_where_the_upward_force_first_exceeds_the_threshold() {
    // F_d = 105 N: F(0.10) = 100 N ≤ F_d, F(0.11) = 110 N > F_d, so the substep starting at
    // t = 0.11 s is the first free one (exact, by the definition of the check; no tolerance but
    // round-off on the time, 1e-12 s).
    let (mut s, loads) = held_body(105.0);
    let started = Instant::now();
    for k in 1..=11 {
        s.advance(0.01 * f64::from(k), &loads).expect("stable");
        assert!(s.is_held(0), "released too early, before t = {}", s.time());
        assert_eq!(s.bodies()[0].centre().z, 5.0, "a held body does not move");
        assert_eq!(s.bodies()[0].velocity().z, 0.0);
    }
    s.advance(0.12, &loads).expect("stable");
    assert!(
        !s.is_held(0),
        "not released in the substep starting at t = 0.11 s"
    );
    let run_time_s = started.elapsed().as_secs_f64();
    let releases = s.releases();
    assert_eq!(releases.len(), 1);
    assert_eq!(releases[0].0, "deck");
    record(Record {
        id: "washout-support-release-time".into(),
        capability: "washout support (S1-22)".into(),
        reference: "S1-22: released in the substep where the upward force first exceeds F_d, t = 0.11 s \
                    for F = 1000 t N and F_d = 105 N"
            .into(),
        case: "1 kg body held by a support with F_d = 105 N under an upward ramp 1000 t N".into(),
        resolution: "max_step = 0.01 s".into(),
        measure: "|release time − 0.11 s|".into(),
        value: (releases[0].1 - 0.11).abs(),
        bound: Some(1e-12),
        bound_source: "exact by the definition of the check: round-off on the time only".into(),
        unit: "s".into(),
        source: "structure-solver/tests/washout_support.rs::releases_in_the_step_where_the_upward_force_first_exceeds_the_threshold"
            .into(),
        run_time_s,
        ..Default::default()
    });
    assert!(
        (releases[0].1 - 0.11).abs() < 1e-12,
        "released at {} s",
        releases[0].1
    );
    assert!(
        s.bodies()[0].centre().z > 5.0,
        "the released body rises under 110 N against 9.8 N"
    );
    // Released for good: the load drops below F_d again, the body stays free.
    let falling = |_t: f64| Ok(ExternalLoads::zeros(0, 1, 0));
    s.advance(0.5, &falling).expect("stable");
    assert!(!s.is_held(0));
    assert!(
        s.bodies()[0].velocity().z < 0.0,
        "falls freely once the load is gone"
    );
}

#[test]
fn never_releases_when_the_threshold_is_above_every_force_reached() {
    // F(t) ≤ 1500 N over 1.5 s; F_d = 2000 N is never exceeded: the body never moves.
    let (mut s, loads) = held_body(2000.0);
    s.advance(1.5, &loads).expect("stable");
    assert!(s.is_held(0));
    assert!(s.releases().is_empty());
    assert_eq!(s.bodies()[0].centre().z, 5.0);
    assert_eq!(s.bodies()[0].displacement().norm(), 0.0);
}
