//! Bad input is refused before any step with an error naming the file, the key and what is
//! allowed; an unstable run stops with a diagnostic naming the step, the particle and the
//! quantity, and keeps the output written so far.

use fluid_solver::FluidSolver;
use schemas::case::Case;
use std::path::{Path, PathBuf};
use std::process::Command;

const GOOD: &str = r#"
[case]
name = "small"
end_time = 0.2

[fluid.water]
spacing = 0.02
time_step = 8.0e-4
output_interval = 0.05
tank = { min = [0.0, 0.0, 0.0], max = [0.2, 0.2, 0.3] }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.1, 0.2, 0.2]
"#;

fn parse(text: &str) -> Result<Case, String> {
    Case::parse(Path::new("cases/small/case.toml"), text.to_string()).map_err(|e| e.to_string())
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

#[test]
fn the_reference_case_is_accepted() {
    let case = parse(GOOD).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(case.fluid["water"].body_names(), Vec::<&str>::new());
}

#[test]
fn unstable_time_step_is_refused_with_the_limit() {
    let e = error_of(&GOOD.replace("time_step = 8.0e-4", "time_step = 5.0e-3"));
    assert!(
        e.contains("cases/small/case.toml") && e.contains("`fluid.water.time_step`"),
        "{e}"
    );
    assert!(e.contains("Courant") && e.contains("time_step ≤"), "{e}");
    let viscous = GOOD
        .replace("time_step = 8.0e-4", "time_step = 8.0e-4\nviscosity = 1.0")
        .replace("spacing = 0.02", "spacing = 0.02\nsound_speed = 1.0");
    let e = error_of(&viscous);
    assert!(
        e.contains("`fluid.water.time_step`") && e.contains("viscous"),
        "{e}"
    );
}

#[test]
fn body_outside_the_domain_is_refused() {
    let text = format!(
        "{GOOD}\n[[fluid.water.body]]\nname = \"box\"\nmin = [0.15, 0.05, 0.25]\nmax = [0.25, 0.1, 0.28]\n"
    );
    let e = error_of(&text);
    assert!(
        e.contains("`fluid.water.body[0]`") && e.contains("outside the domain"),
        "{e}"
    );
}

#[test]
fn zero_spacing_is_refused() {
    let e = error_of(&GOOD.replace("spacing = 0.02", "spacing = 0.0"));
    assert!(e.contains("`fluid.water.spacing`") && e.contains("> 0"), "{e}");
}

#[test]
fn overlapping_blocks_are_refused() {
    let text = format!("{GOOD}\n[[fluid.water.block]]\nmin = [0.05, 0.0, 0.0]\nmax = [0.15, 0.2, 0.1]\n");
    let e = error_of(&text);
    assert!(
        e.contains("`fluid.water.block[1]`") && e.contains("overlaps `fluid.water.block[0]`"),
        "{e}"
    );
    let gate = format!("{GOOD}\n[[fluid.water.gate]]\nmin = [0.08, 0.0, 0.0]\nmax = [0.12, 0.2, 0.2]\n");
    let e = error_of(&gate);
    assert!(
        e.contains("`fluid.water.gate[0]`") && e.contains("overlaps"),
        "{e}"
    );
}

#[test]
fn other_bad_keys_name_what_is_allowed() {
    // Extents off the lattice are rounded (see `lattice.rs`), but a tank needs one layer.
    let e = error_of(&GOOD.replace("max = [0.2, 0.2, 0.3]", "max = [0.2, 0.004, 0.3]"));
    assert!(e.contains("at least one spacing"), "{e}");
    let e = error_of(&GOOD.replace(
        "output_interval = 0.05",
        "output_interval = 0.05\nwall_layers = 2",
    ));
    assert!(
        e.contains("`fluid.water.wall_layers`") && e.contains("4 … 10"),
        "{e}"
    );
    let e = error_of(&GOOD.replace("output_interval = 0.05", "output_interval = 0.05\nspeed = 3"));
    assert!(e.contains("speed"), "{e}");
    let damped = |value: &str| {
        GOOD.replace(
            "spacing = 0.02",
            &format!("spacing = 0.02\nartificial_viscosity = {value}"),
        )
    };
    parse(&damped("0.05")).unwrap_or_else(|e| panic!("{e}"));
    let e = error_of(&damped("-0.1"));
    assert!(
        e.contains("`fluid.water.artificial_viscosity`") && e.contains("[0, 1]"),
        "{e}"
    );
    // With ISPH the E-MPS-only keys are not refused but named as unused (issue 12: one key
    // switches a case's method), `e_mps_settings_are_named_unused_when_isph_runs` below.
    let isph =
        parse(&damped("0.05\nmethod = \"isph\"\nsound_speed = 12.1")).unwrap_or_else(|e| panic!("{e}"));
    let unused = isph.fluid["water"].unused_by_method();
    assert_eq!(unused.len(), 2, "{unused:?}");
    assert!(
        unused[0].contains("`sound_speed` = 12.1") && unused[1].contains("`artificial_viscosity` = 0.05")
    );
    assert!(parse(&damped("0.05")).map(|c| c.fluid["water"].unused_by_method().is_empty()) == Ok(true));
    // ISPH's pressure gradient: one of three names.
    let isph = |form: &str| {
        GOOD.replace("time_step = 8.0e-4", "time_step = 8.0e-4\nmethod = \"isph\"")
            + &format!("\n[fluid.water.isph]\npressure_gradient = \"{form}\"\n")
    };
    let symmetric =
        parse(&(isph("symmetric") + "influence_radius = 2.0\n")).unwrap_or_else(|e| panic!("{e}"));
    assert!(symmetric.fluid["water"].warnings().is_empty());
    // With a body the symmetric gradient is warned about (no face normals at its convex edges:
    // a load near them reads wrong), the default is not; a wall box has them with either.
    let obstacle = "\n[[fluid.water.wall]]\nmin = [0.14, 0.06, 0.0]\nmax = [0.18, 0.1, 0.06]\n";
    let body = "\n[[fluid.water.body]]\nname = \"box\"\nmin = [0.14, 0.06, 0.02]\nmax = [0.18, 0.1, 0.06]\n";
    let symmetric_with = |solid: &str| {
        parse(&(isph("symmetric") + "influence_radius = 2.0\n" + solid))
            .unwrap_or_else(|e| panic!("{e}"))
            .fluid["water"]
            .warnings()
    };
    assert!(symmetric_with(obstacle).is_empty());
    let warnings = symmetric_with(body);
    assert!(
        warnings.len() == 1
            && warnings[0].contains("`isph.pressure_gradient`")
            && warnings[0].contains("body")
            && warnings[0].contains("corrected-difference"),
        "{warnings:?}"
    );
    // The exact projection's bodies complete the water's kernel sums (no faces' normals): no
    // warning; outside 1.95 … 2.15 Δs it is refused as the symmetric gradient is.
    let conservative = parse(&(isph("conservative") + "influence_radius = 2.0\n" + body))
        .unwrap_or_else(|e| panic!("{e}"))
        .fluid["water"]
        .warnings();
    assert!(conservative.is_empty(), "{conservative:?}");
    for solid in [obstacle, body] {
        let default = parse(&(isph("corrected-difference") + solid)).unwrap_or_else(|e| panic!("{e}"));
        assert!(default.fluid["water"].warnings().is_empty());
    }
    parse(&isph("corrected-difference")).unwrap_or_else(|e| panic!("{e}"));
    // The symmetric forms' support is 2.0 Δs unless given, S2-8's 2.4 (S2, Table 1).
    let support = |form: &str| {
        parse(&isph(form)).unwrap_or_else(|e| panic!("{e}")).fluid["water"]
            .isph_settings()
            .support()
    };
    assert_eq!(
        [
            support("corrected-difference"),
            support("symmetric"),
            support("conservative")
        ],
        [2.4, 2.0, 2.0]
    );
    // The symmetric form only where the lattice is restored (S2's 2.4 spacings is not).
    let e = error_of(&(isph("symmetric") + "influence_radius = 2.4\n"));
    assert!(
        e.contains("`fluid.water.isph.influence_radius`")
            && e.contains("[1.95, 2.15]")
            && e.contains("got 2.4"),
        "{e}"
    );
    let e = error_of(&(isph("conservative") + "influence_radius = 2.4\n"));
    assert!(
        e.contains("`fluid.water.isph.influence_radius`")
            && e.contains("\"conservative\"")
            && e.contains("got 2.4"),
        "{e}"
    );
    let e = error_of(&isph("antisymmetric"));
    assert!(
        e.contains("pressure_gradient")
            && e.contains("corrected-difference")
            && e.contains("symmetric")
            && e.contains("conservative"),
        "{e}"
    );
    // The kernel correction: only for the symmetric forms, and one of two names.
    let e = error_of(&(isph("corrected-difference") + "kernel_correction = \"moment\"\n"));
    assert!(
        e.contains("`fluid.water.isph.kernel_correction`")
            && e.contains("corrected-difference")
            && e.contains("conservative"),
        "{e}"
    );
    parse(&(isph("corrected-difference") + "kernel_correction = \"none\"\n"))
        .unwrap_or_else(|e| panic!("{e}"));
    parse(&(isph("symmetric") + "kernel_correction = \"moment\"\n")).unwrap_or_else(|e| panic!("{e}"));
    let e = error_of(&(isph("conservative") + "kernel_correction = \"bonet-lok\"\n"));
    assert!(
        e.contains("kernel_correction") && e.contains("none") && e.contains("moment"),
        "{e}"
    );
    // ISPH's particle shifting: one of two names, a coefficient in (0, 6].
    let shift = |line: &str| {
        GOOD.replace("time_step = 8.0e-4", "time_step = 8.0e-4\nmethod = \"isph\"")
            + &format!("\n[fluid.water.isph]\n{line}\n")
    };
    parse(&shift("shifting = \"lind\"")).unwrap_or_else(|e| panic!("{e}"));
    parse(&shift("shifting = \"off\"")).unwrap_or_else(|e| panic!("{e}"));
    let e = error_of(&shift("shifting = \"xu\""));
    assert!(
        e.contains("shifting") && e.contains("off") && e.contains("lind"),
        "{e}"
    );
    let e = error_of(&shift("shifting = \"lind\"\nshifting_coefficient = 0.0"));
    assert!(
        e.contains("`fluid.water.isph.shifting_coefficient`") && e.contains("(0, 6]"),
        "{e}"
    );
    // With resolved bodies too (the water in a body's support is not shifted).
    parse(
        &(shift("shifting = \"lind\"")
            + "\n[[fluid.water.body]]\nname = \"box\"\nmin = [0.14, 0.06, 0.02]\nmax = [0.18, 0.1, 0.06]\n"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let probe =
        format!("{GOOD}\n[[fluid.water.probe]]\nname = \"p\"\nkind = \"pressure\"\nposition = [0.1, 0.1]\n");
    let e = error_of(&probe);
    assert!(
        e.contains("`fluid.water.probe[0].position`") && e.contains("3 coordinates"),
        "{e}"
    );
}

#[test]
fn nan_is_caught_naming_step_particle_and_quantity() {
    let case = parse(GOOD).unwrap_or_else(|e| panic!("{e}"));
    let mut solver = FluidSolver::new(&case.fluid["water"]);
    solver.advance_to(0.01).unwrap_or_else(|e| panic!("{e}"));
    let p = solver.particles_mut();
    let i = (0..p.len())
        .find(|&i| p.kind[i] == fluid_solver::Kind::Fluid.code())
        .unwrap_or(0);
    p.vx[i] = f64::NAN;
    let id = p.id[i];
    let e = solver.step(8.0e-4).expect_err("a NaN velocity must stop the run");
    println!("{e}");
    assert_eq!(e.particle, Some(id));
    assert_eq!(e.step, 14);
    assert!(e.quantity == "position" || e.quantity == "velocity", "{e}");
}

#[test]
fn cli_reports_instability_and_keeps_the_last_good_frames() {
    // A valid but far too soft case: c = 1 m/s passes the acoustic check with Δt = 0.02 s, but
    // the falling water soon moves more than half a spacing per step.
    let text = GOOD
        .replace("time_step = 8.0e-4", "time_step = 0.01\nsound_speed = 1.0")
        .replace("name = \"small\"", "name = \"soft\"")
        .replace("end_time = 0.2", "end_time = 2.0");
    let (dir, run) = run_cli("fluid-bad-input", &text);
    let out = dir.join("out");
    let stderr = String::from_utf8_lossy(&run.stderr);
    println!("{stderr}");
    assert!(!run.status.success());
    assert!(
        stderr.contains("unstable run stopped at step") && stderr.contains("particle"),
        "{stderr}"
    );
    let pvd = std::fs::read_to_string(out.join("water.pvd")).unwrap_or_else(|e| panic!("{e}"));
    let frames: Vec<&str> = pvd.lines().filter(|l| l.contains("<DataSet")).collect();
    assert!(!frames.is_empty());
    for f in frames {
        let file = f
            .split("file=\"")
            .nth(1)
            .and_then(|s| s.split('"').next())
            .unwrap_or_default();
        assert!(out.join(file).is_file(), "the PVD lists {file}, which is missing");
    }
    // A missing case file is a clear error too.
    let run = Command::new(env!("CARGO_BIN_EXE_fluid-solver"))
        .args(["run", &dir.join("nope.toml").to_string_lossy()])
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(!run.status.success());
    assert!(String::from_utf8_lossy(&run.stderr).contains("cannot read the case file"));
}

#[test]
fn energy_growing_without_a_source_is_caught() {
    let case = parse(GOOD).unwrap_or_else(|e| panic!("{e}"));
    let mut solver = FluidSolver::new(&case.fluid["water"]);
    solver.advance_to(0.01).unwrap_or_else(|e| panic!("{e}"));
    // Kick the resting water upwards at 1.5 m/s: 1.1 J/kg per particle, more than the allowed
    // growth of 0.1 · g · tank height = 0.29 J/kg; each particle moves only 0.06 Δs per step.
    let p = solver.particles_mut();
    for i in (0..p.len()).filter(|&i| p.kind[i] == fluid_solver::Kind::Fluid.code()) {
        p.vz[i] = 1.5;
    }
    let e = solver
        .step(8.0e-4)
        .expect_err("energy from nowhere must stop the run");
    println!("{e}");
    assert_eq!(e.quantity, "mechanical energy");
    assert!(e.particle.is_some() && e.step == 14, "{e}");
}

#[test]
fn a_box_without_particles_is_refused() {
    let text = format!("{GOOD}\n[[fluid.water.gate]]\nmin = [0.101, 0.0, 0.0]\nmax = [0.109, 0.2, 0.2]\n");
    let e = error_of(&text);
    assert!(
        e.contains("`fluid.water.gate[0]`") && e.contains("holds no particle"),
        "{e}"
    );
}

/// A case written for E-MPS (its sound speed set) runs with ISPH when `method = "isph"` is its
/// only change, and the run says, before its first step, that the sound speed is not used.
#[test]
fn e_mps_settings_are_named_unused_when_isph_runs() {
    let text = GOOD
        .replace(
            "time_step = 8.0e-4",
            "time_step = 8.0e-4\nsound_speed = 12.1\nmethod = \"isph\"",
        )
        .replace("end_time = 0.2", "end_time = 0.0016")
        .replace("name = \"small\"", "name = \"switched\"");
    let (dir, run) = run_cli("fluid-switched", &text);
    let stderr = String::from_utf8_lossy(&run.stderr);
    println!("{stderr}");
    assert!(run.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: water: `sound_speed` = 12.1 m/s is not used: ISPH has no sound speed"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Writes `text` as `case.toml` in a fresh folder `PREFIX-PID` and runs `fluid-solver run` on it
/// with its output in the folder's `out`; returns the folder and how the run ended.
fn run_cli(prefix: &str, text: &str) -> (PathBuf, std::process::Output) {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("{prefix}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let case = dir.join("case.toml");
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let run = Command::new(env!("CARGO_BIN_EXE_fluid-solver"))
        .args([
            "run",
            &case.to_string_lossy(),
            "--out",
            &dir.join("out").to_string_lossy(),
        ])
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    (dir, run)
}
