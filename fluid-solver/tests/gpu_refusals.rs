//! What the GPU path refuses: cases with features it does not run yet (by the case key or the
//! command-line flag), and no adapter at all (exit code 2 with how to get one); and what it
//! accepts since issue 38 (damping zones, the artificial viscosity, mesh solids, terrains,
//! bodies from meshes, wave makers, inflow and outflow boundaries, filtered wall-pressure
//! sensors, tanks far from the origin, ISPH with its default settings).

use crate::gpu_common;

use schemas::case::fluid::PaddleKind;
use schemas::case::{Case, FluidConfig};
use schemas::geometry::{write_binary_stl, TriangleMesh};
use std::path::{Path, PathBuf};
use std::process::Command;

const GOOD: &str = r#"
[case]
name = "small"
end_time = 0.004

[fluid.water]
backend = "gpu"
spacing = 0.02
time_step = 8.0e-4
output_interval = 0.002
tank = { min = [0.0, 0.0, 0.0], max = [0.2, 0.06, 0.3], lid = true }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.1, 0.06, 0.2]
"#;

fn error_of(text: &str) -> String {
    match Case::parse(Path::new("cases/small/case.toml"), text.to_string()) {
        Ok(_) => panic!("the case should have been refused:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn gpu_backend_refuses_what_it_does_not_run_naming_the_feature() {
    Case::parse(Path::new("cases/small/case.toml"), GOOD.to_string()).unwrap_or_else(|e| panic!("{e}"));
    let e = error_of(&GOOD.replace("backend = \"gpu\"", "backend = \"cuda\""));
    assert!(
        e.contains("cases/small/case.toml") && e.contains("cpu") && e.contains("gpu"),
        "{e}"
    );
    // ISPH with its default settings runs on the GPU (tests/gpu_isph.rs)
    let isph = GOOD.replace("backend = \"gpu\"", "backend = \"gpu\"\nmethod = \"isph\"");
    Case::parse(Path::new("cases/small/case.toml"), isph.clone()).unwrap_or_else(|e| panic!("{e}"));
    // ISPH settings and features the device does not run yet are refused by name
    for (extra, named) in [
        ("\n[fluid.water.isph]\npressure_gradient = \"corrected-difference\"\n", "isph.pressure_gradient"),
        ("\n[fluid.water.isph]\nshifting = \"lind\"\n", "isph.shifting"),
        (
            "\n[[fluid.water.body]]\nname = \"box\"\nmin = [0.14, 0.0, 0.0]\nmax = [0.18, 0.06, 0.04]\n",
            "resolved bodies",
        ),
        (
            "\n[[fluid.water.probe]]\nname = \"p\"\nkind = \"wall-pressure\"\nposition = [0.2, 0.03, 0.04]\nnormal = \"-x\"\ndiameter = 0.04\nwindow = 0.01\n",
            "wall-pressure sensors",
        ),
    ] {
        let e = error_of(&format!("{isph}{extra}"));
        assert!(
            e.contains("`fluid.water.backend`") && e.contains(named) && e.contains("isph") && e.contains("backend = \"cpu\""),
            "{e}"
        );
    }
    // resolved bodies run on the GPU (tests/gpu_bodies.rs)
    let body = "\n[[fluid.water.body]]\nname = \"box\"\nmin = [0.14, 0.0, 0.0]\nmax = [0.18, 0.06, 0.04]\n";
    Case::parse(Path::new("cases/small/case.toml"), format!("{GOOD}{body}"))
        .unwrap_or_else(|e| panic!("{e}"));
    let probe = "\n[[fluid.water.probe]]\nname = \"p\"\nkind = \"wall-pressure\"\nposition = [0.2, 0.03, 0.04]\nnormal = \"-x\"\ndiameter = 0.04\nwindow = 0.01\n";
    // filtered sensors run on the GPU (tests/gpu_filtered_probes.rs)
    Case::parse(Path::new("cases/small/case.toml"), format!("{GOOD}{probe}"))
        .unwrap_or_else(|e| panic!("{e}"));

    // A tank 2 km from the origin runs since the device keeps positions from the tank's corner
    // (tests/gpu_far_from_origin.rs)
    let far = GOOD
        .replace(
            "min = [0.0, 0.0, 0.0], max = [0.2,",
            "min = [2000.0, 0.0, 0.0], max = [2000.2,",
        )
        .replace(
            "min = [0.0, 0.0, 0.0]\nmax = [0.1,",
            "min = [2000.0, 0.0, 0.0]\nmax = [2000.1,",
        );
    assert!(far.contains("2000.2") && far.contains("2000.1"));
    Case::parse(Path::new("cases/small/case.toml"), far).unwrap_or_else(|e| panic!("{e}"));
    // A tank 700 m long at Δs = 0.02 m (35 000 spacings): at its far end plain f32 positions
    // would round by 4.2e-5 m = 2.1e-3 Δs, so the device keeps them wide (hi + lo, tests/
    // gpu_wide_positions.rs), their high parts on a grid of 2⁻¹³ m (rounding 6.1e-5 m =
    // 3.1e-3 Δs, for plane and cell tests only).
    let long = GOOD.replace("max = [0.2, 0.06, 0.3], lid", "max = [700.0, 0.06, 0.3], lid");
    assert!(long.contains("700.0"));
    let case = Case::parse(Path::new("cases/small/case.toml"), long).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(case.fluid["water"].gpu_quantum(), Some(2f64.powi(-13)));
    // 20 km at Δs = 0.06 m (333 000 spacings): past 16 384 m the high parts need a quantum of
    // 2⁻⁸ m and round by 2.0e-3 m = 0.033 Δs, more than the 0.02 Δs the wide positions allow
    // (at most 273 066 spacings at this Δs)
    let longer = GOOD
        .replace("spacing = 0.02", "spacing = 0.06")
        .replace("max = [0.2, 0.06, 0.3], lid", "max = [20000.0, 0.06, 0.3], lid");
    assert!(longer.contains("20000.0") && longer.contains("0.06\n"));
    let e = error_of(&longer);
    assert!(
        e.contains("`fluid.water.backend`") && e.contains("two f32 parts") && e.contains("273066 spacings"),
        "{e}"
    );
}

/// Open boundaries run on the GPU since issue 38 (`gpu_open_boundaries.rs`): the case file
/// with an inflow and an outflow is accepted with `backend = "gpu"`, and so is each alone.
#[test]
fn gpu_backend_accepts_open_boundaries() {
    let edits: [fn(&mut FluidConfig); 3] = [|_| {}, |c| c.inflow = None, |c| c.outflow = None];
    for edit in edits {
        let (_, mut cfg) = crate::common::load_case("bridge-washout-small");
        edit(&mut cfg);
        assert!(cfg.inflow.is_some() || cfg.outflow.is_some());
        cfg.gpu_support("fluid.x")
            .unwrap_or_else(|e| panic!("`{}`: {}", e.key, e.message));
    }
}

/// Wave makers run on the GPU since issue 38 (`gpu_wave_maker.rs`): the case file with a piston,
/// and the same with a flap, are accepted with `backend = "gpu"`.
#[test]
fn gpu_backend_accepts_wave_makers() {
    for kind in [PaddleKind::Piston, PaddleKind::Flap] {
        let (_, mut cfg) = crate::common::load_case("bridge-deck-solitary");
        if let Some(w) = &mut cfg.wave_maker {
            w.kind = kind;
        }
        assert!(cfg.wave_maker.is_some(), "bridge-deck-solitary has a wave maker");
        cfg.gpu_support("fluid.x")
            .unwrap_or_else(|e| panic!("{kind:?}: `{}`: {}", e.key, e.message));
    }
}

/// What issue 38 put on the device is accepted with `backend = "gpu"`, each alone: a damping
/// zone, the artificial viscosity, a solid from an STL, a terrain plane and a body from the same
/// STL (their GPU-against-CPU tests: `gpu_damping.rs`, `gpu_artificial_viscosity.rs`,
/// `gpu_scene_walls.rs`, `gpu_mesh_bodies.rs`).
#[test]
fn gpu_backend_accepts_damping_viscosity_solids_terrains_and_mesh_bodies() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu_accepts");
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let half = [0.02; 3];
    write_binary_stl(
        &dir.join("cube.stl"),
        &TriangleMesh::cuboid(half.map(|h| -h), half),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    for (settings, tables) in [
        ("", "\n[[fluid.water.damping]]\nmin = [0.1, 0.0, 0.0]\nmax = [0.2, 0.06, 0.3]\nrate = 10.0\n"),
        ("\nartificial_viscosity = 0.05", ""),
        ("", "\n[[fluid.water.solid]]\nmesh = \"cube.stl\"\ntranslate = [0.15, 0.03, 0.03]\n"),
        ("", "\n[[fluid.water.terrain]]\nplane = { point = [0.1, 0.0, 0.0], normal = [-1.0, 0.0, 4.0] }\n"),
        ("", "\n[[fluid.water.body]]\nname = \"cube\"\nmesh = { file = \"cube.stl\", translate = [0.15, 0.03, 0.2] }\n"),
    ] {
        let text = format!(
            "{}{tables}",
            GOOD.replace("backend = \"gpu\"", &format!("backend = \"gpu\"{settings}"))
        );
        Case::parse(&dir.join("case.toml"), text).unwrap_or_else(|e| panic!("{settings}{tables}: {e}"));
    }
}

fn write_case(dir: &str, text: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
    path
}

/// With the Vulkan loader pointed at no driver, `--backend gpu` stops before any step with
/// exit code 2 and says how to get a device or to use the CPU.
#[test]
fn no_adapter_is_a_clear_error_with_exit_code_2() {
    let case = write_case("gpu_no_adapter", &GOOD.replace("backend = \"gpu\"\n", ""));
    let out = Command::new(env!("CARGO_BIN_EXE_fluid-solver"))
        .args(["run", &case.to_string_lossy(), "--backend", "gpu", "--out"])
        .arg(case.with_file_name("out"))
        .env("VK_DRIVER_FILES", "/nonexistent/icd.json")
        .env("VK_ICD_FILENAMES", "/nonexistent/icd.json")
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    let err = String::from_utf8_lossy(&out.stderr);
    println!("{err}");
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("no GPU") && err.contains("mesa-vulkan-drivers") && err.contains("backend = \"cpu\""),
        "{err}"
    );
}

/// `backend = "gpu"` in the case: the run goes through on the device and writes its frames
/// (positions copied back only for the frames).
#[test]
fn a_gpu_case_runs_through_the_command_line() {
    if gpu_common::device().is_none() {
        return;
    }
    let case = write_case("gpu_run", GOOD);
    let out_dir = case.with_file_name("out");
    let out = Command::new(env!("CARGO_BIN_EXE_fluid-solver"))
        .args(["run", &case.to_string_lossy(), "--out"])
        .arg(&out_dir)
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    let err = String::from_utf8_lossy(&out.stderr);
    println!("{err}");
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(err.contains("running on the GPU"), "{err}");
    for k in 0..3 {
        let frame = out_dir.join(format!("water_{k:05}.vtu"));
        assert!(frame.is_file(), "missing {}", frame.display());
    }
}

/// ISPH on the GPU does not run wave makers and open boundaries yet: each is refused by name.
#[test]
fn gpu_backend_refuses_isph_with_a_wave_maker_or_open_boundaries() {
    for (case, named) in [
        ("bridge-deck-solitary", "a wave maker"),
        ("bridge-washout-small", "inflow and outflow"),
    ] {
        let (_, mut cfg) = crate::common::load_case(case);
        cfg.method = schemas::case::fluid::FluidMethodName::Isph;
        cfg.body.clear(); // refused on its own (above)
        match cfg.gpu_support("fluid.x") {
            Ok(()) => panic!("{case} with ISPH should be refused on the GPU"),
            Err(e) => assert!(
                e.key == "fluid.x.backend" && e.message.contains(named) && e.message.contains("isph"),
                "`{}`: {}",
                e.key,
                e.message
            ),
        }
    }
}
