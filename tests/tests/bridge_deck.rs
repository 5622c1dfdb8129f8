//! Issue 37 item 5: `cases/bridge-deck-solitary` at its CI size. A deck from an STL mesh (a slab
//! on three girders) held fixed with its girders' soffit at the still-water level, struck by a
//! solitary wave (H/d = 0.4) from a Goring piston, run by E-MPS and by ISPH through the real
//! processes. The case's d/16 is halved to d/8, its Δt doubled and its end cut from 1.4 s to
//! 1.15 s (the load passes by 1.1 s); ISPH adds Lind's shifting and its own Δt. Checks: the
//! forces are finite; the deck is unloaded until the wave reaches it and loaded after; each
//! method brings the wave between the times of the solitary and the linear long-wave speeds; the peak uplift against the hydrostatic uplift under
//! the crest. The two methods' peak horizontal forces are reported: they disagree by 1.85. Numbers: docs/notes/case-bridge-deck-solitary.md.

use schemas::validation::{largest, record, Record};
use schemas::wave_motion::GoringSolitary;
use stack_tests::{case_from, coupler_run, csv_header, csv_rows, out_dir, stderr, workspace};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Still-water depth d and wave height H [m] (the case's wave maker).
const DEPTH: f64 = 0.1;
const HEIGHT: f64 = 0.04;
/// Flume width B [m], water density ρ [kg/m³], gravity g [m/s²] (the case's).
const WIDTH: f64 = 0.05;
const RHO: f64 = 1000.0;
const G: f64 = 9.8;
/// The deck (deck_stl.py, placed by case.toml): girders' soffit at the still water, three
/// girders 25 mm wide, the slab's underside 25 mm higher, 200 mm long.
const GIRDER_WIDTHS: f64 = 3.0 * 0.025;
const SLAB_LENGTH: f64 = 0.2;
const GIRDER_DEPTH: f64 = 0.025;
/// The coupling window [s]: one force sample each.
const WINDOW: f64 = 2.5e-3;
/// The running mean the peaks are taken of: 8 windows, 20 ms, against the wave's passage of
/// about 0.3 s; it keeps single-window pressure spikes (E-MPS) out of the peaks.
const MEAN_WINDOWS: usize = 8;

/// Peak uplift over the hydrostatic uplift under the crest (the independent estimate, 1): the
/// band is 1 ± twice E-MPS's measured resolution spread, its peak F_z moving by 37 % from d/8 to
/// d/16 (2.14 → 2.93 N, 29 Nov 2026): [1 − 0.74, 1 + 0.74]. Measured 0.46 (ISPH d/8), 0.77
/// (E-MPS d/8), 0.99 (E-MPS d/16).
const UPLIFT_LOW: f64 = 0.26;
const UPLIFT_HIGH: f64 = 1.74;

/// One run's force history (window end, F_x, F_z) and its gauge half a depth before the deck.
struct Run {
    forces: Vec<(f64, f64, f64)>,
    gauge: Vec<(f64, f64)>,
    seconds: f64,
}

/// The named columns of each row of a CSV file with a header line (NaN for a field that is no
/// number).
fn columns(path: &Path, names: &[&str]) -> Vec<Vec<f64>> {
    let header = csv_header(path);
    let at: Vec<usize> = names
        .iter()
        .map(|n| {
            header
                .iter()
                .position(|h| h == n)
                .unwrap_or_else(|| panic!("{}: no column {n} in {header:?}", path.display()))
        })
        .collect();
    csv_rows(path)
        .iter()
        .map(|row| {
            at.iter()
                .map(|&i| row.get(i).copied().unwrap_or(f64::NAN))
                .collect()
        })
        .collect()
}

/// The case file at d/8 for `method` (`"emps"`, as shipped, or `"isph"` with S2-8's gradient and Lind's shifting, the case's wave setting),
/// written with its mesh into `dir`.
fn ci_twin(dir: &Path, method: &str) -> PathBuf {
    // E-MPS: c Δt/Δs = 0.8 as shipped; ISPH: u_max Δt/Δs = 0.32 (its limit is 0.4).
    let (method, time_step) = match method {
        "emps" => ("\"emps\"", "1.25e-3"),
        _ => (
            "\"isph\"\nisph = { shifting = \"lind\", pressure_gradient = \"corrected-difference\" }",
            "2.5e-3",
        ),
    };
    let case = case_from(
        "bridge-deck-solitary",
        dir,
        &[
            ("method", method),
            ("spacing", "0.0125"),
            ("time_step", time_step),
            ("end_time", "1.15"),
            ("output_interval", "1.15"),
        ],
    );
    let mesh = workspace().join("cases/bridge-deck-solitary/deck.stl");
    std::fs::copy(&mesh, dir.join("deck.stl")).unwrap_or_else(|e| panic!("{}: {e}", mesh.display()));
    case
}

fn run(method: &str) -> Run {
    let dir = out_dir(&format!("bridge-deck-{method}"));
    let case = ci_twin(&dir, method);
    let out = dir.join("out");
    let started = Instant::now();
    let done = coupler_run(&case, &out);
    let seconds = started.elapsed().as_secs_f64();
    assert!(done.status.success(), "{method}: {}", stderr(&done));
    let forces = columns(&out.join("ledger.csv"), &["time", "bridge_fx", "bridge_fz"])
        .into_iter()
        .map(|r| (r[0], r[1], r[2]))
        .collect();
    let gauge = columns(&out.join("flume/flume_probes.csv"), &["time", "gauge-deck"])
        .into_iter()
        .map(|r| (r[0], r[1]))
        .collect();
    let _ = std::fs::remove_dir_all(&dir);
    Run {
        forces,
        gauge,
        seconds,
    }
}

/// The largest running mean over [`MEAN_WINDOWS`] samples.
fn peak_mean(v: &[f64]) -> f64 {
    largest(
        v.windows(MEAN_WINDOWS)
            .map(|w| w.iter().sum::<f64>() / MEAN_WINDOWS as f64),
        f64::NEG_INFINITY,
    )
}

/// What one run shows.
struct Loads {
    arrival: f64,
    crest: f64,
    peak_fx: f64,
    peak_fz: f64,
}

/// Checks one run on its own and returns its peaks.
fn loads(method: &str, r: &Run) -> Loads {
    let expected = (1.15 / WINDOW).round() as usize;
    assert_eq!(r.forces.len(), expected, "{method}: windows in the ledger");
    for &(t, fx, fz) in &r.forces {
        assert!(
            fx.is_finite() && fz.is_finite(),
            "{method}: t = {t}: F = ({fx}, {fz})"
        );
    }
    assert!(r.gauge.iter().all(|g| g.1.is_finite()), "{method}: gauge");
    // The wave reaches the deck: the gauge half a depth before it first reads d + H/4.
    let arrival = r
        .gauge
        .iter()
        .find(|g| g.1 > DEPTH + 0.25 * HEIGHT)
        .map(|g| g.0)
        .unwrap_or_else(|| panic!("{method}: the wave never reaches the deck's gauge"));
    let crest = largest(r.gauge.iter().map(|g| g.1), f64::NEG_INFINITY) - DEPTH;
    let magnitude = |&(_, fx, fz): &(f64, f64, f64)| fx.hypot(fz);
    let peak = largest(r.forces.iter().map(magnitude), 0.0);
    let quiet: Vec<f64> = r
        .forces
        .iter()
        .filter(|f| f.0 < arrival - 0.1)
        .map(magnitude)
        .collect();
    let loaded: Vec<f64> = r
        .forces
        .iter()
        .filter(|f| f.0 >= arrival && f.0 <= arrival + 0.3)
        .map(magnitude)
        .collect();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    let quiet_max = largest(quiet.iter().copied(), 0.0);
    let peak_at = r
        .forces
        .iter()
        .find(|f| magnitude(f) == peak)
        .map(|f| f.0)
        .unwrap_or(f64::NAN);
    let fx: Vec<f64> = r.forces.iter().map(|f| f.1).collect();
    let fz: Vec<f64> = r.forces.iter().map(|f| f.2).collect();
    let (peak_fx, peak_fz) = (peak_mean(&fx), peak_mean(&fz));
    println!(
        "{method}: {:.1} s; wave at the deck t = {arrival:.3} s, crest η = {crest:.4} m; |F| before \
         ≤ {quiet_max:.4} N (mean {:.4}), after mean {:.3} N, peak {peak:.3} N at {peak_at:.3} s; \
         20 ms peaks F_x = {peak_fx:.3} N, F_z = {peak_fz:.3} N",
        r.seconds,
        mean(&quiet),
        mean(&loaded)
    );
    assert!(quiet.len() > 100, "{method}: the wave came at t = {arrival} s");
    // Not loaded before: measured at most 1.3 % (E-MPS) and 0.8 % (ISPH) of the peak at d/8
    // (the note); 5 % is four times that, far below any load the water resting under the
    // girders would put on them if the deck were touched before the wave.
    assert!(
        quiet_max <= 0.05 * peak,
        "{method}: the deck is loaded before the wave: {quiet_max} N against a peak of {peak} N"
    );
    // Loaded after: the mean over the 0.3 s after the arrival is measured at 160 (E-MPS) and
    // 1 500 (ISPH) times the mean before; 20 times asks that the load comes with the wave.
    assert!(
        mean(&loaded) >= 20.0 * mean(&quiet),
        "{method}: no load when the wave arrives"
    );
    // The largest load falls while the wave passes (about 0.3 s), not before it.
    assert!(
        peak_at >= arrival && peak_at <= arrival + 0.4,
        "{method}: the peak at {peak_at} s, the wave at {arrival} s"
    );
    Loads {
        arrival,
        crest,
        peak_fx,
        peak_fz,
    }
}

/// Long-wave hydrostatic uplift under a crest η (pressure ρ g (η − z) below the water line,
/// long-wave theory's hydrostatic pressure): on the girders' soffits at the still water and,
/// when η is above it, on the slab's underside between them, all under the crest at once.
fn hydrostatic_uplift(crest: f64) -> f64 {
    let girders = crest * GIRDER_WIDTHS * WIDTH;
    let slab = (crest - GIRDER_DEPTH).max(0.0) * (SLAB_LENGTH - GIRDER_WIDTHS) * WIDTH;
    RHO * G * (girders + slab)
}

/// The times the front η = H/4 of the first-order solitary wave Goring's paddle makes reaches
/// the deck's gauge, 0.4 m from the paddle's face at rest, travelling at √(g(d + H)) and at
/// √(g d). The paddle's target wave has its crest at x₀ < 0 (behind the paddle) at t = 0 and
/// moves at c = √(g(d + H)); its front, arcosh 2 / k ahead of the crest, leaves the paddle's face
/// at (−x₀ − arcosh 2 / k) / c.
fn arrival_window() -> (f64, f64) {
    let goring = GoringSolitary::new(HEIGHT, DEPTH, G).unwrap_or_else(|e| panic!("{e}"));
    let wave = goring.target_wave();
    let (solitary, linear) = (wave.celerity(), (G * DEPTH).sqrt());
    let leaves = (-wave.crest_x0() - 2.0f64.acosh() / wave.wavenumber()) / solitary;
    let distance = 0.45 - 0.05;
    (leaves + distance / solitary, leaves + distance / linear)
}

#[test]
fn a_solitary_wave_loads_the_held_deck_near_its_hydrostatic_uplift_by_both_methods() {
    let emps_run = run("emps");
    let isph_run = run("isph");
    let emps = loads("E-MPS", &emps_run);
    let isph = loads("ISPH", &isph_run);

    // Each method brings the wave's front (η = H/4) to the deck's gauge between the times of a
    // front travelling from the paddle at the solitary wave's celerity √(g(d + H)) and at the
    // linear long-wave speed √(g d), one probe row (5 ms) either way: slower than the latter is a
    // numerical loss, faster than the former no wave Goring's paddle makes.
    let window = arrival_window();
    for (method, l) in [("E-MPS", &emps), ("ISPH", &isph)] {
        println!(
            "{method}: the front at the deck's gauge at {:.3} s (a wave at √(g(d + H)): {:.3} s, at √(g d): {:.3} s)",
            l.arrival, window.0, window.1
        );
        assert!(
            l.arrival >= window.0 - 0.005 && l.arrival <= window.1 + 0.005,
            "{method}: the front at {} s, outside [{}, {}] s",
            l.arrival,
            window.0,
            window.1
        );
    }

    // Peak horizontal force, E-MPS over ISPH: reported, not bounded. The methods disagree by
    // a factor of 1.85 at d/8 while E-MPS moves by 5.6 % from d/8 to d/16, and ISPH does not
    // run d/16 (docs/notes/case-bridge-deck-solitary.md): no bound from an independent
    // reference or a spread exists yet, and one taken from this ratio would only repeat it.
    let ratio = emps.peak_fx / isph.peak_fx;
    println!(
        "peak F_x: E-MPS {:.3} N, ISPH {:.3} N, ratio {ratio:.2}",
        emps.peak_fx, isph.peak_fx
    );
    record(Record {
        id: "bridge-deck-solitary-peak-fx-emps-over-isph".into(),
        capability: "wave load on a held bridge deck from an STL mesh (E-MPS against ISPH)".into(),
        reference: "the same case run by ISPH (no experiment's numbers found)".into(),
        case: "cases/bridge-deck-solitary at its CI size".into(),
        resolution: "Δs = d/8 = 12.5 mm, window 2.5 ms".into(),
        measure: "peak of the 20 ms mean horizontal force, E-MPS / ISPH".into(),
        value: ratio,
        bound: None,
        bound_source: "not met: the methods disagree (docs/notes/case-bridge-deck-solitary.md)".into(),
        unit: "".into(),
        source: "tests/tests/bridge_deck.rs::a_solitary_wave_loads_the_held_deck_near_its_hydrostatic_uplift_by_both_methods".into(),
        run_time_s: emps_run.seconds + isph_run.seconds,
        ..Default::default()
    });
    assert!(ratio.is_finite() && ratio > 0.0, "peak F_x ratio {ratio}");

    // The independent check: the peak uplift against the hydrostatic uplift under the crest
    // each run's own gauge measured.
    for (method, l) in [("E-MPS", &emps), ("ISPH", &isph)] {
        let estimate = hydrostatic_uplift(l.crest);
        let share = l.peak_fz / estimate;
        println!(
            "{method}: peak F_z {:.3} N, hydrostatic uplift under η = {:.4} m {estimate:.3} N, ratio {share:.2}",
            l.peak_fz, l.crest
        );
        assert!(
            (UPLIFT_LOW..=UPLIFT_HIGH).contains(&share),
            "{method}: peak uplift {} N is {share} of the hydrostatic {estimate} N",
            l.peak_fz
        );
    }
}
