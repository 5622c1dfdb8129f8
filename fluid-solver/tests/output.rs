//! Output files: the VTU's appended blocks match its header, the PVD lists the frames, and a
//! standalone run writes frames and a probe CSV with one column per probe.

use fluid_solver::particles::Particles;
use fluid_solver::vtu::write_vtu;
use fluid_solver::Kind;
use schemas::case::Case;
use schemas::pvd::Collection;
use std::path::{Path, PathBuf};

fn scratch_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("fluid-output-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir
}

#[test]
fn vtu_blocks_match_the_header() {
    let mut p = Particles::default();
    p.push([0.0, 0.0, 0.0], Kind::Fluid);
    p.push([1.0, 0.0, 0.0], Kind::Wall);
    p.push([2.0, 0.0, 0.0], Kind::Dummy); // dummies are left out of frames
    p.pressure[0] = 12.5;
    let path = scratch_dir("vtu").join("frame.vtu");
    write_vtu(&path, &p, &mut schemas::participant::DiscardProgress).unwrap_or_else(|e| panic!("{e}"));
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{e}"));
    let split = bytes
        .windows(2)
        .position(|w| w == b"\n_")
        .unwrap_or_else(|| panic!("no appended data"))
        + 2;
    let header = String::from_utf8_lossy(&bytes[..split]);
    assert!(header.contains("NumberOfPoints=\"2\""), "{header}");
    let offsets: Vec<usize> = header
        .split("offset=\"")
        .skip(1)
        .filter_map(|s| s.split('"').next()?.parse().ok())
        .collect();
    // velocity, pressure, kind, id, points, connectivity, offsets, types
    let sizes = [2 * 3 * 8, 2 * 8, 2, 2 * 4, 2 * 3 * 8, 2 * 8, 2 * 8, 2];
    assert_eq!(offsets.len(), sizes.len());
    for (off, size) in offsets.iter().zip(sizes) {
        let at = split + off;
        let mut len = [0u8; 8];
        len.copy_from_slice(&bytes[at..at + 8]);
        assert_eq!(u64::from_le_bytes(len) as usize, size);
    }
    let mut pressure = [0u8; 8];
    pressure.copy_from_slice(&bytes[split + offsets[1] + 8..split + offsets[1] + 16]);
    assert_eq!(f64::from_le_bytes(pressure), 12.5);
    assert!(String::from_utf8_lossy(&bytes[bytes.len() - 30..]).contains("</VTKFile>"));

    let mut series = Collection::new(path.with_file_name("run.pvd"));
    series.add(0.0, "frame.vtu").unwrap_or_else(|e| panic!("{e}"));
    series.add(0.5, "frame.vtu").unwrap_or_else(|e| panic!("{e}"));
    let pvd = std::fs::read_to_string(path.with_file_name("run.pvd")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(pvd.matches("<DataSet").count(), 2);
    assert!(pvd.contains("timestep=\"0.5\""));
}

#[test]
fn standalone_run_writes_frames_and_probes() {
    let text = r#"
[case]
name = "tiny-break"
end_time = 0.1

[fluid.water]
spacing = 0.02
time_step = 8.0e-4
viscosity_term = false
output_interval = 0.05
probe_interval = 0.01
tank = { min = [0.0, 0.0, 0.0], max = [0.4, 0.08, 0.3] }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.1, 0.08, 0.2]

[[fluid.water.gate]]
min = [0.1, 0.0, 0.0]
max = [0.14, 0.08, 0.2]

[[fluid.water.probe]]
name = "front"
kind = "surge-front"

[[fluid.water.probe]]
name = "h"
kind = "water-height"
position = [0.01, 0.04]

[[fluid.water.probe]]
name = "p"
kind = "pressure"
position = [0.01, 0.04, 0.01]
"#;
    let case = Case::parse(Path::new("tiny.toml"), text.to_string()).unwrap_or_else(|e| panic!("{e}"));
    let out = scratch_dir("run");
    let summary = fluid_solver::run::run_case(&case, &out, false).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(summary.frames, 3);
    assert_eq!(summary.fluid_particles, 5 * 4 * 10);
    let csv = std::fs::read_to_string(out.join("water_probes.csv")).unwrap_or_else(|e| panic!("{e}"));
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').filter_map(|v| v.parse().ok()).collect())
        .collect();
    assert_eq!(csv.lines().next(), Some("time,front,h,p,removed"));
    assert_eq!(rows.len(), 11);
    // At t = 0 the front is the column's face and the gauge sees the column's height.
    assert!(
        (rows[0][1] - 0.1).abs() < 1e-12 && (rows[0][2] - 0.2).abs() < 1e-12,
        "{:?}",
        rows[0]
    );
    // The front advances once the gate is gone.
    assert!(rows[10][1] > 0.15, "{:?}", rows[10]);
    // Water presses on the floor near the left wall once it has settled onto it.
    assert!(rows[10][3] > 0.0, "{:?}", rows[10]);
    for k in 0..3 {
        assert!(out.join(format!("water_{k:05}.vtu")).is_file());
    }
}
