//! Free-surface meshes (issue 5): a lattice sphere and a lattice box of fluid particles give a
//! closed surface holding the particles' volume `N Δs³`; the VTP file parses back.
//!
//! Tolerances: volume and area within 5 %, mean radius within half a spacing — the acceptance
//! criteria of issue 5. What eats into them: the kernel (radius r = 2 Δs) rounds the box's edges
//! and corners (measured −4.0 % of the area of a 32 × 24 × 16 box), and on a sphere moves the
//! iso-surface inward by about σ²/R (σ² = r²/15 ≈ 0.27 Δs², the kernel's second moment per axis):
//! 0.033 Δs, −1.25 % of the volume at R = 8 Δs (measured −1.6 %).

use fluid_solver::particles::Particles;
use fluid_solver::surface_mesh::{fluid_surface, TriangleMesh};
use fluid_solver::vtp::{write_vtp, SurfaceFrames};
use fluid_solver::Kind;
use std::collections::HashMap;
use std::path::PathBuf;

const SPACING: f64 = 0.01;

fn scratch_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("fluid-surface-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir
}

/// Lattice sites `corner + k Δs` within `radius` of `centre`, as fluid particles.
fn lattice_sphere(centre: [f64; 3], radius: f64) -> Particles {
    let mut p = Particles::default();
    let reach = (radius / SPACING).ceil() as i32 + 1;
    for i in -reach..=reach {
        for j in -reach..=reach {
            for k in -reach..=reach {
                let d = [i, j, k].map(|c| f64::from(c) * SPACING);
                if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() <= radius {
                    p.push([0, 1, 2].map(|a| centre[a] + d[a]), Kind::Fluid);
                }
            }
        }
    }
    p
}

/// Every undirected edge is shared by exactly two triangles, which run it in opposite directions.
fn assert_closed_and_oriented(mesh: &TriangleMesh) {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for t in &mesh.triangles {
        for e in 0..3 {
            *directed.entry((t[e], t[(e + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        assert_eq!(n, 1, "edge {a}→{b} is run {n} times");
        assert_eq!(directed.get(&(b, a)), Some(&1), "edge {a}–{b} has one triangle");
    }
}

/// Σ x₀·(x₁ × x₂) / 6: the enclosed volume of a closed, outward-wound mesh.
fn enclosed_volume(mesh: &TriangleMesh) -> f64 {
    let v = &mesh.vertices;
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| v[i as usize]);
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum::<f64>()
        / 6.0
}

fn area(mesh: &TriangleMesh) -> f64 {
    let v = &mesh.vertices;
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| v[i as usize]);
            let (u, w) = ([0, 1, 2].map(|k| b[k] - a[k]), [0, 1, 2].map(|k| c[k] - a[k]));
            let n = [
                u[1] * w[2] - u[2] * w[1],
                u[2] * w[0] - u[0] * w[2],
                u[0] * w[1] - u[1] * w[0],
            ];
            0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
        })
        .sum()
}

#[test]
fn lattice_sphere_gives_a_closed_surface_with_its_volume_and_radius() {
    let radius = 8.0 * SPACING;
    // Off the sampling grid on purpose.
    let centre = [0.1234, -0.0371, 0.2519];
    let p = lattice_sphere(centre, radius);
    let mesh = fluid_surface(&p, SPACING);
    assert!(mesh.triangles.len() > 1000, "{} triangles", mesh.triangles.len());
    assert_closed_and_oriented(&mesh);

    let particles_volume = p.len() as f64 * SPACING.powi(3);
    let volume = enclosed_volume(&mesh);
    let rel = (volume - particles_volume) / particles_volume;
    assert!(
        rel.abs() < 0.05,
        "volume {volume:.4e} vs N Δs³ {particles_volume:.4e} ({rel:+.3})"
    );

    let mean_radius = mesh
        .vertices
        .iter()
        .map(|v| (0..3).map(|a| (v[a] - centre[a]).powi(2)).sum::<f64>().sqrt())
        .sum::<f64>()
        / mesh.vertices.len() as f64;
    assert!(
        (mean_radius - radius).abs() < 0.5 * SPACING,
        "mean radius {mean_radius:.5} vs {radius:.5}"
    );
    // Normals point outward.
    let outward = mesh
        .vertices
        .iter()
        .zip(&mesh.normals)
        .filter(|(v, n)| (0..3).map(|a| (v[a] - centre[a]) * f64::from(n[a])).sum::<f64>() > 0.0)
        .count();
    assert_eq!(outward, mesh.vertices.len());
    println!(
        "sphere: {} particles, {} triangles, volume {rel:+.4}, mean radius {:+.4} Δs",
        p.len(),
        mesh.triangles.len(),
        (mean_radius - radius) / SPACING
    );
}

#[test]
fn lattice_box_gives_the_box_area() {
    let sites = [32, 24, 16];
    let corner = [-0.3012, 0.0047, 1.0];
    let mut p = Particles::default();
    for k in 0..sites[2] {
        for j in 0..sites[1] {
            for i in 0..sites[0] {
                let s = [i, j, k].map(|c| f64::from(c) * SPACING);
                p.push([0, 1, 2].map(|a| corner[a] + s[a]), Kind::Fluid);
            }
        }
    }
    // Walls beside the water are not part of the fluid's surface.
    p.push([corner[0] - 3.0 * SPACING, corner[1], corner[2]], Kind::Wall);
    let mesh = fluid_surface(&p, SPACING);
    assert_closed_and_oriented(&mesh);
    let [a, b, c] = sites.map(|n| f64::from(n) * SPACING);
    let box_area = 2.0 * (a * b + b * c + c * a);
    let rel = (area(&mesh) - box_area) / box_area;
    assert!(
        rel.abs() < 0.05,
        "area {:.5} vs box {box_area:.5} ({rel:+.3})",
        area(&mesh)
    );
    let rel_volume = enclosed_volume(&mesh) / (a * b * c) - 1.0;
    assert!(rel_volume.abs() < 0.05, "volume {rel_volume:+.3}");
    println!("box: area {rel:+.4}, volume {rel_volume:+.4}");
}

/// The appended blocks of a VTP written by `write_vtp`, checked against its header.
struct ParsedVtp {
    points: Vec<[f64; 3]>,
    triangles: Vec<[i64; 3]>,
}

fn read_vtp(path: &std::path::Path) -> ParsedVtp {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let split = bytes
        .windows(2)
        .position(|w| w == b"\n_")
        .unwrap_or_else(|| panic!("no appended data"))
        + 2;
    let header = String::from_utf8_lossy(&bytes[..split]).into_owned();
    assert!(header.contains("type=\"PolyData\""), "{header}");
    let attr = |name: &str| -> usize {
        let at = header
            .find(&format!("{name}=\""))
            .unwrap_or_else(|| panic!("no {name}"));
        header[at + name.len() + 2..]
            .split('"')
            .next()
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| panic!("bad {name}"))
    };
    let (n, m) = (attr("NumberOfPoints"), attr("NumberOfPolys"));
    let offsets: Vec<usize> = header
        .split("offset=\"")
        .skip(1)
        .filter_map(|s| s.split('"').next()?.parse().ok())
        .collect();
    let block = |k: usize| -> &[u8] {
        let at = split + offsets[k];
        let mut len = [0u8; 8];
        len.copy_from_slice(&bytes[at..at + 8]);
        &bytes[at + 8..at + 8 + u64::from_le_bytes(len) as usize]
    };
    let f64s = |b: &[u8]| -> Vec<f64> {
        b.chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or_else(|_| panic!("8 bytes"))))
            .collect()
    };
    let i64s = |b: &[u8]| -> Vec<i64> {
        b.chunks_exact(8)
            .map(|c| i64::from_le_bytes(c.try_into().unwrap_or_else(|_| panic!("8 bytes"))))
            .collect()
    };
    // normals, points, connectivity, offsets
    assert_eq!(offsets.len(), 4);
    assert_eq!(block(0).len(), n * 3 * 4);
    let points = f64s(block(1));
    let connectivity = i64s(block(2));
    let polys = i64s(block(3));
    assert_eq!(points.len(), 3 * n);
    assert_eq!(connectivity.len(), 3 * m);
    assert_eq!(polys, (1..=m as i64).map(|t| 3 * t).collect::<Vec<_>>());
    assert!(connectivity.iter().all(|&v| v >= 0 && (v as usize) < n));
    assert!(String::from_utf8_lossy(&bytes[bytes.len() - 30..]).contains("</VTKFile>"));
    ParsedVtp {
        points: points.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
        triangles: connectivity.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
    }
}

#[test]
fn written_vtp_parses_back_to_the_mesh() {
    let p = lattice_sphere([0.5, 0.5, 0.5], 4.0 * SPACING);
    let mesh = fluid_surface(&p, SPACING);
    let path = scratch_dir("vtp").join("sphere.vtp");
    write_vtp(&path, &mesh, &mut schemas::participant::DiscardProgress).unwrap_or_else(|e| panic!("{e}"));
    let back = read_vtp(&path);
    assert_eq!(back.points.len(), mesh.vertices.len());
    assert_eq!(back.triangles.len(), mesh.triangles.len());
    assert_eq!(back.points, mesh.vertices);
    assert!(back
        .triangles
        .iter()
        .zip(&mesh.triangles)
        .all(|(b, t)| *b == t.map(i64::from)));
}

#[test]
fn empty_fluid_writes_an_empty_valid_file_and_series() {
    let mut p = Particles::default();
    p.push([0.0; 3], Kind::Wall);
    let dir = scratch_dir("empty");
    let mut frames = SurfaceFrames::new(&dir, "tank", SPACING);
    frames
        .write(0, 0.0, &p, &mut schemas::participant::DiscardProgress)
        .unwrap_or_else(|(path, e)| panic!("{}: {e}", path.display()));
    frames
        .write(
            1,
            0.25,
            &Particles::default(),
            &mut schemas::participant::DiscardProgress,
        )
        .unwrap_or_else(|(path, e)| panic!("{}: {e}", path.display()));
    for k in 0..2 {
        let back = read_vtp(&dir.join(format!("tank_surface_{k:05}.vtp")));
        assert!(back.points.is_empty() && back.triangles.is_empty());
    }
    let pvd = std::fs::read_to_string(dir.join("tank_surface.pvd")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(pvd.matches("<DataSet").count(), 2);
    assert!(pvd.contains("file=\"tank_surface_00001.vtp\"") && pvd.contains("timestep=\"0.25\""));
}

#[test]
fn unwritable_folder_names_the_file() {
    let dir = scratch_dir("unwritable").join("missing-folder");
    let mut frames = SurfaceFrames::new(&dir, "tank", SPACING);
    let err = frames.write(
        0,
        0.0,
        &lattice_sphere([0.0; 3], 3.0 * SPACING),
        &mut schemas::participant::DiscardProgress,
    );
    match err {
        Err((path, _)) => assert!(path.ends_with("tank_surface_00000.vtp"), "{}", path.display()),
        Ok(()) => panic!("wrote into a folder that does not exist"),
    }
}

const TINY_BREAK: &str = r#"
[case]
name = "tiny-break"
end_time = 0.1

[fluid.water]
spacing = 0.02
time_step = 8.0e-4
viscosity_term = false
output_interval = 0.05
surface_mesh = true
tank = { min = [0.0, 0.0, 0.0], max = [0.4, 0.16, 0.3] }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.16, 0.16, 0.2]

[[fluid.water.gate]]
min = [0.16, 0.0, 0.0]
max = [0.2, 0.16, 0.2]
"#;

#[test]
fn standalone_run_and_participant_write_surface_frames() {
    let case = schemas::case::Case::parse(std::path::Path::new("tiny.toml"), TINY_BREAK.to_string())
        .unwrap_or_else(|e| panic!("{e}"));
    let out = scratch_dir("run");
    let summary = fluid_solver::run::run_case(&case, &out, false).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(summary.frames, 3);
    let pvd = std::fs::read_to_string(out.join("water_surface.pvd")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(pvd.matches("<DataSet").count(), 3);
    for k in 0..3 {
        let back = read_vtp(&out.join(format!("water_surface_{k:05}.vtp")));
        assert!(
            back.triangles.len() > 100,
            "frame {k}: {} triangles",
            back.triangles.len()
        );
    }
    // The first frame is the water column at rest: 8 × 8 × 10 particles, a closed box.
    let back = read_vtp(&out.join("water_surface_00000.vtp"));
    let mesh = TriangleMesh {
        vertices: back.points,
        normals: Vec::new(),
        triangles: back.triangles.iter().map(|t| t.map(|v| v as u32)).collect(),
    };
    assert_closed_and_oriented(&mesh);
    assert!(enclosed_volume(&mesh) > 0.0);

    let dir = scratch_dir("participant");
    fluid_solver::participant::FluidParticipant::from_case(&case, "water", Some(&dir))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        read_vtp(&dir.join("water_surface_00000.vtp")).triangles.len(),
        mesh.triangles.len()
    );
}

#[test]
fn particles_gone_astray_are_left_out() {
    let mut p = lattice_sphere([0.2, 0.3, 0.4], 3.0 * SPACING);
    let clean = fluid_surface(&p, SPACING);
    p.push([f64::NAN, 0.0, 0.0], Kind::Fluid);
    p.push([1.0e300, -1.0e300, 0.0], Kind::Fluid);
    p.push([0.0, f64::INFINITY, 0.0], Kind::Fluid);
    assert_eq!(fluid_surface(&p, SPACING), clean);
}
