//! The output estimate `coupler run` prints before a run (issue #41 item 6): within ±30 % of what
//! three cheap shipped cases write — the implicit oscillator (its recording repeats every sweep),
//! a frame (snapshots and tables per history row) and the tutorial for 0.05 s (particle frames
//! and free-surface meshes). The ±30 % is the issue's requirement; measured on 2026-11-29 on the
//! 2-core machine the three were 0.99, 1.00 and 0.86 of their estimates (the full table is in
//! docs/guide/outputs.md), and the whole test took about 4 s in release.

use stack_tests::{coupler, out_dir, stderr, workspace};
use std::path::Path;

/// Bytes of every file under `dir`.
fn written(dir: &Path) -> u64 {
    std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
        .flatten()
        .map(|entry| match entry.metadata() {
            Ok(m) if m.is_dir() => written(&entry.path()),
            Ok(m) => m.len(),
            Err(_) => 0,
        })
        .sum()
}

/// The bytes in the line `estimate: … about 722 kB of output (…)`.
fn estimated(err: &str) -> f64 {
    let line = err
        .lines()
        .find(|l| l.starts_with("estimate:"))
        .unwrap_or_else(|| panic!("no estimate line: {err}"));
    let size = line
        .split("about ")
        .nth(1)
        .and_then(|rest| rest.split(" of output").next())
        .unwrap_or_else(|| panic!("no `about SIZE of output` in: {line}"));
    let (number, unit) = size.split_once(' ').unwrap_or((size, "B"));
    let scale = match unit {
        "kB" => 1e3,
        "MB" => 1e6,
        "GB" => 1e9,
        _ => 1.0,
    };
    number.parse::<f64>().unwrap_or_else(|e| panic!("`{size}`: {e}")) * scale
}

/// Runs `cases/NAME` (with `extra` arguments) and returns (estimate, bytes written).
fn run(root: &Path, name: &str, extra: &[&str]) -> (f64, u64) {
    let case = workspace().join("cases").join(name).join("case.toml");
    let out = root.join(name);
    let mut args = vec![
        "run",
        case.to_str().unwrap_or_default(),
        "--out",
        out.to_str().unwrap_or_default(),
    ];
    args.extend_from_slice(extra);
    let done = coupler(&args);
    let err = stderr(&done);
    assert!(done.status.success(), "{name}: {err}");
    (estimated(&err), written(&out))
}

#[test]
fn the_printed_estimate_is_within_30_percent_of_what_shipped_cases_write() {
    let root = out_dir("output-estimate");
    let mut misses = Vec::new();
    for (name, extra) in [
        ("oscillator", &[][..]),
        ("structure-plastic-collapse", &[][..]),
        ("tutorial", &["--end-time", "0.05"][..]),
    ] {
        let (estimate, bytes) = run(&root, name, extra);
        let ratio = bytes as f64 / estimate;
        eprintln!("{name}: estimate {estimate:.0} B, written {bytes} B, ratio {ratio:.2}");
        if !(0.7..=1.3).contains(&ratio) {
            misses.push(format!(
                "{name}: wrote {bytes} B, estimated {estimate:.0} B ({ratio:.2})"
            ));
        }
    }
    assert!(misses.is_empty(), "outside ±30 %: {misses:?}");
}

/// Mesh solids, mesh bodies and terrains count in the estimate (before, a mesh body counted 0
/// particles and solids and terrains were left out): the fluid alone in a tank with a 1:2 beach
/// (a `[[terrain]]` plane), an STL block across the tank standing in the water and an STL body
/// held in it, for three frames. The ±30 % is the issue's requirement, as above; without the
/// skins and the mesh body the estimate is about 0.65 of this one (their 4 200 particles of about
/// 12 800), so the test fails on the old count.
#[test]
fn the_estimate_counts_mesh_solids_bodies_and_terrains() {
    let dir = out_dir("output-estimate-meshes");
    let pier = dir.join("pier.stl");
    let block = dir.join("block.stl");
    schemas::geometry::write_binary_stl(
        &pier,
        &schemas::geometry::TriangleMesh::cuboid([0.2, 0.0, 0.0], [0.4, 0.3, 0.3]),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    schemas::geometry::write_binary_stl(
        &block,
        &schemas::geometry::TriangleMesh::cuboid([0.0, 0.0, 0.0], [0.1, 0.1, 0.06]),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let case = dir.join("case.toml");
    std::fs::write(
        &case,
        r#"[case]
name = "meshes"
end_time = 0.02

[fluid.water]
spacing = 0.02
sound_speed = 10.0
time_step = 1.0e-3
output_interval = 0.01
tank = { min = [0.0, 0.0, 0.0], max = [1.2, 0.3, 0.4] }

[[fluid.water.terrain]]
plane = { point = [0.6, 0.0, 0.0], normal = [-1.0, 0.0, 2.0] }

[[fluid.water.solid]]
mesh = "pier.stl"

[[fluid.water.body]]
name = "block"
mesh = { file = "block.stl", translate = [0.5, 0.1, 0.02] }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.6, 0.3, 0.2]
"#,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let done = coupler(&[
        "run",
        case.to_str().unwrap_or_default(),
        "--out",
        out.to_str().unwrap_or_default(),
    ]);
    let err = stderr(&done);
    assert!(done.status.success(), "{err}");
    let (estimate, bytes) = (estimated(&err), written(&out));
    let ratio = bytes as f64 / estimate;
    eprintln!("meshes: estimate {estimate:.0} B, written {bytes} B, ratio {ratio:.2}");
    assert!(
        (0.7..=1.3).contains(&ratio),
        "wrote {bytes} B, estimated {estimate:.0} B ({ratio:.2})"
    );
}
