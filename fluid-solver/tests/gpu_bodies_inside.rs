//! The instability detector's "inside a body" check on the GPU path: water put inside a box body
//! or a mesh body that was moved and turned is found by the device at the body's present pose,
//! and the host names the step, the particle and the body as the CPU does
//! (`bodies_inside_check.rs` has the scene and the CPU's rule).

use crate::bodies_inside_check::{at_moved_body, put_first_fluid_at, raised_body, MOVED_AND_TURNED};
use crate::gpu_common;

use fluid_solver::{FluidSolver, Instability};
use schemas::case::FluidConfig;

/// Runs up to 4 steps of `cfg` on the CPU and on the GPU with the body at [`MOVED_AND_TURNED`],
/// the first water particle put at `local` in the body's frame after the second; both findings
/// (`None` for a run without one), or `None` without a device.
fn findings(cfg: &FluidConfig, local: [f64; 3]) -> Option<[Option<Instability>; 2]> {
    let dev = gpu_common::device()?;
    let mut cpu = FluidSolver::new(cfg);
    let mut gpu = FluidSolver::new(cfg);
    gpu.to_device(cfg, dev).unwrap_or_else(|e| panic!("{e}"));
    let run = |s: &mut FluidSolver| -> Option<Instability> {
        s.set_body_motion(&MOVED_AND_TURNED, &[0.0; 6], 0.0)
            .unwrap_or_else(|e| panic!("{e}"));
        for k in 0..4 {
            if k == 2 {
                put_first_fluid_at(s, at_moved_body(local));
            }
            if let Err(e) = s.step(cfg.time_step) {
                return Some(e);
            }
        }
        None
    };
    let found = [run(&mut cpu), run(&mut gpu)];
    for (path, f) in ["CPU", "GPU"].iter().zip(&found) {
        println!(
            "{path}: {}",
            f.as_ref().map_or("no finding".into(), |e| e.to_string())
        );
    }
    Some(found)
}

/// The message without the particle's coordinates (f32 on the device): the body and its pose,
/// and the rule.
fn without_coordinates(e: &Instability) -> (&str, &str) {
    let m = e.message.as_str();
    let body = m.split(": r = ").next().unwrap_or(m);
    let rule = m.rsplit("in the body's frame, ").next().unwrap_or(m);
    (body, rule)
}

/// Water 1.5 spacings inside the moved and turned body's inner sites (box body: well within its
/// box less half a spacing) is found at the step after it was put there, as on the CPU; 0.25
/// spacings inside the body's end face it is no finding on either path.
fn found_as_on_the_cpu(mesh: bool) {
    let cfg = raised_body(if mesh { "gpu-mesh" } else { "gpu-box" }, mesh);
    let Some([cpu, gpu]) = findings(&cfg, [0.045, 0.005, -0.005]) else {
        return;
    };
    let (a, b) = (
        cpu.expect("the CPU found nothing"),
        gpu.expect("the GPU found nothing"),
    );
    assert_eq!(
        (a.step, a.quantity, a.particle),
        (b.step, b.quantity, b.particle),
        "CPU: {a}\nGPU: {b}"
    );
    assert_eq!(b.step, 3, "{b}");
    assert!(b.message.starts_with("inside body 0"), "{b}");
    assert_eq!(without_coordinates(&a), without_coordinates(&b));
    let Some(none) = findings(&cfg, [0.075, 0.005, -0.005]) else {
        return;
    };
    assert!(none.iter().all(Option::is_none), "{none:?}");
}

#[test]
fn water_inside_a_moved_and_turned_box_body_is_found_as_on_the_cpu() {
    found_as_on_the_cpu(false);
}

#[test]
fn water_inside_a_moved_and_turned_mesh_body_is_found_as_on_the_cpu() {
    found_as_on_the_cpu(true);
}
