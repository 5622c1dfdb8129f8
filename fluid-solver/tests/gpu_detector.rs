//! The instability detector on the GPU path (reduced on the device, explained by the host's
//! detector on a copy): the same finding at the same step as on the CPU for a particle made too
//! fast, a particle put inside a wall or a wall block (the block as moved onto the lattice), a
//! NaN, and energy fed in without a source.

use crate::gpu_common;

use fluid_solver::{FluidSolver, Instability, Kind};
use schemas::case::Case;
use std::path::Path;

const CASE: &str = r#"
[case]
name = "small"
end_time = 0.1

[fluid.water]
spacing = 0.02
time_step = 8.0e-4
output_interval = 0.05
tank = { min = [0.0, 0.0, 0.0], max = [0.2, 0.06, 0.3], lid = true }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.1, 0.06, 0.2]
"#;

/// Runs up to 6 steps on the CPU and on the GPU with `disturb` applied to the particles after
/// the second step; returns both findings.
fn findings(disturb: impl Fn(&mut fluid_solver::particles::Particles)) -> Option<(Instability, Instability)> {
    findings_in(CASE, disturb)
}

/// As [`findings`], for the case `text`.
fn findings_in(
    text: &str,
    disturb: impl Fn(&mut fluid_solver::particles::Particles),
) -> Option<(Instability, Instability)> {
    let dev = gpu_common::device()?;
    let case = Case::parse(Path::new("small.toml"), text.to_string()).unwrap_or_else(|e| panic!("{e}"));
    let cfg = &case.fluid["water"];
    let mut cpu = FluidSolver::new(cfg);
    let mut gpu = FluidSolver::new(cfg);
    gpu.to_device(cfg, dev).unwrap_or_else(|e| panic!("{e}"));
    let run = |s: &mut FluidSolver| -> Instability {
        for k in 0..6 {
            if k == 2 {
                disturb(s.particles_mut());
            }
            if let Err(e) = s.step(cfg.time_step) {
                return e;
            }
        }
        panic!("no instability was found")
    };
    let (a, b) = (run(&mut cpu), run(&mut gpu));
    println!("CPU: {a}\nGPU: {b}");
    Some((a, b))
}

/// The first fluid particle by id.
fn first_fluid(p: &fluid_solver::particles::Particles) -> usize {
    (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid.code())
        .min_by_key(|&i| p.id[i])
        .unwrap_or_else(|| panic!("no fluid"))
}

fn same(a: &Instability, b: &Instability) {
    assert_eq!(
        (a.step, a.quantity, a.particle),
        (b.step, b.quantity, b.particle),
        "CPU: {a}\nGPU: {b}"
    );
}

#[test]
fn a_too_fast_particle_is_found_as_on_the_cpu() {
    let Some((a, b)) = findings(|p| {
        let i = first_fluid(p);
        p.vx[i] = 30.0;
    }) else {
        return;
    };
    same(&a, &b);
    assert_eq!(b.quantity, "velocity", "{b}");
    // the diagnostic names the time step that would hold this speed (0.5 Δs per step)
    assert!(a.message.contains("use time_step ≤"), "{a}");
}

#[test]
fn a_particle_inside_a_wall_is_found_as_on_the_cpu() {
    let Some((a, b)) = findings(|p| {
        let i = first_fluid(p);
        p.x[i] = -0.05;
    }) else {
        return;
    };
    same(&a, &b);
    assert!(b.message.contains("inside a wall"), "{b}");
}

/// A wall block written from x = 0.148 m is built from x = 0.14 m (the nearest lattice face); the
/// detector's box is that less half a spacing, from x = 0.15 m. A particle put at x = 0.153 m is
/// inside it (and outside the written block less half a spacing, from 0.158 m): found by the
/// device as by the CPU.
#[test]
fn a_particle_inside_a_wall_block_on_the_lattice_is_found_as_on_the_cpu() {
    let text = format!("{CASE}\n[[fluid.water.wall]]\nmin = [0.148, 0.0, 0.0]\nmax = [0.2, 0.06, 0.05]\n");
    let Some((a, b)) = findings_in(&text, |p| {
        let i = first_fluid(p);
        (p.x[i], p.y[i], p.z[i]) = (0.153, 0.025, 0.025);
    }) else {
        return;
    };
    same(&a, &b);
    assert_eq!(b.step, 3, "{b}");
    assert!(b.message.contains("inside a wall block [0.15"), "{b}");
}

#[test]
fn a_nan_is_found() {
    let Some((a, b)) = findings(|p| {
        let i = first_fluid(p);
        p.vz[i] = f64::NAN;
    }) else {
        return;
    };
    same(&a, &b);
    assert!(b.message.contains("not a number"), "{b}");
}

#[test]
fn energy_fed_in_without_a_source_is_found_as_on_the_cpu() {
    let Some((a, b)) = findings(|p| {
        for i in 0..p.len() {
            if p.kind[i] == Kind::Fluid.code() {
                p.vz[i] += 1.5;
            }
        }
    }) else {
        return;
    };
    assert_eq!((a.step, a.quantity), (b.step, b.quantity), "CPU: {a}\nGPU: {b}");
    assert_eq!(b.quantity, "mechanical energy", "{b}");
}

/// A fluid particle above an open tank's domain has left through the open top: the device
/// counts it and removes it before the next step, as the CPU does, without copying the
/// particles back.
#[test]
fn fluid_leaving_through_the_open_top_is_removed_as_on_the_cpu() {
    let Some(dev) = gpu_common::device() else {
        return;
    };
    let text = CASE.replace(", lid = true", "");
    let case = Case::parse(Path::new("small.toml"), text).unwrap_or_else(|e| panic!("{e}"));
    let cfg = &case.fluid["water"];
    let mut cpu = FluidSolver::new(cfg);
    let mut gpu = FluidSolver::new(cfg);
    gpu.to_device(cfg, dev).unwrap_or_else(|e| panic!("{e}"));
    for s in [&mut cpu, &mut gpu] {
        let top = s.domain().hi[2];
        for k in 0..4 {
            s.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
            if k == 1 {
                let p = s.particles_mut();
                let i = first_fluid(p);
                p.z[i] = top + 0.01;
            }
        }
        s.sync_host();
    }
    assert_eq!((cpu.escaped(), gpu.escaped()), (1, 1));
    assert_eq!(cpu.particles().len(), gpu.particles().len());
    // whole copies: the one that moved the particle (particles_mut) and the final one
    assert_eq!(
        gpu.host_copies().0,
        2,
        "the escape must not copy the particles back"
    );
}
