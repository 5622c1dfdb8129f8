//! Real scenes' keys (issue 37): solids from meshes, terrains from height grids and planes, the
//! wave maker and damping zones. Good files load and are placed; bad ones are refused when the
//! case is loaded, with the key, the file and what is wrong: a mesh that is not closed, one with
//! a flipped or a degenerate triangle, an inverted one, one far larger than the tank (drawn in
//! millimetres), a grid with a missing value, a grid outside the tank, a paddle too thin or one
//! that would leave the tank, a flap with a bad hinge, without a depth, turning too far or
//! leaving the tank, an initial wave off the water or out of the tank, and the GPU path refusing
//! wave makers by name (it runs damping zones).

use schemas::case::Case;
use schemas::geometry::{write_ascii_grid, write_binary_stl, HeightGrid, TriangleMesh};
use std::path::{Path, PathBuf};

/// A fresh folder for one test's files.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("scene-files-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

/// A 1 × 0.2 × 0.3 m flume at Δs = 0.02 m with water 0.1 m deep, and `extra` appended to its
/// fluid section.
fn flume(extra: &str) -> String {
    format!(
        r#"[case]
name = "scene"
end_time = 1.0

[fluid.flume]
spacing = 0.02
time_step = 1.0e-3
sound_speed = 10.0
output_interval = 0.1
tank = {{ min = [0.0, 0.0, 0.0], max = [1.0, 0.2, 0.3] }}

[[fluid.flume.block]]
min = [0.1, 0.0, 0.0]
max = [1.0, 0.2, 0.1]
{extra}"#
    )
}

fn parse(dir: &Path, text: String) -> Result<Case, String> {
    Case::parse(&dir.join("case.toml"), text).map_err(|e| e.to_string())
}

fn refused(dir: &Path, text: String, fragments: &[&str]) {
    let err = match parse(dir, text) {
        Ok(_) => panic!("the case was accepted; expected an error with {fragments:?}"),
        Err(e) => e,
    };
    for f in fragments {
        assert!(err.contains(f), "the error does not say `{f}`:\n{err}");
    }
    println!("refused: {err}");
}

const PIER: &str = "\n[[fluid.flume.solid]]\nmesh = \"pier.stl\"\n";

#[test]
fn a_closed_mesh_is_read_and_placed_by_scale_rotation_and_translation() {
    let dir = folder("placed");
    // a 10 × 20 × 40 mm box drawn in millimetres at the origin
    let mesh = TriangleMesh::cuboid([0.0; 3], [10.0, 20.0, 40.0]);
    write_binary_stl(&dir.join("pier.stl"), &mesh).unwrap_or_else(|e| panic!("{e}"));
    let text = flume("\n[[fluid.flume.solid]]\nmesh = \"pier.stl\"\nscale = 0.001\nrotate = [0.0, 0.0, 90.0]\ntranslate = [0.5, 0.05, 0.0]\n");
    let case = parse(&dir, text).unwrap_or_else(|e| panic!("{e}"));
    let placed = case.fluid["flume"].solid[0]
        .placed
        .get()
        .unwrap_or_else(|| panic!("not loaded"));
    let (lo, hi) = placed.aabb();
    // rotated by 90° about z: x spans −20 … 0 mm, y 0 … 10 mm, then moved
    let want = ([0.48, 0.05, 0.0], [0.5, 0.06, 0.04]);
    for a in 0..3 {
        assert!(
            (lo[a] - want.0[a]).abs() < 1e-12 && (hi[a] - want.1[a]).abs() < 1e-12,
            "{lo:?} … {hi:?}"
        );
    }
    assert!((placed.signed_volume() - 8e-6).abs() < 1e-18);
}

#[test]
fn meshes_that_are_no_solid_are_refused_naming_the_file_and_the_fault() {
    let dir = folder("bad-meshes");
    let cube = TriangleMesh::cuboid([0.4, 0.05, 0.0], [0.5, 0.15, 0.2]);
    let mut open = cube.clone();
    open.triangles.pop();
    write_binary_stl(&dir.join("pier.stl"), &open).unwrap_or_else(|e| panic!("{e}"));
    refused(
        &dir,
        flume(PIER),
        &["fluid.flume.solid[0].mesh", "pier.stl", "open"],
    );

    let mut flipped = cube.clone();
    flipped.triangles[3].swap(0, 1);
    write_binary_stl(&dir.join("pier.stl"), &flipped).unwrap_or_else(|e| panic!("{e}"));
    refused(&dir, flume(PIER), &["pier.stl", "flipped"]);

    let mut inverted = cube.clone();
    inverted.triangles.iter_mut().for_each(|t| t.swap(0, 1));
    write_binary_stl(&dir.join("pier.stl"), &inverted).unwrap_or_else(|e| panic!("{e}"));
    refused(&dir, flume(PIER), &["pier.stl", "inverted"]);

    let mut degenerate = cube.clone();
    let v = degenerate.triangles[0];
    degenerate.triangles.push([v[0], v[0], v[1]]);
    write_binary_stl(&dir.join("pier.stl"), &degenerate).unwrap_or_else(|e| panic!("{e}"));
    refused(&dir, flume(PIER), &["pier.stl", "degenerate"]);

    // the same pier drawn in millimetres and placed without a scale
    let mm = TriangleMesh::cuboid([400.0, 50.0, 0.0], [500.0, 150.0, 200.0]);
    write_binary_stl(&dir.join("pier.stl"), &mm).unwrap_or_else(|e| panic!("{e}"));
    refused(&dir, flume(PIER), &["pier.stl", "millimetres", "scale = 0.001"]);

    refused(
        &dir,
        flume("\n[[fluid.flume.solid]]\nmesh = \"missing.stl\"\n"),
        &["fluid.flume.solid[0].mesh", "missing.stl"],
    );
    std::fs::write(dir.join("pier.ply"), "ply\n").unwrap_or_else(|e| panic!("{e}"));
    refused(
        &dir,
        flume("\n[[fluid.flume.solid]]\nmesh = \"pier.ply\"\n"),
        &["pier.ply", "stl", "obj"],
    );
}

#[test]
fn grids_with_missing_values_or_off_the_tank_and_bad_planes_are_refused() {
    let dir = folder("bad-grids");
    let grid = HeightGrid::from_fn(11, 5, [0.0, 0.0], [0.1, 0.05], |x, _| 0.05 * x)
        .unwrap_or_else(|e| panic!("{e}"));
    write_ascii_grid(&dir.join("bed.asc"), &grid).unwrap_or_else(|e| panic!("{e}"));
    let bed = "\n[[fluid.flume.terrain]]\ngrid = \"bed.asc\"\n";
    parse(&dir, flume(bed)).unwrap_or_else(|e| panic!("a good grid was refused: {e}"));

    // one value of the file replaced by the NODATA value
    let text = std::fs::read_to_string(dir.join("bed.asc")).unwrap_or_else(|e| panic!("{e}"));
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    lines.insert(6, "NODATA_value -9999".into());
    lines.retain(|l| !l.is_empty());
    let data = lines
        .iter()
        .position(|l| l.starts_with(|c: char| c.is_ascii_digit() || c == '-'))
        .unwrap_or(7);
    let mut row: Vec<String> = lines[data].split_whitespace().map(str::to_string).collect();
    row[3] = "-9999".into();
    lines[data] = row.join(" ");
    std::fs::write(dir.join("hole.asc"), lines.join("\n") + "\n").unwrap_or_else(|e| panic!("{e}"));
    refused(
        &dir,
        flume("\n[[fluid.flume.terrain]]\ngrid = \"hole.asc\"\n"),
        &["fluid.flume.terrain[0].grid", "hole.asc"],
    );

    refused(
        &dir,
        flume("\n[[fluid.flume.terrain]]\ngrid = \"bed.asc\"\ntranslate = [100.0, 0.0, 0.0]\n"),
        &["fluid.flume.terrain[0].grid", "outside the tank"],
    );
    refused(
        &dir,
        flume("\n[[fluid.flume.terrain]]\nplane = { point = [0.5, 0.0, 0.0], normal = [1.0, 0.0, -2.0] }\n"),
        &["fluid.flume.terrain[0].plane.normal", "point up"],
    );
    refused(
        &dir,
        flume("\n[[fluid.flume.terrain]]\n"),
        &["fluid.flume.terrain[0]", "exactly one of `grid`"],
    );
}

#[test]
fn a_wave_maker_too_thin_or_leaving_the_tank_is_refused_and_the_gpu_path_takes_it() {
    let dir = folder("wave-maker");
    let paddle = |min_x: f64, max_x: f64, extra: &str| {
        format!(
            "\n[fluid.flume.wave_maker]\nmin = [{min_x}, 0.0, 0.0]\nmax = [{max_x}, 0.2, 0.3]\nmotion = \"solitary\"\nwave_height = 0.02\ndepth = 0.1\n{extra}"
        )
    };
    let good = flume(&paddle(0.0, 0.08, ""));
    let case = parse(&dir, good.clone()).unwrap_or_else(|e| panic!("{e}"));
    let built = case.fluid["flume"]
        .wave_maker
        .as_ref()
        .and_then(|w| w.built.clone());
    let stroke = built.map(|m| m.range(10.0).1).unwrap_or(0.0);
    // Goring's stroke √(16 H d / 3) less 0.05 % (the cut at |θ| = 3.8)
    assert!(
        (stroke / (16.0 * 0.02 * 0.1 / 3.0f64).sqrt() - 1.0).abs() < 1e-3,
        "{stroke}"
    );

    refused(
        &dir,
        flume(&paddle(0.0, 0.06, "")),
        &["fluid.flume.wave_maker.max", "wall_layers"],
    );
    // a paddle whose stroke within the run's 1 s (0.06 m) would carry it past the tank's end
    let near_end = flume(&paddle(0.0, 0.08, ""))
        .replace("max = [1.0, 0.2, 0.3] }", "max = [0.12, 0.2, 0.3] }")
        .replace("max = [1.0, 0.2, 0.1]", "max = [0.12, 0.2, 0.1]");
    refused(
        &dir,
        near_end,
        &["fluid.flume.wave_maker.motion", "would leave the tank"],
    );
    refused(
        &dir,
        flume(&paddle(0.0, 0.08, "")).replace("wave_height = 0.02", "wave_height = 0.07"),
        &["fluid.flume.wave_maker.wave_height", "0.6"],
    );
    refused(
        &dir,
        flume(&paddle(0.0, 0.08, "")).replace("motion = \"solitary\"", "motion = \"table\""),
        &["fluid.flume.wave_maker.table", "required"],
    );
    std::fs::write(dir.join("stroke.csv"), "t, x\n0, 0\n1, oops\n").unwrap_or_else(|e| panic!("{e}"));
    refused(
        &dir,
        flume(&paddle(0.0, 0.08, "table = \"stroke.csv\"\n"))
            .replace("motion = \"solitary\"", "motion = \"table\""),
        &["fluid.flume.wave_maker.table", "stroke.csv", "line 3"],
    );

    // wave makers run on the GPU (fluid-solver/tests/gpu_wave_maker.rs)
    let gpu = good.replace("spacing = 0.02", "backend = \"gpu\"\nspacing = 0.02");
    parse(&dir, gpu).unwrap_or_else(|e| panic!("{e}"));
    let damped =
        flume("\n[[fluid.flume.damping]]\nmin = [0.8, 0.0, 0.0]\nmax = [1.0, 0.2, 0.3]\nrate = 5.0\n");
    parse(&dir, damped.clone()).unwrap_or_else(|e| panic!("{e}"));
    // damping zones run on the GPU (fluid-solver/tests/gpu_damping.rs)
    parse(
        &dir,
        damped.replace("spacing = 0.02", "backend = \"gpu\"\nspacing = 0.02"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    refused(
        &dir,
        damped.replace("rate = 5.0", "rate = 5.0\naxis = \"z\""),
        &["fluid.flume.damping[0].axis"],
    );
}

/// A flap (`kind = "flap"`) in the 1 m flume: hinged l = 0.2 m under the floor it makes the
/// solitary wave (H/d = 0.2) with a stroke (d + l)/(d/2 + l) = 6/5 of Goring's at the
/// still-water level, turning by θ = atan(X / (d + l)); refused, naming the key: without
/// `hinge_z`, with it above the paddle's bottom or on a piston, without `depth` (a table), hinged
/// on the floor (tan θ = X_p / (d/2): 50° by the run's end at 1 s, > 30°), swinging back through
/// the tank's end wall (regular waves, ±16°), rising into a lid, and on the GPU.
#[test]
fn a_flap_with_a_bad_hinge_no_depth_too_steep_or_leaving_the_tank_is_refused() {
    let dir = folder("flap");
    let flap = |min_x: f64, motion: &str, extra: &str| {
        let max_x = min_x + 0.08;
        format!(
            "\n[fluid.flume.wave_maker]\nkind = \"flap\"\nmin = [{min_x}, 0.0, 0.0]\nmax = [{max_x}, 0.2, 0.3]\nmotion = \"{motion}\"\n{extra}"
        )
    };
    let solitary = "wave_height = 0.02\ndepth = 0.1\n";
    let good = flume(&flap(0.0, "solitary", &format!("{solitary}hinge_z = -0.2\n")));
    let case = parse(&dir, good.clone()).unwrap_or_else(|e| panic!("{e}"));
    let built = case.fluid["flume"]
        .wave_maker
        .as_ref()
        .and_then(|w| w.built.clone());
    let Some(schemas::wave_motion::WaveMakerMotion::Flap(m)) = built.as_deref() else {
        panic!("not a flap: {built:?}")
    };
    // X = X_p (d + l)/(d/2 + l) with Goring's X_p → √(16 H d / 3) (less 0.05 %, his cut)
    let goring = (16.0 * 0.02 * 0.1 / 3.0f64).sqrt();
    assert!((m.range(100.0).1 / (goring * 0.3 / 0.25) - 1.0).abs() < 1e-3);
    let (_, top) = m.angle_range(1.0);
    assert!(
        (top.tan() - m.range(1.0).1 / 0.3).abs() < 1e-12,
        "{}",
        top.to_degrees()
    );

    refused(
        &dir,
        flume(&flap(0.0, "solitary", solitary)),
        &["fluid.flume.wave_maker.hinge_z", "required", "flap"],
    );
    refused(
        &dir,
        flume(&flap(0.0, "solitary", &format!("{solitary}hinge_z = 0.05\n"))),
        &["fluid.flume.wave_maker.hinge_z", "at or below", "min.z = 0"],
    );
    refused(
        &dir,
        flume(
            &flap(0.0, "solitary", &format!("{solitary}hinge_z = -0.2\n")).replace("kind = \"flap\"\n", ""),
        ),
        &["fluid.flume.wave_maker.hinge_z", "kind = \"flap\" only"],
    );
    std::fs::write(dir.join("flap.csv"), "t, x\n0, 0\n1, 0.02\n").unwrap_or_else(|e| panic!("{e}"));
    refused(
        &dir,
        flume(&flap(0.0, "table", "table = \"flap.csv\"\nhinge_z = 0.0\n")),
        &["fluid.flume.wave_maker.depth", "required with kind = \"flap\""],
    );
    refused(
        &dir,
        flume(&flap(0.0, "solitary", &format!("{solitary}hinge_z = 0.0\n"))),
        &[
            "fluid.flume.wave_maker.motion",
            "the flap turns from 0.0° to",
            "±30°",
        ],
    );
    // Regular waves T = 1 s on d = 0.1 m (kd = 0.68, H/S = 0.35 for l = 0): S/2 = 0.029 m,
    // θ = ±16°; leaning back the top of a paddle against the end wall (x = 0) goes through it,
    // 0.1 m further in it stays in.
    let regular = "wave_height = 0.02\ndepth = 0.1\nperiod = 1.0\nhinge_z = 0.0\n";
    refused(
        &dir,
        flume(&flap(0.0, "regular", regular)),
        &[
            "fluid.flume.wave_maker.motion",
            "would leave the tank",
            "x from 0 to 1",
        ],
    );
    let inside = flume(&flap(0.1, "regular", regular)).replace(
        "min = [0.1, 0.0, 0.0]\nmax = [1.0",
        "min = [0.18, 0.0, 0.0]\nmax = [1.0",
    );
    parse(&dir, inside).unwrap_or_else(|e| panic!("{e}"));
    // the top back corner rises by √(0.08² + 0.5²) − 0.5 = 6 mm as the flap passes tan θ = 0.16
    refused(
        &dir,
        good.replace("max = [1.0, 0.2, 0.3] }", "max = [1.0, 0.2, 0.3], lid = true }"),
        &["fluid.flume.wave_maker.motion", "lid at 0.3"],
    );
    // a flap too (fluid-solver/tests/gpu_wave_maker.rs)
    parse(
        &dir,
        good.replace("spacing = 0.02", "backend = \"gpu\"\nspacing = 0.02"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
}

/// A terrain from a GeoTIFF (`grid = "bed.tif"`) is the terrain from the ESRI ASCII grid of the
/// same cells: the heights at every lattice column of the flume agree exactly (both hold the
/// heights as written, f64). A grid file of another kind is refused naming the formats read.
#[test]
fn a_geotiff_terrain_is_the_ascii_grids_terrain() {
    let dir = folder("geotiff");
    let grid = HeightGrid::from_fn(11, 5, [0.0, 0.0], [0.1, 0.05], |x, y| 0.05 * x + 0.01 * y)
        .unwrap_or_else(|e| panic!("{e}"));
    write_ascii_grid(&dir.join("bed.asc"), &grid).unwrap_or_else(|e| panic!("{e}"));
    schemas::geometry::write_geotiff(&dir.join("bed.tif"), &grid).unwrap_or_else(|e| panic!("{e}"));
    let load = |file: &str| {
        let case = parse(
            &dir,
            flume(&format!("\n[[fluid.flume.terrain]]\ngrid = \"{file}\"\n")),
        )
        .unwrap_or_else(|e| panic!("{file}: {e}"));
        case.fluid["flume"].terrain[0].clone()
    };
    let (asc, tif) = (load("bed.asc"), load("bed.tif"));
    let mut compared = 0;
    for i in 0..50 {
        for j in 0..10 {
            let (x, y) = (0.01 + 0.02 * f64::from(i), 0.01 + 0.02 * f64::from(j));
            assert_eq!(asc.height_at(x, y), tif.height_at(x, y), "at {x}, {y}");
            compared += usize::from(asc.height_at(x, y).is_some());
        }
    }
    assert!(compared > 200, "only {compared} columns have terrain");

    std::fs::copy(dir.join("bed.asc"), dir.join("bed.xyz")).unwrap_or_else(|e| panic!("{e}"));
    refused(
        &dir,
        flume("\n[[fluid.flume.terrain]]\ngrid = \"bed.xyz\"\n"),
        &["fluid.flume.terrain[0].grid", "bed.xyz", ".asc", ".tif"],
    );
}

/// `[initial_wave]` in the 1 m flume (still level 0.1 m): a good wave loads; refused, naming the
/// key: H/d above 0.6, a crest outside the tank, a direction other than ±x, a still level no
/// block's top is at (depth 0.15 m: the wave would float above the water), a crest above the
/// tank's top.
#[test]
fn an_initial_wave_off_the_water_or_out_of_the_tank_is_refused() {
    let dir = folder("initial-wave");
    let wave = |extra: &str| {
        flume(&format!(
            "\n[fluid.flume.initial_wave]\nheight = 0.02\ndepth = 0.1\ncrest = 0.5\n{extra}"
        ))
    };
    let case = parse(&dir, wave("direction = \"-x\"\n")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        case.fluid["flume"].initial_wave.as_ref().and_then(|w| w.sign()),
        Some(-1.0)
    );
    refused(
        &dir,
        wave("").replace("height = 0.02", "height = 0.07"),
        &["fluid.flume.initial_wave.height", "0.6"],
    );
    refused(
        &dir,
        wave("").replace("crest = 0.5", "crest = 1.5"),
        &["fluid.flume.initial_wave.crest", "outside the tank"],
    );
    refused(
        &dir,
        wave("direction = \"x\"\n"),
        &["fluid.flume.initial_wave.direction", "\"+x\" or \"-x\""],
    );
    refused(
        &dir,
        wave("").replace("depth = 0.1", "depth = 0.15"),
        &["fluid.flume.initial_wave.depth", "no block's top"],
    );
    refused(
        &dir,
        wave("").replace("max = [1.0, 0.2, 0.3] }", "max = [1.0, 0.2, 0.11] }"),
        &["fluid.flume.initial_wave.depth", "above the tank's top"],
    );
}
