//! Issue 5: a box floating at rest in still water, through the real processes (`coupler run`
//! with the E-MPS fluid and the rigid-body structure solver, explicit coupling, one fluid step
//! per window). It must settle at its hydrostatic draft (body density / water density × height)
//! within 5 % (the bound) and its heave must die out. Gravity acts once on each side:
//! the fluid reports pressure and contact forces only, the structure applies the box's weight.

use schemas::validation::{record, Record};
use stack_tests::{coupler_run, csv_rows, out_dir, pool_level, stderr, FLOATING_POOL_CASE};
use std::time::Instant;

const HEIGHT: f64 = 0.08;
const DENSITY_RATIO: f64 = 0.4;

#[test]
fn a_box_floats_at_its_hydrostatic_draft_and_its_heave_settles() {
    let dir = out_dir("floating-at-rest");
    let case = dir.join("case.toml");
    std::fs::write(&case, FLOATING_POOL_CASE).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let started = Instant::now();
    let run = coupler_run(&case, &out);
    let run_time_s = started.elapsed().as_secs_f64();
    let err = stderr(&run);
    println!("{err}");
    assert!(run.status.success(), "{err}");

    // The box's height over the run (columns t, x, y, z, qw, …).
    let rows = csv_rows(&out.join("float/body-box.csv"));
    assert!(rows.len() > 150, "history rows: {}", rows.len());
    let late: Vec<&Vec<f64>> = rows.iter().filter(|r| r[0] >= 1.5).collect();
    let z_mean = late.iter().map(|r| r[3]).sum::<f64>() / late.len() as f64;
    let (z_lo, z_hi) = late
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), r| (lo.min(r[3]), hi.max(r[3])));
    let tilt = late
        .iter()
        .map(|r| 2.0 * (r[5] * r[5] + r[6] * r[6]).sqrt().asin())
        .fold(0.0, schemas::validation::max_or_nan);

    // The free surface at the end, away from the box, where the pressure field's P = 0.
    let (level, top, interior) = pool_level(&out.join("pool/pool_00004.vtu"));
    assert!(interior > 1000, "interior particles: {interior}");
    let last = rows.last().cloned().unwrap_or_default();
    let bottom = last[3] - 0.5 * HEIGHT;
    let draft = level - bottom;
    let expected = DENSITY_RATIO * HEIGHT;
    println!(
        "t ≥ 1.5 s: box centre z mean {z_mean:.5} m, range {:.2} mm, tilt ≤ {:.3}°; free surface {level:.5} m (highest particle {top:.5} m); draft {:.2} mm, hydrostatic {:.2} mm ({:+.2} %)",
        1e3 * (z_hi - z_lo),
        tilt.to_degrees(),
        1e3 * draft,
        1e3 * expected,
        100.0 * (draft / expected - 1.0)
    );
    record(Record {
        id: "floating-box-draft-emps".into(),
        capability: "resolved floating body at rest (E-MPS, coupled)".into(),
        reference: "hydrostatic draft: body density / water density × height = 32.0 mm (Archimedes)".into(),
        case: "16 × 16 × 8 cm box of 400 kg/m³ in still water 0.2 m deep, 2 s".into(),
        resolution: "E-MPS, Δs = 0.02 m, Δt = 8e-4 s, explicit coupling, one fluid step per window".into(),
        measure: "|draft / hydrostatic − 1| at the end, from the free surface where P = 0".into(),
        value: (draft / expected - 1.0).abs(),
        bound: Some(0.05),
        bound_source: "the issue (issue 5)".into(),
        source:
            "tests/tests/floating_at_rest.rs::a_box_floats_at_its_hydrostatic_draft_and_its_heave_settles"
                .into(),
        run_time_s,
        ..Default::default()
    });
    assert!(
        (draft / expected - 1.0).abs() < 0.05,
        "draft {draft} m vs {expected} m (bound 5 %)"
    );
    // Settled heave: over the last 0.5 s the height moves by less than a tenth of the draft.
    assert!(
        z_hi - z_lo < 0.1 * expected,
        "heave range {} m over the last 0.5 s",
        z_hi - z_lo
    );
    assert!(
        tilt < 2f64.to_radians(),
        "the box tilted by {}°",
        tilt.to_degrees()
    );
}
