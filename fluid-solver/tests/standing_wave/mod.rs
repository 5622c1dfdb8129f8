//! A linear standing wave in a closed tank (issue 37), a module of the `wave_maker` test binary
//! (one binary less to build in CI): the methods' gravity waves against
//! ω² = g k tanh(k d), with no paddle and no step in the surface to make a bore.
//!
//! The tank is L = 0.4 m long, d = 0.1 m deep and four spacings wide (the quasi-2-D flume of
//! `cases/solitary-wave-flat`). The water starts flat with the velocity of the first sloshing
//! mode at its zero crossing: the potential φ = (a g/ω) cosh(kz)/cosh(kd) cos(kx) cos(ωt),
//! k = π/L, a = 0.01 m (ka = 0.079, so the second-order frequency shift is below 1 %). Its
//! surface is then η = a cos(kx) sin(ωt), and the water's centre of mass moves along the tank as
//! x̄ − L/2 = −A sin(ωt) with A = 2aL/(π²d), the only shape the first mode gives it.
//!
//! The full check (two periods) fails today with every method (`docs/notes/standing-wave.md`):
//! the default, the exact projection with its kernel correction (`isph::kernel_correction`),
//! reaches 0.98 A at the first swing at d/16 and then loses about 5 % a swing (0.93, 0.88,
//! 0.81 A), its half periods 3 % long, most of it this tank's width: particle side walls read
//! the pressure as flat along them (eight particles wide the second crossing is 1.6 % of a period
//! late, sixteen wide 1.05 %); without the correction the symmetric gradients
//! (`"symmetric"`, `"conservative"` with `kernel_correction = "none"`) reach 0.71–0.76 A at the
//! first swing at d/8, d/16 and d/32, whatever the time step, the checkerboard share or the
//! shifting, and 0.49 A at the second; the corrected difference
//! reaches A but crosses L/2 first 12 % of a half period early and its next swing grows to
//! 1.3–1.8 A; with Lind's shifting it follows the first half period within 5 %, grows to 1.2 A at
//! d/16 and keeps 0.97–1.04 A at d/32 (the setting `cases/solitary-wave-flat` uses); E-MPS
//! damps it (`docs/notes/emps-gravity-waves.md`).

use crate::common;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidMethodName, PressureGradient, Shifting};
use schemas::case::FluidConfig;
use schemas::validation::{record, Record};
use std::f64::consts::PI;

/// Depth d [m].
const DEPTH: f64 = 0.1;
/// Tank length L [m]: half the first mode's wavelength.
const LENGTH: f64 = 0.4;
/// Amplitude a of the surface [m].
const AMPLITUDE: f64 = 0.01;
/// Gravity of the cases [m/s²].
const G: f64 = 9.8;

/// ω of the first mode (the linear dispersion relation ω² = g k tanh(k d)).
fn omega() -> f64 {
    let k = PI / LENGTH;
    (G * k * (k * DEPTH).tanh()).sqrt()
}

/// The closed tank at `per_depth` spacings per depth, still water to d, with ISPH's gradient
/// `gradient` and `shifting`, or with E-MPS (c = 7 m/s, 5 √(gd), Courant 0.5).
fn tank(
    method: FluidMethodName,
    gradient: PressureGradient,
    shifting: Shifting,
    per_depth: f64,
) -> FluidConfig {
    let (_, mut cfg) = common::load_case("solitary-wave-flat");
    let ds = DEPTH / per_depth;
    let width = 4.0 * ds;
    cfg.spacing = ds;
    cfg.wave_maker = None;
    cfg.probe.clear();
    cfg.damping.clear();
    cfg.tank.max = [LENGTH, width, 0.16];
    cfg.block.truncate(1);
    cfg.block[0].min = [0.0, 0.0, 0.0];
    cfg.block[0].max = [LENGTH, width, DEPTH];
    // the wave's top speed is a ω / (k d) ≈ 0.1 m/s: the flume's u_in + 2√(gd) is far too high
    cfg.max_velocity = Some(1.0);
    if method == FluidMethodName::Emps {
        cfg.method = method;
        cfg.isph = None;
        cfg.sound_speed = Some(7.0);
        cfg.time_step = 0.5 * ds / 7.0;
    } else {
        let isph = cfg.isph.get_or_insert_with(Default::default);
        isph.pressure_gradient = gradient;
        isph.shifting = shifting;
        cfg.time_step = 0.2 * ds;
    }
    cfg.validate("fluid.tank").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}

/// Sets the first mode's velocity at its zero crossing on every fluid particle (module doc).
fn start_the_mode(solver: &mut FluidSolver) {
    let k = PI / LENGTH;
    let scale = AMPLITUDE * G * k / omega() / (k * DEPTH).cosh();
    let p = solver.particles_mut();
    for i in 0..p.len() {
        if p.kind[i] == Kind::Fluid.code() {
            p.vx[i] = -scale * (k * p.z[i]).cosh() * (k * p.x[i]).sin();
            p.vz[i] = scale * (k * p.z[i]).sinh() * (k * p.x[i]).cos();
        }
    }
}

/// x̄ − L/2 of the fluid.
fn centre_offset(solver: &FluidSolver) -> f64 {
    let p = solver.particles();
    let (sum, n) = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid.code())
        .fold((0.0, 0.0), |(s, n), i| (s + p.x[i], n + 1.0));
    sum / n - LENGTH / 2.0
}

/// What the centre of mass did over two periods: the extremum of each swing over A, and the
/// times it crossed L/2.
struct Swing {
    extrema: Vec<f64>,
    crossings: Vec<f64>,
}

fn swing(method: FluidMethodName, gradient: PressureGradient, shifting: Shifting, per_depth: f64) -> Swing {
    swing_of(&tank(method, gradient, shifting, per_depth), 2.1)
}

/// [`swing`] of the tank `cfg` over `periods` periods.
fn swing_of(cfg: &FluidConfig, periods: f64) -> Swing {
    let method = cfg.method;
    let mut solver = FluidSolver::new(cfg);
    start_the_mode(&mut solver);
    let period = 2.0 * PI / omega();
    let big_a = 2.0 * AMPLITUDE * LENGTH / (PI * PI * DEPTH);
    let every = 2.5e-3;
    let (mut t, mut last, mut extremum) = (0.0, 0.0, 0.0_f64);
    let (mut extrema, mut crossings) = (Vec::new(), Vec::new());
    while t < periods * period {
        t += every;
        solver.advance_to(t).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        let x = centre_offset(&solver);
        assert!(x.is_finite(), "{method:?}: the centre of mass is {x} at {t} s");
        if t > 0.1 * period && (last > 0.0) != (x > 0.0) {
            crossings.push(t - every * x / (x - last));
            extrema.push(extremum / big_a);
            extremum = 0.0;
        }
        extremum = extremum.max(x.abs());
        last = x;
    }
    Swing { extrema, crossings }
}

/// Each swing's extremum within 5 % of A (the second-order shift at ka = 0.079 is below 1 %;
/// the other modes the lattice lets in are of order Δs/L = 1.6 %), and each crossing of L/2
/// within 3 % of a period of n π/ω, over two periods.
fn check(name: &str, s: &Swing) {
    let period = 2.0 * PI / omega();
    println!(
        "{name}: swings {:.3?} A; crossings {:.4?} s (theory every {:.4} s from {:.4} s)",
        s.extrema,
        s.crossings,
        0.5 * period,
        0.5 * period
    );
    assert!(
        s.crossings.len() >= 4,
        "{name}: {} crossings in two periods",
        s.crossings.len()
    );
    for (n, (&x, &t)) in s.extrema.iter().zip(&s.crossings).enumerate() {
        assert!((x - 1.0).abs() < 0.05, "{name}: swing {} reaches {x:.3} A", n + 1);
        let theory = 0.5 * period * (n + 1) as f64;
        assert!(
            (t - theory).abs() < 0.03 * period,
            "{name}: crossing {} at {t:.4} s against {theory:.4} s",
            n + 1
        );
    }
}

/// The first swing of the default ISPH (the exact projection with its kernel correction) at
/// d/16: its extremum within 5 % of A and its crossing of L/2 within 3 % of a period of π/ω,
/// [`check`]'s bounds (from theory), over 0.6 of a period (about 16 s on 2 cores). Measured
/// (1 Dec 2026): 0.981 A, crossing 0.4538 s against 0.4422 s (1.3 % of a period); without the
/// kernel correction 0.757 A, 0.4087 s, then 0.490 A and no further crossing in two periods
/// (`docs/notes/standing-wave.md`).
#[test]
fn the_default_isph_carries_a_standing_wave_through_its_first_swing() {
    let cfg = tank(
        FluidMethodName::Isph,
        PressureGradient::default(),
        Shifting::Off,
        16.0,
    );
    let started = std::time::Instant::now();
    let s = swing_of(&cfg, 0.6);
    let period = 2.0 * PI / omega();
    println!(
        "ISPH default, d/16, first swing: {:.3?} A, crossing {:.4?} s",
        s.extrema, s.crossings
    );
    let (Some(&x), Some(&t)) = (s.extrema.first(), s.crossings.first()) else {
        panic!(
            "the centre of mass did not cross L/2 in 0.6 periods: {:?}",
            s.crossings
        );
    };
    let row = Record {
        case: "the first sloshing mode of a closed tank, L = 0.4 m, d = 0.1 m, a = 0.01 m (a/d = 0.1), started at its zero crossing".into(),
        resolution: "ISPH defaults (exact projection, kernel correction), Δs = d/16, Δt = 0.2 Δs s".into(),
        source: "fluid-solver/tests/standing_wave/mod.rs::the_default_isph_carries_a_standing_wave_through_its_first_swing".into(),
        run_time_s: started.elapsed().as_secs_f64(),
        bound_source: "standing_wave::check's bounds: second-order shift < 1 % at ka = 0.079, lattice modes ≈ Δs/L".into(),
        ..Default::default()
    };
    record(Record {
        id: "isph-standing-wave-first-swing".into(),
        capability: "ISPH (default) gravity wave: standing wave's first swing".into(),
        reference: "linear theory: the centre of mass swings to A = 2aL/(π²d)".into(),
        measure: "|extremum of the first swing / A − 1|".into(),
        value: (x - 1.0).abs(),
        bound: Some(0.05),
        unit: "".into(),
        ..row.clone()
    });
    record(Record {
        id: "isph-standing-wave-first-crossing".into(),
        capability: "ISPH (default) gravity wave: standing wave's half period".into(),
        reference: "linear theory: the centre of mass crosses L/2 at π/ω, ω² = g k tanh(kd)".into(),
        measure: "|first crossing − π/ω| / period".into(),
        value: (t - 0.5 * period).abs() / period,
        bound: Some(0.03),
        unit: "".into(),
        ..row
    });
    assert!((x - 1.0).abs() < 0.05, "the first swing reaches {x:.3} A");
    assert!(
        (t - 0.5 * period).abs() < 0.03 * period,
        "the first crossing at {t:.4} s against {:.4} s",
        0.5 * period
    );
}

#[test]
#[ignore = "fails today: the default keeps 0.98 A at the first swing, then loses about 5 % a swing, its half periods 3 % long in this tank four particles wide (docs/notes/standing-wave.md)"]
fn a_standing_wave_keeps_its_amplitude_and_period_with_default_isph() {
    let s = swing(
        FluidMethodName::Isph,
        PressureGradient::default(),
        Shifting::Off,
        16.0,
    );
    check("ISPH default (conservative, kernel correction), d/16", &s);
}

#[test]
#[ignore = "fails today: the first half period is 12 % short and the wave grows (docs/notes/standing-wave.md)"]
fn a_standing_wave_keeps_its_amplitude_and_period_with_s2_8_isph() {
    let s = swing(
        FluidMethodName::Isph,
        PressureGradient::CorrectedDifference,
        Shifting::Off,
        16.0,
    );
    check("ISPH corrected difference, d/16", &s);
}

#[test]
#[ignore = "fails today: the wave grows to 1.2 A at d/16; at d/32 it keeps 0.97-1.04 A, its third crossing 4.6 % of a period late (docs/notes/standing-wave.md)"]
fn a_standing_wave_keeps_its_amplitude_and_period_with_s2_8_isph_and_shifting() {
    let s = swing(
        FluidMethodName::Isph,
        PressureGradient::CorrectedDifference,
        Shifting::Lind,
        16.0,
    );
    check("ISPH corrected difference with Lind shifting, d/16", &s);
}

#[test]
#[ignore = "fails today: E-MPS damps the wave, 0.45 A at the second swing at d/8, less at d/16 (docs/notes/emps-gravity-waves.md)"]
fn a_standing_wave_keeps_its_amplitude_and_period_with_emps() {
    let s = swing(
        FluidMethodName::Emps,
        PressureGradient::default(),
        Shifting::Off,
        16.0,
    );
    check("E-MPS, d/16", &s);
}
