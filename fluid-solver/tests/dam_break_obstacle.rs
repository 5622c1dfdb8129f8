//! The CI twin of `cases/dam-break-obstacle` (Δs = 0.04 m, 0.8 s): a dam break against a box
//! with an open top, sensors and gauges runs to its end from its case file, with no workaround,
//! and its probes read a plausible history: the front runs towards −x no faster than the
//! shallow-water (Ritter) front 2√(g H), the water reaches the box, and the sensor on the box's
//! face low down (P1) is dry before and loaded after. Then against the experiment
//! (`cases/dam-break-obstacle/experiment.csv`, Kleefsman et al. 2005): the water reaches the
//! gauges H3 and H2 when it did there, and P1's mean load after the impact is the measured one.
//! The same twin with `method = "isph"` (the case's one key) passes the same checks, and the
//! box's face towards the water is pressed, not pulled, where the water runs up it.

use schemas::case::fluid::{FluidMethodName, IsphConfig, PressureGradient, Shifting};
use schemas::case::Case;
use schemas::validation::{record, Record};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[test]
fn the_ci_twin_runs_to_its_end_with_sensors_and_gauges() {
    let _ = run_twin(FluidMethodName::Emps);
}

/// ISPH on the same twin (issue 12): the E-MPS test's checks, and every sensor on the box's face
/// towards the water (P1 … P4, 0.021 … 0.141 m up) reads a positive mean over 0.45 – 0.8 s, as
/// in the experiment (3.2 – 6.3 kPa over 0.45 – 0.6 and 0.6 – 0.8 s). Before the faces' normals at
/// convex edges (`fluid_solver::isph::walls`), P4, 2 cm below the box's top edge, read −1.9 and
/// −2.3 kPa there: the edge's mean normal made water running up the face read as leaving it,
/// and the wall pulled it back.
#[test]
fn the_ci_twin_runs_with_isph_and_the_box_face_is_pressed_where_the_water_runs_up() {
    let (header, rows) = run_twin(FluidMethodName::Isph);
    assert_the_face_is_pressed("ISPH", &header, &rows);
}

/// The same with `pressure_gradient = "symmetric"` (at 2.0 Δs) and shifting: the walls' convex
/// edges take the faces' normals with that gradient too (`fluid_solver::isph::walls`). With the
/// walls' own normals P4 read −2.4 / −2.2 kPa over 0.45–0.6 / 0.6–0.8 s (−169 % of the
/// experiment's mean over 0.6–0.8 s); with the faces' normals +1.2 / +2.4 kPa, and P1 … P4
/// +4.9 / −7.5 / −23.3 / −22.9 % of the experiment's means over 0.6–0.8 s. Only the face is checked: H3 wets 32 ms late with this option (the E-MPS
/// test's tolerance is 30 ms; README, session 18). A non-default setting: run with `--ignored`
/// (35 s of CI's 2 cores; the default ISPH's twin above checks the same face).
#[test]
#[ignore = "non-default ISPH setting (35 s on 2 cores); run with --ignored"]
fn the_ci_twin_with_the_symmetric_isph_gradient_presses_the_box_face() {
    let settings = IsphConfig {
        influence_radius: Some(2.0),
        pressure_gradient: PressureGradient::Symmetric,
        shifting: Shifting::Lind,
        ..IsphConfig::default()
    };
    let (header, rows, out, _) = twin_table(FluidMethodName::Isph, Some(settings));
    let _ = std::fs::remove_dir_all(&out);
    assert_the_face_is_pressed("ISPH symmetric + shifting", &header, &rows);
}

/// Every sensor on the box's face towards the water (P1 … P4) reads a positive mean over 0.45 –
/// 0.6 s and over 0.6 – 0.8 s, as in the experiment.
fn assert_the_face_is_pressed(label: &str, header: &[String], rows: &[Vec<f64>]) {
    let t = column(header, "time");
    for sensor in ["P1", "P2", "P3", "P4"] {
        let c = column(header, sensor);
        let (early, late) = (mean_over(rows, t, c, 0.45, 0.6), mean_over(rows, t, c, 0.6, 0.8));
        println!("{label} {sensor}: mean {early:.0} Pa over 0.45–0.6 s, {late:.0} Pa over 0.6–0.8 s");
        assert!(
            early > 0.0 && late > 0.0,
            "{label}: {sensor} is pulled: mean {early:.0} / {late:.0} Pa over 0.45–0.6 / 0.6–0.8 s (experiment: pressed)"
        );
    }
}

/// Runs the CI twin with `method` (and ISPH `settings`, or the default) to its end; returns the
/// probe table, the output folder and the run's wall time [s].
fn twin_table(
    method: FluidMethodName,
    settings: Option<IsphConfig>,
) -> (Vec<String>, Vec<Vec<f64>>, PathBuf, f64) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../cases/dam-break-obstacle/case-ci.toml");
    let mut case = Case::load(&path).unwrap_or_else(|e| panic!("{e}"));
    for (name, cfg) in case.fluid.iter_mut() {
        cfg.method = method;
        if settings.is_some() {
            cfg.isph = settings;
        }
        cfg.validate(&format!("fluid.{name}"))
            .unwrap_or_else(|e| panic!("{e:?}"));
    }
    let form = settings.map(|s| s.pressure_gradient);
    let out = std::env::temp_dir().join(format!(
        "dam-break-obstacle-ci-{method:?}-{form:?}-{}",
        std::process::id()
    ));
    let started = Instant::now();
    let summary = fluid_solver::run::run_case(&case, &out, false).unwrap_or_else(|e| panic!("{e}"));
    let run_time_s = started.elapsed().as_secs_f64();
    println!("{summary}");
    assert!((summary.time - case.info.end_time).abs() < 1e-9);
    let (header, rows) = table(&out.join("tank_probes.csv"));
    (header, rows, out, run_time_s)
}

/// Runs the CI twin with `method` and checks what both methods must give (module doc); returns
/// the probe table.
fn run_twin(method: FluidMethodName) -> (Vec<String>, Vec<Vec<f64>>) {
    let (header, rows, out, run_time_s) = twin_table(method, None);
    let col = |name: &str| column(&header, name);
    let (t, front, p1, h4) = (col("time"), col("front"), col("P1"), col("H4"));
    let (ds, g, h0): (f64, f64, f64) = (0.04, 9.8, 0.55);
    let ritter = 2.0 * (g * h0).sqrt();
    let column_face = 3.22 - 1.992;
    let box_face = 3.22 - 0.8245;
    for r in &rows {
        assert!(
            r[front] <= column_face + ritter * r[t] + 2.0 * ds,
            "at t = {} s the front is at {} m, beyond the Ritter front {} m",
            r[t],
            r[front],
            column_face + ritter * r[t]
        );
    }
    let arrival = rows.iter().find(|r| r[front] >= box_face).map(|r| r[t]);
    println!(
        "front reaches the box's face at {arrival:?} s (Ritter: {:.3} s)",
        (box_face - column_face) / ritter
    );
    let arrival = arrival.unwrap_or_else(|| panic!("the water never reached the box"));
    let before = rows
        .iter()
        .filter(|r| r[t] < arrival - 0.05)
        .map(|r| r[p1].abs())
        .fold(0.0, schemas::validation::max_or_nan);
    let peak = rows
        .iter()
        .map(|r| r[p1])
        .fold(0.0, schemas::validation::max_or_nan);
    println!(
        "P1: {before:.1} Pa before the water arrives, peak {peak:.0} Pa; H4 from {:.3} to {:.3} m",
        rows[0][h4],
        rows[rows.len() - 1][h4]
    );
    assert!(before < 1.0, "P1 reads {before} Pa while dry");
    assert!(peak > 1000.0 * g * 0.04, "P1 must feel the surge: peak {peak} Pa");
    assert!(
        rows[rows.len() - 1][h4] < rows[0][h4] - 0.1,
        "the reservoir empties at H4"
    );
    // Pressure noise (issue 15: reported, not bounded): RMS of the step-to-step change of the
    // unfiltered sensor (one row per step) over the 0.3 s after the water arrives.
    let raw = col("P1-raw");
    let after: Vec<f64> = rows
        .iter()
        .filter(|r| r[t] >= arrival && r[t] <= arrival + 0.3)
        .map(|r| r[raw])
        .collect();
    let steps = after.len().saturating_sub(1).max(1) as f64;
    let rms = (after.windows(2).map(|w| (w[1] - w[0]).powi(2)).sum::<f64>() / steps).sqrt();
    let raw_peak = after.iter().copied().fold(0.0, schemas::validation::max_or_nan);
    println!(
        "P1-raw: step-to-step RMS change {rms:.0} Pa over {} steps after arrival, raw peak {raw_peak:.0} Pa (5 ms filter: {peak:.0} Pa)",
        after.len()
    );
    against_the_experiment(&rows, &col, ds, twin_record(method, run_time_s));
    let _ = std::fs::remove_dir_all(&out);
    (header, rows)
}

/// A CSV file's header and rows of numbers (lines starting with `#` are comments).
fn table(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header = lines
        .next()
        .unwrap_or_default()
        .split(',')
        .map(String::from)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap_or(f64::NAN)).collect())
        .collect();
    (header, rows)
}

/// The index of column `name` in `header`.
fn column(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"))
}

/// First time a column passes `level`.
fn first_above(rows: &[Vec<f64>], t: usize, c: usize, level: f64) -> Option<f64> {
    rows.iter().find(|r| r[c] > level).map(|r| r[t])
}

/// Mean of a column over [a, b].
fn mean_over(rows: &[Vec<f64>], t: usize, c: usize, a: f64, b: f64) -> f64 {
    let v: Vec<f64> = rows
        .iter()
        .filter(|r| r[t] >= a && r[t] <= b)
        .map(|r| r[c])
        .collect();
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

/// The experiment's pressure as the case's sensor reads it: the mean of the last 5 ms
/// (`window = 0.005`), at the experiment's own samples.
fn filtered(rows: &[Vec<f64>], t: usize, c: usize, window: f64) -> Vec<Vec<f64>> {
    rows.iter()
        .enumerate()
        .map(|(i, r)| {
            let past: Vec<f64> = rows[..=i]
                .iter()
                .rev()
                .take_while(|q| q[t] > r[t] - window)
                .map(|q| q[c])
                .collect();
            vec![r[t], past.iter().sum::<f64>() / past.len() as f64]
        })
        .collect()
}

/// What the records of `against_the_experiment` share for `method`: the scene, the run (of
/// `run_time_s`) and its test; and the method's id tag and name.
fn twin_record(method: FluidMethodName, run_time_s: f64) -> (Record, &'static str, &'static str) {
    let (tag, name, test) = match method {
        FluidMethodName::Isph => (
            "isph",
            "ISPH",
            "the_ci_twin_runs_with_isph_and_the_box_face_is_pressed_where_the_water_runs_up",
        ),
        _ => (
            "emps",
            "E-MPS",
            "the_ci_twin_runs_to_its_end_with_sensors_and_gauges",
        ),
    };
    let row = Record {
        reference: "MARIN experiment (Kleefsman et al. 2005, SPHERIC test 2), cases/dam-break-obstacle/experiment.csv"
            .into(),
        case: "cases/dam-break-obstacle/case-ci.toml: dam break against a box, 0 … 0.8 s".into(),
        resolution: format!("{name}, Δs = 0.04 m"),
        source: format!("fluid-solver/tests/dam_break_obstacle.rs::{test}"),
        run_time_s,
        ..Default::default()
    };
    (row, tag, name)
}

fn against_the_experiment(
    rows: &[Vec<f64>],
    col: &dyn Fn(&str) -> usize,
    ds: f64,
    (row, tag, name): (Record, &str, &str),
) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../cases/dam-break-obstacle/experiment.csv");
    let (header, exp) = table(&path);
    let ecol = |name: &str| column(&header, name);
    let (t, et) = (col("time"), ecol("time"));
    // Wetting: the first time a gauge reads more than 2 cm. Tolerance: two spacings of travel at
    // the experiment's mean front speed to H2 (1.0 m in 0.368 s, 2.7 m/s): at Δs = 0.04 m, 30 ms
    // — the front is resolved to a particle layer, and the lattice moves the column's face by 8 mm
    // and its top by 1 cm (the run's notes).
    let tolerance = 2.0 * ds / 2.7;
    for gauge in ["H3", "H2"] {
        let measured = first_above(&exp, et, ecol(gauge), 0.02).unwrap_or(f64::NAN);
        let computed = first_above(rows, t, col(gauge), 0.02).unwrap_or(f64::NAN);
        println!("{gauge} wets at {computed:.3} s, in the experiment at {measured:.3} s");
        record(Record {
            id: format!("{tag}-marin-ci-{}-wetting", gauge.to_lowercase()),
            capability: format!("{name} dam-break front against a box: gauge {gauge} wets"),
            measure: format!("|time {gauge} first reads > 2 cm − the experiment's|"),
            value: (computed - measured).abs(),
            bound: Some(tolerance),
            bound_source: "two spacings of travel at the experiment's mean front speed to H2 (2.7 m/s)"
                .into(),
            unit: "s".into(),
            ..row.clone()
        });
        assert!(
            (computed - measured).abs() <= tolerance,
            "{gauge} wets at {computed:.3} s, the experiment at {measured:.3} s (tolerance {tolerance:.3} s)"
        );
    }
    // P1 after the impact (0.6 … 0.8 s, the run-up on the face that follows the first peak): the
    // mean of the 5 ms-filtered sensor against the experiment filtered the same way. Measured on
    // the full case to 4 s (README): +1.6 % at Δs = 0.04 m, +12 % at 0.02 m; tolerance 20 %,
    // twice the change between the two spacings.
    let exp_p1 = filtered(&exp, et, ecol("P1"), 0.005);
    let measured = mean_over(&exp_p1, 0, 1, 0.6, 0.8);
    let computed = mean_over(rows, t, col("P1"), 0.6, 0.8);
    let peak_exp = exp_p1
        .iter()
        .filter(|r| r[0] < 0.8)
        .map(|r| r[1])
        .fold(0.0, schemas::validation::max_or_nan);
    let peak = rows
        .iter()
        .map(|r| r[col("P1")])
        .fold(0.0, schemas::validation::max_or_nan);
    println!(
        "P1, mean over 0.6–0.8 s: {computed:.0} Pa, experiment {measured:.0} Pa ({:+.1} %); 5 ms peak {peak:.0} Pa, experiment {peak_exp:.0} Pa (not bounded: E-MPS impact peaks run high)",
        100.0 * (computed / measured - 1.0)
    );
    record(Record {
        id: format!("{tag}-marin-ci-p1-slow-load"),
        capability: format!("{name} pressure on a box after the impact: sensor P1"),
        measure: "mean of the 5 ms-filtered P1 over 0.6 … 0.8 s / the experiment's, filtered alike − 1"
            .into(),
        value: 100.0 * (computed / measured - 1.0),
        bound: Some(20.0),
        bound_source: "twice the change between Δs = 0.04 and 0.02 m on the full case (+1.6 %, +12 %)".into(),
        unit: "%".into(),
        ..row.clone()
    });
    record(Record {
        id: format!("{tag}-marin-ci-p1-peak"),
        capability: format!("{name} impact pressure on a box: sensor P1's peak"),
        measure: "largest 5 ms-filtered P1 before 0.8 s / the experiment's, filtered alike".into(),
        value: peak / peak_exp,
        bound: None,
        bound_source: "E-MPS impact peaks run high (cases/dam-break-obstacle/README.md)".into(),
        ..row
    });
    assert!(
        (computed / measured - 1.0).abs() <= 0.2,
        "P1's mean over 0.6–0.8 s is {computed:.0} Pa, the experiment's {measured:.0} Pa (tolerance 20 %)"
    );
}
