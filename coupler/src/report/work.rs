//! The work a run did, read from its case and its outputs: coupling windows (or solver steps of
//! a one-solver case), fluid particle-steps, and solver sweeps per window from the ledger.

use schemas::case::Case;
use std::path::Path;

/// What a run did.
#[derive(Debug, Clone, Copy, Default)]
pub struct Work {
    pub steps: f64,
    pub particle_steps: f64,
    pub sweeps: f64,
}

/// The work of the run of `case` whose output folder is `out`.
pub fn work(case: &Case, out: &Path) -> Work {
    let end = case.info.end_time;
    let mut particle_steps = 0.0;
    for (name, fluid) in &case.fluid {
        let dir = if case.coupling.is_some() {
            out.join(name)
        } else {
            out.to_path_buf()
        };
        let particles = first_frame_points(&dir, name).unwrap_or(0) as f64;
        particle_steps += particles * (end / fluid.time_step).ceil();
    }
    match case.coupling {
        Some(_) => {
            let (windows, sweeps) = ledger_sweeps(&out.join("ledger.csv"));
            Work {
                steps: windows,
                particle_steps,
                sweeps: if windows > 0.0 { sweeps / windows } else { 0.0 },
            }
        }
        None => {
            let step = case
                .fluid
                .values()
                .map(|f| f.time_step)
                .chain(
                    case.structure
                        .values()
                        .filter_map(|s| s.frame.as_ref().map(|f| f.time_step).or(s.max_step)),
                )
                .next()
                .unwrap_or(end);
            Work {
                steps: (end / step).ceil(),
                particle_steps,
                sweeps: 0.0,
            }
        }
    }
}

/// Particles in a fluid's first VTU frame (`NAME_00000.vtu`, `NumberOfPoints`), or in its
/// pieces when the fluid ran on MPI ranks (`NAME_00000_rRRRR.vtu`).
fn first_frame_points(dir: &Path, name: &str) -> Option<u64> {
    if let Some(n) = vtu_points(&dir.join(format!("{name}_00000.vtu"))) {
        return Some(n);
    }
    let pieces: Vec<u64> = (0..)
        .map_while(|r| vtu_points(&dir.join(format!("{name}_00000_r{r:04}.vtu"))))
        .collect();
    (!pieces.is_empty()).then(|| pieces.iter().sum())
}

/// `NumberOfPoints` of a VTU file.
fn vtu_points(path: &Path) -> Option<u64> {
    use std::io::Read;
    let mut head = [0u8; 4096];
    let mut file = std::fs::File::open(path).ok()?;
    let n = file.read(&mut head).ok()?;
    let text = String::from_utf8_lossy(&head[..n]);
    let at = text.find("NumberOfPoints=\"")? + "NumberOfPoints=\"".len();
    text[at..].split('"').next()?.parse().ok()
}

/// (windows, sweeps) summed over the ledger's rows.
fn ledger_sweeps(path: &Path) -> (f64, f64) {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let Some(col) = header.iter().position(|h| *h == "iterations") else {
        return (0.0, 0.0);
    };
    lines.fold((0.0, 0.0), |(w, s), l| {
        let it = l
            .split(',')
            .nth(col)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0);
        (w + 1.0, s + it)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_frames_particles_are_read_from_the_file_or_summed_over_its_pieces() {
        let dir = std::env::temp_dir().join(format!("coupler-work-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        let head =
            |n: u64| format!("<VTKFile><UnstructuredGrid><Piece NumberOfPoints=\"{n}\" NumberOfCells=\"0\">");
        std::fs::write(dir.join("one_00000.vtu"), head(120)).unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(dir.join("ranked_00000_r0000.vtu"), head(70)).unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(dir.join("ranked_00000_r0001.vtu"), head(50)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(first_frame_points(&dir, "one"), Some(120));
        assert_eq!(
            first_frame_points(&dir, "ranked"),
            Some(120),
            "the pieces of a run on ranks"
        );
        assert_eq!(first_frame_points(&dir, "none"), None);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
