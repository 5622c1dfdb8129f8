//! Inflow and outflow boundaries (`open_boundary`): the particle balance closes exactly, the
//! inflow feeds u_in × area, the boundaries' state is saved and restored with the particles, the
//! bridge-washout cases build and run, and bad boundary keys are refused naming the key.

use fluid_solver::open_boundary::ParticleBalance;
use fluid_solver::particles::Particles;
use fluid_solver::state::FluidState;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::FluidMethodName;
use schemas::case::{Case, FluidConfig};
use schemas::validation::{record, Record};
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// A dry channel 3.0 × 0.5 × 0.6 m (Δs = 5 cm): a 0.5 m strip feeds u_in = 1 m/s up to a level of
/// 0.3 m (from 0.1 m, reached at 0.4 s); water leaves behind x = 2.5 m.
const CHANNEL: &str = r#"
[case]
name = "channel"
end_time = 2.0

[fluid.river]
spacing = 0.05
time_step = 2.0e-3
viscosity_term = false
output_interval = 0.1
tank = { min = [0.0, 0.0, 0.0], max = [3.0, 0.5, 0.6] }

[fluid.river.inflow]
plane = 0.5
velocity = 1.0
strip_length = 0.5
level = 0.3
initial_level = 0.1
rise_time = 0.4

[fluid.river.outflow]
plane = 2.5
"#;

const SPACING: f64 = 0.05;
const PLANE: f64 = 0.5;
const U_IN: f64 = 1.0;
/// u_in × level × width of the channel [m³/s].
const INFLOW_RATE: f64 = 1.0 * 0.3 * 0.5;

fn parse(text: &str) -> Result<Case, String> {
    Case::parse(Path::new("cases/channel/case.toml"), text.to_string()).map_err(|e| e.to_string())
}

fn channel() -> FluidConfig {
    let case = parse(CHANNEL).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["river"].clone()
}

fn error_of(text: &str) -> String {
    match parse(text) {
        Ok(_) => panic!("the case should have been refused:\n{text}"),
        Err(e) => {
            println!("{e}");
            e
        }
    }
}

/// Counts of (all, fluid, inflow) particles.
fn counts(s: &FluidSolver) -> (i64, i64, i64) {
    let p = s.particles();
    (
        p.len() as i64,
        p.count(Kind::Fluid) as i64,
        p.count(Kind::Inflow) as i64,
    )
}

/// One run of the channel to `end` and what the tests read from it: every 0.05 s the particle
/// balance is checked (every particle added or removed counted once, ids unique, no fluid
/// behind the outflow plane); from 1.0 s on, the velocity flux just inside the inflow plane is
/// sampled after every step; the state at 1.2 s and the particles and balance at 1.4 s are kept.
struct ChannelRun {
    solver: FluidSolver,
    balance: ParticleBalance,
    count_changed: bool,
    /// Rates over [1, end] s: particles entering through the plane, and the velocity flux just
    /// inside it [m³/s] (when `end` > 1 s).
    counted: f64,
    carried: f64,
    at_1_2: Option<FluidState>,
    at_1_4: Option<(Particles, ParticleBalance)>,
    run_time_s: f64,
}

/// The E-MPS channel to 2 s, run once for the tests that read it.
fn emps_channel() -> &'static ChannelRun {
    static RUN: OnceLock<ChannelRun> = OnceLock::new();
    RUN.get_or_init(|| channel_run(&channel(), 2.0))
}

/// When the water just inside the plane has stopped slowing down (the level is at its maximum
/// from 0.4 s; the water decelerates while the flow downstream builds up, until 0.9 s): the
/// rates are measured from here, over whole layers of strip travel.
const RATE_FROM: f64 = 1.0;

/// Runs `cfg` (the channel) to `end` in 0.05 s stretches; see [`ChannelRun`].
fn channel_run(cfg: &FluidConfig, end: f64) -> ChannelRun {
    let started = std::time::Instant::now();
    let mut s = FluidSolver::new(cfg);
    let m = s.particle_mass();
    let (n0, f0, i0) = counts(&s);
    assert_eq!(
        (f0, i0),
        (0, 10 * 10 * 2),
        "the initial strip: 10 layers × 10 sites × 2 rows"
    );
    let volume = SPACING.powi(3);
    // Velocity flux just inside the plane: Σ u_x Δs³ / δ over the water in [x_in, x_in + δ],
    // i.e. what the water really carries (it may be squeezed or stretched by the pressure).
    // Strip particles that crossed the plane in the last step count too: they turn into fluid
    // at the start of the next one.
    let slab = 2.0 * SPACING;
    let (mut flux_sum, mut samples, mut entered0) = (0.0, 0, 0);
    let (mut count_changed, mut at_1_2, mut at_1_4) = (false, None, None);
    let stretches = (end / 0.05).round() as usize;
    for k in 1..=stretches {
        let target = (k as f64 * 0.05).min(end);
        while let Some(dt) = s.next_step_towards(target) {
            s.step(dt).unwrap_or_else(|e| panic!("{e}"));
            if s.time() > RATE_FROM + 1e-9 {
                let p = s.particles();
                let q: f64 = (0..p.len())
                    .filter(|&k| p.kind[k] == Kind::Fluid.code() || p.kind[k] == Kind::Inflow.code())
                    .filter(|&k| p.x[k] >= PLANE && p.x[k] < PLANE + slab)
                    .map(|k| p.vx[k])
                    .sum::<f64>()
                    * volume
                    / slab;
                flux_sum += q;
                samples += 1;
            }
        }
        s.land_on(target);
        let b = s.open_boundaries().balance();
        let (n, f, i) = counts(&s);
        let (ins, ent, rem) = (b.inserted as i64, b.entered as i64, b.removed as i64);
        // Exact: every particle added or removed is counted once.
        assert_eq!(n - n0, ins - rem, "t = {}: all particles vs {b:?}", s.time());
        assert_eq!(f - f0, ent - rem, "t = {}: fluid vs {b:?}", s.time());
        assert_eq!(i - i0, ins - ent, "t = {}: strip vs {b:?}", s.time());
        // Mass inside = mass in − mass out (each particle carries ρ0 Δs³).
        let inside = f as f64 * m;
        assert_eq!(inside, (f0 + ent - rem) as f64 * m);
        let p = s.particles();
        let ids: HashSet<u32> = p.id.iter().copied().collect();
        assert_eq!(
            ids.len(),
            p.len(),
            "t = {}: particle ids are not unique",
            s.time()
        );
        assert!(
            (0..p.len()).all(|k| p.kind[k] != Kind::Fluid.code() || p.x[k] <= 2.5 + 0.5 * SPACING),
            "fluid left behind the outflow plane"
        );
        count_changed |= n != n0;
        match k {
            20 => entered0 = b.entered,
            24 => at_1_2 = Some(s.save_state()),
            28 => at_1_4 = Some((s.particles().clone(), b)),
            _ => {}
        }
    }
    let balance = s.open_boundaries().balance();
    println!("{balance:?}, fluid mass {:.3} kg", counts(&s).1 as f64 * m);
    let counted = (balance.entered - entered0) as f64 * volume / (s.time() - RATE_FROM);
    ChannelRun {
        solver: s,
        balance,
        count_changed,
        counted,
        carried: flux_sum / samples.max(1) as f64,
        at_1_2,
        at_1_4,
        run_time_s: started.elapsed().as_secs_f64(),
    }
}

#[test]
fn particle_balance_closes_exactly_and_ids_stay_unique() {
    let run = emps_channel();
    let b = run.balance;
    assert!(
        run.count_changed && b.removed > 0 && b.entered > b.removed,
        "{b:?}"
    );
}

/// CI twin of [`inflow_rate_matches_u_in_times_area_with_isph`]: the channel with ISPH for
/// 0.3 s, its particle balance exact every 0.05 s and water entering through the plane.
#[test]
fn particle_balance_closes_exactly_with_isph() {
    let run = channel_run(&isph_channel(), 0.3);
    let b = run.balance;
    assert!(run.count_changed && b.entered > 0, "{b:?}");
}

#[test]
fn inflow_rate_matches_u_in_times_area() {
    inflow_rate_of(&channel(), emps_channel(), 2.0);
}

/// The channel with ISPH (issue 12: inflow and outflow with either method): the same rate
/// within the same 2 %, measured over [1.0, 1.5] s (10 spacings of strip travel), and the
/// particle balance exact (fluid thrown over the channel's open top counted too). Measured
/// 30 Nov 2026: 0.15000 m³/s through the plane, the carried flux within 0.044 % of it (−0.5 %
/// before the ISPH wall and step changes of sessions 25–33); about 15–40 s in release, so
/// ignored in CI; its twin is [`particle_balance_closes_exactly_with_isph`].
#[test]
#[ignore]
fn inflow_rate_matches_u_in_times_area_with_isph() {
    let cfg = isph_channel();
    let n0 = FluidSolver::new(&cfg).particles().len() as i64;
    let run = channel_run(&cfg, 1.5);
    inflow_rate_of(&cfg, &run, 1.5);
    let s = &run.solver;
    let b = s.open_boundaries().balance();
    let (n, f, i) = counts(s);
    let (ins, ent) = (b.inserted as i64, b.entered as i64);
    let rem = s.removed() as i64;
    println!("{b:?}, {} over the open top", s.escaped());
    assert_eq!((n, f, i), (n0 + ins - rem, ent - rem, 200 + ins - ent), "{b:?}");
    assert!(b.removed > 0, "water reached the outflow: {b:?}");
}

/// The channel with the ISPH method.
fn isph_channel() -> FluidConfig {
    let mut cfg = channel();
    cfg.method = schemas::case::fluid::FluidMethodName::Isph;
    cfg.isph = Some(schemas::case::fluid::IsphConfig::default());
    cfg.sound_speed = None;
    cfg.validate("fluid.river").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}

/// Checks the inflow rates of `run` (the channel with `cfg`, to `end`) over [1, end] s against
/// u_in × area, and records them.
fn inflow_rate_of(cfg: &FluidConfig, run: &ChannelRun, end: f64) {
    let (counted, carried) = (run.counted, run.carried);
    println!(
        "u_in A = {INFLOW_RATE:.5} m³/s; particles through the plane {counted:.5} m³/s; velocity flux inside the plane {carried:.5} m³/s"
    );
    // Tolerance 2 %: the issue's requirement for the inflow rate.
    let (method, name, test) = match cfg.method {
        FluidMethodName::Isph => ("isph", "ISPH", "inflow_rate_matches_u_in_times_area_with_isph"),
        _ => ("emps", "E-MPS", "inflow_rate_matches_u_in_times_area"),
    };
    for (what, q) in [("counted", counted), ("carried", carried)] {
        let err = (q - INFLOW_RATE).abs() / INFLOW_RATE;
        record(Record {
            id: format!("open-boundary-{method}-inflow-{what}"),
            capability: format!("{name} inflow plane"),
            reference: "u_in × level × width (the inflow's prescribed rate)".into(),
            case: "a dry channel 3.0 × 0.5 × 0.6 m fed at u_in = 1 m/s up to 0.3 m, outflow behind x = 2.5 m"
                .into(),
            resolution: format!("{name}, Δs = 0.05 m"),
            measure: match what {
                "counted" => {
                    format!("|rate of particles entering through the plane / (u_in A) − 1| over [1, {end}] s")
                }
                _ => format!("|velocity flux just inside the plane / (u_in A) − 1| over [1, {end}] s"),
            },
            value: 100.0 * err,
            bound: Some(2.0),
            bound_source: "the issue's requirement for the inflow rate".into(),
            unit: "%".into(),
            source: format!("fluid-solver/tests/inflow_outflow.rs::{test}"),
            run_time_s: run.run_time_s,
            ..Default::default()
        });
        assert!(
            err < 0.02,
            "{what} inflow rate {q} vs u_in A = {INFLOW_RATE}: {:.2} %",
            100.0 * err
        );
    }
    assert_eq!(Some(U_IN), cfg.inflow.as_ref().and_then(|i| i.velocity));
}

/// A window repeated from a saved state (as implicit coupling repeats one): the channel's state
/// at 1.2 s restored and run to 1.4 s again in the same stretches gives the same particles and
/// balance, with particles removed in the window.
#[test]
fn restore_puts_the_boundaries_back_with_the_particles() {
    let run = emps_channel();
    let (Some(saved), Some((first, b1))) = (&run.at_1_2, &run.at_1_4) else {
        panic!("the shared run keeps its states at 1.2 and 1.4 s");
    };
    let mut s = FluidSolver::new(&channel());
    s.restore_state(saved);
    for k in 25..=28 {
        s.advance_to(k as f64 * 0.05).unwrap_or_else(|e| panic!("{e}"));
    }
    assert_eq!(s.open_boundaries().balance(), *b1);
    assert!(
        s.particles() == first,
        "a repeated window must give the same particles"
    );
    assert!(b1.removed > 0, "the window should have removed particles: {b1:?}");
}

#[test]
fn sound_speed_defaults_to_s1_16_with_the_inflow_speed() {
    // S1-16 with u_max = √(u_in² + 2gH): Table II's u_in = 10 m/s, H = 20 m give 110.9 m/s
    // (the table's value, given to 0.1 m/s).
    let mut cfg = channel();
    if let Some(i) = cfg.inflow.as_mut() {
        (i.velocity, i.level) = (Some(10.0), Some(20.0));
    }
    assert!(
        (cfg.sound_speed() - 110.9).abs() < 0.05,
        "c = {}",
        cfg.sound_speed()
    );
}

#[test]
fn bad_boundaries_are_refused_naming_the_key() {
    let cases = [
        // The plane outside the domain, or too close to the tank's start for the strip.
        (
            "plane = 0.5",
            "plane = 3.5",
            "`fluid.river.inflow.plane`",
            "outside the domain",
        ),
        (
            "plane = 0.5",
            "plane = 0.3",
            "`fluid.river.inflow.plane`",
            "outside the domain",
        ),
        (
            "velocity = 1.0",
            "velocity = 0.0",
            "`fluid.river.inflow.velocity`",
            "> 0",
        ),
        (
            "velocity = 1.0",
            "velocity = -1.0",
            "`fluid.river.inflow.velocity`",
            "> 0",
        ),
        (
            "level = 0.3",
            "level = 0.8",
            "`fluid.river.inflow.level`",
            "above the domain",
        ),
        (
            "strip_length = 0.5",
            "strip_length = 0.1",
            "`fluid.river.inflow.strip_length`",
            "at least",
        ),
        (
            "plane = 2.5",
            "plane = 3.0",
            "`fluid.river.outflow.plane`",
            "outside the domain",
        ),
        (
            "plane = 2.5",
            "plane = 0.4",
            "`fluid.river.outflow.plane`",
            "after the inflow plane",
        ),
    ];
    for (from, to, key, what) in cases {
        let text = if key.contains("outflow") {
            let (head, tail) = CHANNEL.split_at(CHANNEL.find("[fluid.river.outflow]").unwrap_or(0));
            format!("{head}{}", tail.replace(from, to))
        } else {
            CHANNEL.replacen(from, to, 1)
        };
        let e = error_of(&text);
        assert!(
            e.contains("cases/channel/case.toml") && e.contains(key) && e.contains(what),
            "{to}: {e}"
        );
    }
    let block = "[[fluid.river.block]]\nmin = [0.2, 0.0, 0.0]\nmax = [0.4, 0.5, 0.1]\n";
    let e = error_of(&format!("{CHANNEL}{block}"));
    assert!(
        e.contains("`fluid.river.inflow`") && e.contains("overlaps `fluid.river.block[0]`"),
        "{e}"
    );
    let e = error_of(&CHANNEL.replace("[fluid.river.inflow]", "[fluid.river.inflow]\nspeed = 1.0"));
    assert!(e.contains("speed"), "{e}");
}

fn case_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../cases")
        .join(name)
        .join("case.toml")
}

/// Particles of (deck, walls, fluid, strip) of a case's single fluid section.
fn layout_counts(case: &Case) -> (FluidSolver, [usize; 4]) {
    let cfg = case
        .fluid
        .values()
        .next()
        .unwrap_or_else(|| panic!("no fluid section"));
    let s = FluidSolver::new(cfg);
    let p = s.particles();
    let c = [
        p.count(Kind::Body),
        p.count(Kind::Wall) + p.count(Kind::Dummy),
        p.count(Kind::Fluid),
        p.count(Kind::Inflow),
    ];
    (s, c)
}

#[test]
fn bridge_washout_builds_with_the_papers_deck() {
    let case = Case::load(&case_path("bridge-washout")).unwrap_or_else(|e| panic!("{e}"));
    let cfg = &case.fluid["river"];
    let steps = case.info.end_time / cfg.time_step;
    assert!(
        (steps - 1000.0).abs() < 1e-6,
        "Table II: 1 000 steps, got {steps}"
    );
    let (_, [deck, walls, fluid, strip]) = layout_counts(&case);
    println!("bridge-washout at t = 0: deck {deck}, walls/levees/piers/bed {walls}, fluid {fluid}, inflow strip {strip}");
    // Seed 000 §IV-B: superstructure 3 380 particles.
    assert_eq!(deck, 3380);
}

#[test]
fn bridge_washout_small_runs_with_a_closing_balance() {
    let case = Case::load(&case_path("bridge-washout-small")).unwrap_or_else(|e| panic!("{e}"));
    let (mut s, [deck, walls, fluid, strip]) = layout_counts(&case);
    println!("bridge-washout-small at t = 0: deck {deck}, walls {walls}, fluid {fluid}, strip {strip}");
    let (n0, f0, _) = counts(&s);
    // Fluid-only run of the coupled case's fluid section: the deck is held in place.
    let end = case.info.end_time;
    s.advance_to(end).unwrap_or_else(|e| panic!("{e}"));
    let b = s.open_boundaries().balance();
    let (n, f, _) = counts(&s);
    println!("t = {end} s after {} steps: {b:?}, fluid {f}", s.steps());
    assert_eq!(n - n0, b.inserted as i64 - b.removed as i64);
    assert_eq!(f - f0, b.entered as i64 - b.removed as i64);
    assert!(b.entered > 0 && b.removed > 0, "{b:?}");
    // The surge must reach the deck: water above the deck's underside upstream of it.
    let p = s.particles();
    let wet = (0..p.len()).any(|k| p.kind[k] == Kind::Fluid.code() && p.z[k] > 12.0 && p.x[k] > 80.0);
    assert!(wet, "the tsunami did not reach the deck's height");
}

#[test]
fn standalone_run_writes_the_balance_csv() {
    let case = parse(&CHANNEL.replace("end_time = 2.0", "end_time = 0.3")).unwrap_or_else(|e| panic!("{e}"));
    let out =
        PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("inflow-balance-{}", std::process::id()));
    fluid_solver::run::run_case(&case, &out, false).unwrap_or_else(|e| panic!("{e}"));
    let csv = std::fs::read_to_string(out.join("river_balance.csv")).unwrap_or_else(|e| panic!("{e}"));
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap_or(f64::NAN)).collect())
        .collect();
    assert!(
        csv.starts_with("time,inserted,entered,removed,withdrawn,inflow,fluid,total,fluid_mass"),
        "{csv}"
    );
    assert_eq!(rows.len(), 4, "rows at t = 0, 0.1, 0.2, 0.3 s:\n{csv}");
    let (first, last) = (&rows[0], &rows[3]);
    assert_eq!(last[0], 0.3);
    // Δ total = inserted − removed − withdrawn (none: the level only rises); Δ fluid = entered − removed.
    assert_eq!(last[4], 0.0, "{csv}");
    assert_eq!(last[7] - first[7], last[1] - last[3] - last[4], "{csv}");
    assert_eq!(last[6] - first[6], last[2] - last[3], "{csv}");
    assert!(last[2] > 0.0, "{csv}");
}

/// Rows `t, level, velocity` of the surge of [`a_series_drives_the_strip_up_and_down`]: the level
/// rises from 0.1 to 0.32 m over 0.4 s while u rises from 1.0 to 1.5 m/s, holds while u falls to
/// 1.0 m/s, falls back to 0.1 m by 1.2 s while u falls to 0.5 m/s, and holds after the last row.
/// Row times are whole steps (Δt = 2 ms); the crossings of h through (k + ½) Δs are not.
const SURGE: [[f64; 3]; 4] = [
    [0.0, 0.1, 1.0],
    [0.4, 0.32, 1.5],
    [0.8, 0.32, 1.0],
    [1.2, 0.1, 0.5],
];

/// Writes `text` to a new file `name` under the target's temporary folder; returns its path.
fn series_file(name: &str, text: &str) -> PathBuf {
    let dir =
        PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("inflow-series-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
    path
}

/// The channel with its inflow driven by the series file `path` (its velocity and level keys
/// replaced by `series`).
fn series_channel(path: &Path) -> String {
    CHANNEL.replace("velocity = 1.0\n", "").replace(
        "level = 0.3\ninitial_level = 0.1\nrise_time = 0.4\n",
        &format!("series = \"{}\"\n", path.display()),
    )
}

/// Column `c` (1: h, 2: u) of [`SURGE`] at `t`: linear between rows, held after the last.
fn surge(t: f64, c: usize) -> f64 {
    let j = SURGE.iter().rposition(|r| r[0] <= t).unwrap_or(0);
    match SURGE.get(j + 1) {
        Some(next) => {
            let w = (t - SURGE[j][0]) / (next[0] - SURGE[j][0]);
            SURGE[j][c] + w * (next[c] - SURGE[j][c])
        }
        None => SURGE[j][c],
    }
}

/// Exact integrals of the surge over [0, T], per unit width: (∫u dt, ∫u h dt, Δs ∫u n dt, the
/// changes of n, the largest n) with n(t) = round(h(t)/Δs) the strip's rows. On each piece
/// between rows u and h are linear, so ∫u is the trapezoid and ∫u h (quadratic) Simpson's rule,
/// both exact; n is constant between the times h crosses (k + ½) Δs, found on each piece, and
/// ∫u n is the trapezoid on each such interval.
fn surge_integrals(end: f64) -> (f64, f64, f64, usize, usize) {
    let ds = SPACING;
    let mut cuts: Vec<f64> = SURGE.iter().map(|r| r[0]).filter(|&t| t < end).collect();
    cuts.push(end);
    let (mut travel, mut exact, mut rounded, mut jumps, mut most) = (0.0, 0.0, 0.0, 0, 0);
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (ha, hb) = (surge(a, 1), surge(b, 1));
        let (ua, um, ub) = (surge(a, 2), surge(0.5 * (a + b), 2), surge(b, 2));
        travel += 0.5 * (b - a) * (ua + ub);
        exact += (b - a) / 6.0 * (ua * ha + 4.0 * um * surge(0.5 * (a + b), 1) + ub * hb);
        let mut times = vec![a, b];
        if ha != hb {
            for k in 0..=(0.6 / ds) as usize {
                let s = (((k as f64 + 0.5) * ds - ha) / (hb - ha)) * (b - a) + a;
                if s > a && s < b {
                    times.push(s);
                    jumps += 1;
                }
            }
        }
        times.sort_by(f64::total_cmp);
        for p in times.windows(2) {
            let n = (surge(0.5 * (p[0] + p[1]), 1) / ds).round();
            rounded += ds * n * 0.5 * (p[1] - p[0]) * (surge(p[0], 2) + surge(p[1], 2));
            most = most.max(n as usize);
        }
    }
    (travel, exact, rounded, jumps, most)
}

/// Issue 37 item 3: an inflow driven by a time series whose level rises, holds and falls while
/// its velocity changes ([`SURGE`]), run with E-MPS to 1.4 s (700 steps, past the last row).
///
/// Every step: the balance closes exactly (Δ all = inserted − removed − withdrawn − escaped,
/// Δ fluid = entered − removed − escaped, Δ strip = inserted − entered − withdrawn); the strip
/// holds exactly the rows n = round(h(t)/Δs), so its top n Δs is within ½ Δs of h(t); every strip
/// particle moves at u(t − Δt/2), the step's midpoint velocity.
///
/// The volume entered, V_e = entered Δs³, against the analytic references of
/// [`surge_integrals`]: V_n = W Δs ∫u n dt (rows rounded) and V = W ∫u h dt (exact), W = 0.5 m the
/// channel's width (10 sites). Derivation, with D(t) = ∫u the strip's travel (the midpoint
/// velocity makes it exact: no row falls inside a step), ν(D) = n at travel D, and W Δs ν dD the
/// volume the strip carries over dD: V_n = W Δs ∫₀^{D(T)} ν dD. Layer j crosses the plane in the
/// step k in which D passes D_j = (j + ½) Δs and is turned into fluid at the next step's start;
/// it carries n_j = min(n(t_{k−1}), n(t_k)) rows (rows added in step k skip it, rows withdrawn do
/// not), i.e. ν at some D' within u_max Δt of D_j. So V_e = W Δs Σ_{j<N} Δs n_j with N the layers
/// turned into fluid by T, and
/// - on layer j's interval [j Δs, (j + 1) Δs] ν differs from n_j only beyond a change of n
///   between D and D': at most ½ Δs + u_max Δt of the interval per change, by 1 row each: at most
///   C (½ Δs + u_max Δt) over the run, C = 8 changes of n (2 → 6 → 2 rows);
/// - N Δs differs from D(T) by at most ½ Δs + u_max Δt (N = round-down of D(t_{K−1})/Δs + ½, one
///   step behind), at most n_max = 6 rows high.
///
/// Hence |V_e − V_n| ≤ W Δs (C + n_max)(½ Δs + u_max Δt) = 0.5 · 0.05 · 14 · 0.028 = 9.8e-3 m³,
/// and since |n Δs − h| ≤ ½ Δs, |V_n − V| ≤ ½ W Δs D(T) = 0.5 · 0.5 · 0.05 · 1.4 = 1.75e-2 m³:
/// |V_e − V| ≤ 2.73e-2 m³. Measured: see the printed line.
#[test]
fn a_series_drives_the_strip_up_and_down() {
    let text = SURGE
        .iter()
        .map(|r| format!("{}, {}, {}\n", r[0], r[1], r[2]))
        .collect::<String>();
    let path = series_file("surge.csv", &format!("t, level, velocity\n{text}"));
    let case = parse(&series_channel(&path)).unwrap_or_else(|e| panic!("{e}"));
    let cfg = &case.fluid["river"];
    let mut s = FluidSolver::new(cfg);
    let (ds, dt, end) = (SPACING, cfg.time_step, 1.4);
    let floor_site = 0.5 * ds;
    let (n0, f0, i0) = counts(&s);
    assert_eq!(
        (f0, i0),
        (0, 10 * 10 * 2),
        "the initial strip: 10 layers × 10 sites × 2 rows"
    );
    let inflow = Kind::Inflow.code();
    while s.time() < end - 1e-9 {
        s.step(dt).unwrap_or_else(|e| panic!("{e}"));
        let (t, b) = (s.time(), s.open_boundaries().balance());
        let (n, f, i) = counts(&s);
        let (ins, ent, rem, wd, esc) = (
            b.inserted as i64,
            b.entered as i64,
            b.removed as i64,
            b.withdrawn as i64,
            s.escaped() as i64,
        );
        assert_eq!(n - n0, ins - rem - wd - esc, "t = {t}: all particles vs {b:?}");
        assert_eq!(f - f0, ent - rem - esc, "t = {t}: fluid vs {b:?}");
        assert_eq!(i - i0, ins - ent - wd, "t = {t}: strip vs {b:?}");
        let p = s.particles();
        let strip: Vec<usize> = (0..p.len()).filter(|&k| p.kind[k] == inflow).collect();
        let rows = (surge(t, 1) / ds).round() as usize;
        let row_of = |k: usize| ((p.z[k] - floor_site) / ds).round() as usize;
        let top = strip.iter().map(|&k| row_of(k) + 1).max().unwrap_or(0);
        assert_eq!(top, rows, "t = {t}: strip rows vs round(h/Δs)");
        assert!(
            (top as f64 * ds - surge(t, 1)).abs() <= 0.5 * ds + 1e-9,
            "t = {t}: strip top {} m vs h = {} m",
            top as f64 * ds,
            surge(t, 1)
        );
        let u = surge(t - 0.5 * dt, 2);
        assert!(
            strip.iter().all(|&k| (p.vx[k] - u).abs() < 1e-12),
            "t = {t}: the strip moves at u(t − Δt/2) = {u} m/s"
        );
    }
    let b = s.open_boundaries().balance();
    let (travel, exact, rounded, jumps, most) = surge_integrals(end);
    assert_eq!((jumps, most), (8, 6), "the surge's changes of n and largest n");
    let width = 10.0 * ds;
    let entered = b.entered as f64 * ds.powi(3);
    let (v_n, v) = (width * rounded, width * exact);
    let u_max = 1.5;
    let layers_bound = width * ds * (jumps + most) as f64 * (0.5 * ds + u_max * dt);
    let rows_bound = 0.5 * width * ds * travel;
    println!(
        "{b:?}; strip travel {travel:.4} m; entered {entered:.5} m³, W Δs ∫u n dt = {v_n:.5} m³ (bound {layers_bound:.2e}), W ∫u h dt = {v:.5} m³ (bound {:.2e})",
        layers_bound + rows_bound
    );
    assert!((entered - v_n).abs() <= layers_bound, "{entered} vs {v_n}");
    assert!(
        (entered - v).abs() <= layers_bound + rows_bound,
        "{entered} vs {v}"
    );
    // Four falls of one row, each withdrawing a row of 10 sites from every strip layer: 9 or 10
    // layers upstream of the plane (the front one crosses half a spacing after a whole layer's
    // travel) and at most one that crossed in that step.
    assert!(
        (4 * 9 * 10..=4 * 11 * 10).contains(&b.withdrawn),
        "withdrawn {}",
        b.withdrawn
    );
}

/// A series with a constant level and velocity drives the same strip as the constant keys, to
/// the bit: the same particles and balance after 0.3 s with E-MPS and 0.04 s with ISPH.
#[test]
fn a_constant_series_gives_the_particles_of_the_constant_keys() {
    let keys = CHANNEL.replace("initial_level = 0.1\nrise_time = 0.4\n", "");
    let path = series_file("constant.csv", "t, level, velocity\n0, 0.3, 1.0\n1, 0.3, 1.0\n");
    let series = series_channel(&path);
    for (method, end) in [(FluidMethodName::Emps, 0.3), (FluidMethodName::Isph, 0.04)] {
        let run = |text: &str| {
            let case = parse(text).unwrap_or_else(|e| panic!("{e}"));
            let mut cfg = case.fluid["river"].clone();
            if method == FluidMethodName::Isph {
                cfg.method = method;
                cfg.isph = Some(schemas::case::fluid::IsphConfig::default());
                cfg.validate("fluid.river").unwrap_or_else(|e| panic!("{e:?}"));
            }
            let mut s = FluidSolver::new(&cfg);
            s.advance_to(end).unwrap_or_else(|e| panic!("{e}"));
            (
                s.particles().clone(),
                s.open_boundaries().balance(),
                cfg.sound_speed(),
            )
        };
        let (a, b) = (run(&keys), run(&series));
        assert_eq!((a.1, a.2), (b.1, b.2), "{method:?}: balance and sound speed");
        assert!(a.1.entered > 0, "{method:?}: {:?}", a.1);
        assert!(a.0 == b.0, "{method:?}: the particles differ");
    }
}

#[test]
fn bad_series_keys_are_refused_naming_the_key_and_the_file() {
    let good = series_file("good.csv", "0, 0.1, 1.0\n1, 0.3, 1.0\n");
    let text = series_channel(&good);
    let case = parse(&text).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        case.named_files().contains(&good),
        "the series is among the case's input files"
    );
    let key = "`fluid.river.inflow.series`";
    let with = |extra: &str| text.replace("strip_length = 0.5\n", &format!("strip_length = 0.5\n{extra}"));
    let e = error_of(&with("velocity = 1.0\n"));
    assert!(e.contains(key) && e.contains("`velocity` must be absent"), "{e}");
    let e = error_of(&with("level = 0.3\nrise_time = 1.0\n"));
    assert!(
        e.contains(key) && e.contains("`level`, `rise_time` must be absent"),
        "{e}"
    );
    let e = error_of(&CHANNEL.replace("velocity = 1.0\n", ""));
    assert!(
        e.contains("`fluid.river.inflow.velocity`") && e.contains("is required") && e.contains("series"),
        "{e}"
    );
    let e = error_of(&series_channel(Path::new("/nonexistent/inflow.csv")));
    assert!(
        e.contains(key) && e.contains("cannot read the inflow series /nonexistent/inflow.csv"),
        "{e}"
    );
    let high = series_file("high.csv", "t, level, velocity\n0, 0.1, 1.0\n1, 0.7, 1.0\n");
    let e = error_of(&series_channel(&high));
    let at = format!("{} line 3 (t = 1 s)", high.display());
    assert!(
        e.contains(key) && e.contains(&at) && e.contains("[0, 0.6]"),
        "{e}"
    );
    let backwards = series_file("backwards.csv", "0, 0.1, 1.0\n1, 0.3, -1.0\n");
    let e = error_of(&series_channel(&backwards));
    let at = format!("{} line 2 (t = 1 s)", backwards.display());
    assert!(
        e.contains(key) && e.contains(&at) && e.contains("backwards"),
        "{e}"
    );
    // The GPU path runs an inflow driven by a series (gpu_open_boundaries.rs).
    let gpu = text.replace("[fluid.river]\n", "[fluid.river]\nbackend = \"gpu\"\n");
    parse(&gpu).unwrap_or_else(|e| panic!("{e}"));
}
