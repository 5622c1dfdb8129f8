//! Before a run starts: how many windows it has and about how much it will write, from the case
//! alone, printed, and a run refused when that is more than the disk has free or more than
//! `--max-output` allows.
//!
//! An estimate, not a bound: each output is modelled from its byte counts measured on the shipped
//! cases (2026-11-29, the 2-core machine, release build); the table in docs/guide/outputs.md
//! ("How large a run is") compares it with what every shipped case wrote: 0.79–1.16 of it.
//! - fluid frames: `floor(end_time / output_interval) + 1` VTU files of 78 bytes per written
//!   particle (`fluid-solver/src/output/vtu.rs`); written particles are the blocks' water, the
//!   walls, the bodies (a mesh body: its volume in cells), an inflow's strip at full level, the two
//!   wall layers next to the tank and the two outer layers of the mesh solids' and terrains' skins
//!   (their surface area in cells, a plane's slope counted, a grid's not); a `.pvd` line per frame;
//!   a solver running alone also writes one at `end_time`;
//! - free-surface meshes (`surface_mesh`): per frame 700 bytes per Δs² of the water blocks'
//!   surface area (tutorial: 918 kB a frame over 0.5 s for 1300 Δs²; floating box 734 B/Δs² in
//!   its first frame);
//! - probes: a row per `probe_interval` of 13 bytes plus 13 per probe (`{:.6e}` columns);
//! - the recording: per solver sweep, per participant a request and an answer of 178 bytes of
//!   framing (names, wall times, checksum) plus 5 per sample, and 8 bytes per sample and interface
//!   value (a fluid body 25 values, a structure body 19, point mass 9, frame node 15); fitted to
//!   the oscillator (1362 B a sweep) and the floating box (1083 B a window). An implicit window
//!   is counted as [`TYPICAL_SWEEPS`] sweeps (at most `max_iterations`): measured 2.5 on the
//!   tutorial, 5.0 on the oscillator;
//! - the ledger: per window about 30 bytes then 19 per `{:.12e}` number, 4 per participant and
//!   the net force's 3; `interface_energy.csv` about 100 bytes per window;
//! - structure histories: a row per history interval (and one at 0) of 53 bytes per point mass,
//!   165 per free body, 60 per body held by a support (rigid-washout: its initial pose until the
//!   release), 145 per frame node;
//! - a frame's outputs per history row: a snapshot (1500 bytes of tags, 98 per node and per cell
//!   value block: nodes + 3 per member; plastic collapse: 3.2 kB), a `.pvd` line, the section
//!   forces (78 bytes per element end, 4 per member) and an `energy.csv` row (125 bytes);
//! - checkpoints (`coupling.checkpoint_interval`, once the run passes one): the last two, each
//!   87 bytes per fluid particle, outer wall layers included (tutorial: 1.92 MB for 21 919), and
//!   the coupler's, about 10 kB.

use crate::error::CouplerError;
use schemas::case::coupling::Scheme;
use schemas::case::{Case, FluidConfig};
use std::path::Path;

/// Bytes per written particle in a VTU frame.
const VTU_BYTES_PER_PARTICLE: f64 = 78.0;

/// Bytes of a free-surface mesh per frame and Δs² of the water blocks' surface area.
const SURFACE_BYTES_PER_DS2: f64 = 700.0;

/// Bytes of a `.pvd` line (one per frame or snapshot).
const PVD_LINE_BYTES: f64 = 70.0;

/// Bytes per fluid particle in a checkpoint.
const CHECKPOINT_BYTES_PER_PARTICLE: f64 = 87.0;

/// Bytes of the coupler's part of a checkpoint (measured: 8–10 kB).
const CHECKPOINT_COUPLER_BYTES: f64 = 10_000.0;

/// Bytes per window of `interface_energy.csv`.
const INTERFACE_ENERGY_BYTES_PER_WINDOW: f64 = 100.0;

/// Sweeps counted per implicit window (at most `max_iterations`): measured 2.5 (tutorial, 1256
/// sweeps in 500 windows) to 5.0 (oscillator, tolerance 1e-10: 498 in 100).
pub const TYPICAL_SWEEPS: u32 = 5;

/// What a run will write, about.
#[derive(Debug, Clone, Default)]
pub struct Estimate {
    /// Coupling windows (none for a solver run alone).
    pub windows: Option<f64>,
    /// Sweeps counted per window: 1, or [`TYPICAL_SWEEPS`] for an implicit scheme.
    pub sweeps: f64,
    /// Fluid VTU frames: (frames, written particles per frame, bytes).
    pub fluid: Vec<(f64, f64, f64)>,
    /// Free-surface meshes.
    pub surface_meshes: f64,
    /// Probe CSVs.
    pub probes: f64,
    pub recording: f64,
    /// `ledger.csv` and `interface_energy.csv`.
    pub ledger: f64,
    /// Structure CSV histories and frame outputs.
    pub histories: f64,
    /// The checkpoints kept at once ([`crate::checkpoint::KEEP`]).
    pub checkpoints: f64,
}

/// Rows of an output every `interval` up to `end`, the one at 0 included; a solver running
/// `alone` also writes one at `end`, a coupled one only at the window ends at or after each
/// multiple.
fn rows(end: f64, interval: f64, alone: bool) -> f64 {
    let ratio = end / interval;
    1.0 + if alone {
        (ratio - 1e-9).ceil().max(0.0)
    } else {
        (ratio + 1e-9).floor()
    }
}

impl Estimate {
    /// The estimate for `case`.
    pub fn of(case: &Case) -> Estimate {
        let end = case.info.end_time;
        let alone = case.coupling.is_none();
        let mut e = Estimate {
            sweeps: 1.0,
            ..Estimate::default()
        };
        for f in case.fluid.values() {
            let frames = rows(end, f.output_interval, alone);
            let particles = written_particles(f);
            e.fluid.push((
                frames,
                particles,
                frames * (particles * VTU_BYTES_PER_PARTICLE + PVD_LINE_BYTES),
            ));
            if f.surface_mesh {
                let area = surface_area(&f.block);
                let per_frame = SURFACE_BYTES_PER_DS2 * area / (f.spacing * f.spacing) + PVD_LINE_BYTES;
                e.surface_meshes += frames * per_frame;
            }
            let interval = f.probe_interval.unwrap_or(f.output_interval);
            e.probes += rows(end, interval, alone) * (13.0 + 13.0 * f.probe.len() as f64);
        }
        for s in case.structure.values() {
            let Some(h) = &s.history else { continue };
            let n = rows(end, h.interval, alone);
            let held = |b: &str| s.support.iter().any(|x| x.body == b);
            let bodies: f64 = h.bodies.iter().map(|b| if held(b) { 60.0 } else { 165.0 }).sum();
            e.histories += n * (53.0 * h.points.len() as f64 + bodies + 145.0 * h.nodes.len() as f64);
            if let Some(frame) = &s.frame {
                let (nodes, members) = (frame.node.len() as f64, frame.member.len() as f64);
                let snapshots = match (h.vtu, h.vtu_interval) {
                    (false, _) => 0.0,
                    (true, Some(i)) => rows(end, i.max(h.interval), alone),
                    (true, None) => n,
                };
                let snapshot = 1500.0 + 98.0 * (nodes + 3.0 * members) + PVD_LINE_BYTES;
                let sections = if h.section_forces {
                    78.0 * 4.0 * members
                } else {
                    0.0
                };
                e.histories += snapshots * snapshot + n * (sections + 125.0);
            }
        }
        if let Some(c) = &case.coupling {
            let windows = (end / c.window).ceil();
            let samples = f64::from(c.samples.max(1));
            let values: usize = case
                .fluid
                .values()
                .map(|f| 25 * f.body.len())
                .chain(case.structure.values().map(|s| {
                    19 * s.body.len()
                        + 9 * s.point_mass.len()
                        + 15 * s.frame.as_ref().map_or(0, |f| f.node.len())
                }))
                .sum();
            let participants = case.participants().len() as f64;
            if c.scheme == Scheme::Implicit {
                e.sweeps = f64::from(TYPICAL_SWEEPS.min(c.max_iterations.max(1)));
            }
            let per_sweep = participants * 2.0 * (178.0 + samples * 5.0) + samples * 8.0 * values as f64;
            e.windows = Some(windows);
            e.recording = windows * e.sweeps * per_sweep;
            e.ledger = windows * (30.0 + 19.0 * (4.0 * participants + 3.0))
                + windows * INTERFACE_ENERGY_BYTES_PER_WINDOW;
            if let Some(interval) = c.checkpoint_interval {
                let kept = (crate::checkpoint::KEEP as f64).min((end / interval + 1e-9).floor());
                let particles: f64 = case.fluid.values().map(all_particles).sum();
                e.checkpoints = kept * (CHECKPOINT_COUPLER_BYTES + particles * CHECKPOINT_BYTES_PER_PARTICLE);
            }
        }
        e
    }

    /// Bytes in all.
    pub fn total(&self) -> f64 {
        self.fluid.iter().map(|f| f.2).sum::<f64>()
            + self.surface_meshes
            + self.probes
            + self.recording
            + self.ledger
            + self.histories
            + self.checkpoints
    }

    /// One line for the user: windows, total and its parts.
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        for (frames, particles, bytes) in &self.fluid {
            parts.push(format!(
                "fluid frames {} ({} × {} particles × 78 B)",
                bytes_text(*bytes),
                count_text(*frames),
                count_text(*particles),
            ));
        }
        if self.surface_meshes > 0.0 {
            parts.push(format!("free-surface meshes {}", bytes_text(self.surface_meshes)));
        }
        if self.probes > 0.0 {
            parts.push(format!("probes {}", bytes_text(self.probes)));
        }
        if self.windows.is_some() {
            let sweeps = if self.sweeps > 1.0 {
                format!(", assuming {} sweeps per window", self.sweeps)
            } else {
                String::new()
            };
            parts.push(format!("recording {}{sweeps}", bytes_text(self.recording)));
            parts.push(format!("ledger and interface energy {}", bytes_text(self.ledger)));
        }
        if self.checkpoints > 0.0 {
            parts.push(format!("checkpoints {}", bytes_text(self.checkpoints)));
        }
        if self.histories > 0.0 {
            parts.push(format!("structure outputs {}", bytes_text(self.histories)));
        }
        let windows = self
            .windows
            .map(|w| format!("{} windows; ", count_text(w)))
            .unwrap_or_default();
        format!(
            "{windows}about {} of output ({})",
            bytes_text(self.total()),
            parts.join(", ")
        )
    }
    /// Refuses a run whose estimate exceeds `max_output` bytes or the free space where `out` is.
    pub fn check(&self, out: &Path, max_output: u64) -> Result<(), CouplerError> {
        let total = self.total();
        if total > max_output as f64 {
            return Err(CouplerError::Usage(format!(
                "the run is too large: {}; that is above --max-output {}: raise --max-output if it is meant, or \
                 write less (a longer coupling.window or output_interval, a shorter case.end_time)",
                self.describe(),
                bytes_text(max_output as f64)
            )));
        }
        if let Some(free) = free_space(out) {
            if total > free as f64 {
                return Err(CouplerError::Usage(format!(
                    "the run is too large: {}; only {} is free on the disk of {}",
                    self.describe(),
                    bytes_text(free as f64),
                    out.display()
                )));
            }
        }
        Ok(())
    }
}

/// Particles a fluid frame holds: the blocks' water, the bodies and the two wall layers next to
/// the tank (lattice counts, `round(extent / Δs)` per axis as the fluid solver lays them out).
fn written_particles(f: &FluidConfig) -> f64 {
    particles(f, 2.0_f64.min(f64::from(f.wall_layers)))
}

/// Particles a checkpoint holds: as [`written_particles`], with every wall layer.
fn all_particles(f: &FluidConfig) -> f64 {
    particles(f, f64::from(f.wall_layers))
}

/// The blocks' water, the bodies and `layers` wall layers around the tank.
fn particles(f: &FluidConfig, layers: f64) -> f64 {
    let ds = f.spacing;
    let count = |min: [f64; 3], max: [f64; 3]| -> f64 {
        (0..3)
            .map(|a| ((max[a] - min[a]) / ds).round().max(0.0))
            .product()
    };
    let water: f64 = f.block.iter().map(|b| count(b.min, b.max)).sum();
    let walls: f64 = f.wall.iter().map(|w| count(w.min, w.max)).sum();
    // an inflow's strip at its full level (bridge-washout-small: frames grow from 11 935 to
    // 15 303 particles over 7.2 s; the strip at full level accounts for a third of that)
    let inflow = f.inflow.as_ref().map_or(0.0, |i| {
        let span = i.span.unwrap_or([f.tank.min[1], f.tank.max[1]]);
        let floor = f.tank.min[2];
        count(
            [i.plane - i.strip_length, span[0], floor],
            [i.plane, span[1], floor + i.law().map_or(0.0, |l| l.max_level())],
        )
    });
    let bodies: f64 = f
        .body
        .iter()
        .map(|b| match (b.min, b.max, b.placed.get()) {
            (Some(min), Some(max), _) => count(min, max),
            // every site inside the mesh: its volume in cells
            (_, _, Some(mesh)) => mesh.signed_volume().abs() / ds.powi(3),
            _ => 0.0,
        })
        .sum();
    // the skins of mesh solids and terrains, `layers` deep: their surface in cells, times layers
    let skins: f64 = f
        .solid
        .iter()
        .filter_map(|s| s.placed.get())
        .map(|mesh| {
            (0..mesh.triangles.len())
                .map(|t| mesh.triangle_area(t))
                .sum::<f64>()
        })
        .chain(f.terrain.iter().map(|t| terrain_area(t, f)))
        .map(|area| area / (ds * ds) * layers)
        .sum();
    let layers = layers * ds;
    let t = &f.tank;
    let outer_min = [t.min[0] - layers, t.min[1] - layers, t.min[2] - layers];
    let outer_max = [
        t.max[0] + layers,
        t.max[1] + layers,
        t.max[2] + if t.lid { layers } else { 0.0 },
    ];
    let tank_walls = count(outer_min, outer_max) - count(t.min, t.max);
    water + walls + inflow + bodies + skins + tank_walls.max(0.0)
}

/// The area of a terrain's surface inside the tank (or its region): a plane's plan area over the
/// cosine of its slope, a grid's plan area (its slopes left out).
fn terrain_area(t: &schemas::case::fluid::TerrainConfig, f: &FluidConfig) -> f64 {
    let (mut lo, mut hi) = ([f.tank.min[0], f.tank.min[1]], [f.tank.max[0], f.tank.max[1]]);
    if let Some(r) = &t.region {
        for a in 0..2 {
            lo[a] = lo[a].max(r.min[a]);
            hi[a] = hi[a].min(r.max[a]);
        }
    }
    let plan = (hi[0] - lo[0]).max(0.0) * (hi[1] - lo[1]).max(0.0);
    match &t.plane {
        Some(p) => {
            let n = p.normal;
            plan * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt() / n[2].abs()
        }
        None => plan,
    }
}

/// Surface area [m²] of the union of `blocks`: their faces less twice the faces two blocks share
/// (blocks that touch; overlaps are not looked for).
fn surface_area(blocks: &[schemas::case::fluid::Aabb]) -> f64 {
    let extent = |b: &schemas::case::fluid::Aabb, a: usize| (b.max[a] - b.min[a]).max(0.0);
    let faces: f64 = blocks
        .iter()
        .map(|b| {
            2.0 * (extent(b, 0) * extent(b, 1) + extent(b, 1) * extent(b, 2) + extent(b, 2) * extent(b, 0))
        })
        .sum();
    let mut shared = 0.0;
    for (i, a) in blocks.iter().enumerate() {
        for b in &blocks[i + 1..] {
            for axis in 0..3 {
                let touch =
                    (a.max[axis] - b.min[axis]).abs() < 1e-9 || (b.max[axis] - a.min[axis]).abs() < 1e-9;
                if touch {
                    let overlap = |k: usize| (a.max[k].min(b.max[k]) - a.min[k].max(b.min[k])).max(0.0);
                    shared += overlap((axis + 1) % 3) * overlap((axis + 2) % 3);
                }
            }
        }
    }
    (faces - 2.0 * shared).max(0.0)
}

/// Free bytes for an unprivileged user on the file system that holds `dir` (or its nearest
/// existing parent).
fn free_space(dir: &Path) -> Option<u64> {
    let fs = crate::out_folder::file_system(crate::out_folder::nearest_existing(dir))?;
    Some(fs.f_bavail * fs.f_frsize)
}

/// "668 MB", "3.1 TB", "1.0e+21 B": SI units up to petabytes, then powers of ten.
pub fn bytes_text(b: f64) -> String {
    const UNITS: [(&str, f64); 5] = [("PB", 1e15), ("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)];
    if !b.is_finite() || b >= 1e18 {
        return format!("{b:.1e} B");
    }
    for (unit, size) in UNITS {
        if b >= size {
            let v = b / size;
            return if v >= 100.0 {
                format!("{v:.0} {unit}")
            } else {
                format!("{v:.1} {unit}")
            };
        }
    }
    format!("{b:.0} B")
}

/// A count as a person reads it: `7000`, `1.0e12`.
fn count_text(n: f64) -> String {
    if n < 1e9 {
        format!("{n:.0}")
    } else {
        format!("{n:.1e}")
    }
}

/// Parses a size: bytes, or a number with k, M, G, T (powers of 1000; a trailing `B` is allowed).
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim().trim_end_matches(['B', 'b']);
    let (number, scale) = match t.chars().last() {
        Some('k' | 'K') => (&t[..t.len() - 1], 1e3),
        Some('M') => (&t[..t.len() - 1], 1e6),
        Some('G') => (&t[..t.len() - 1], 1e9),
        Some('T') => (&t[..t.len() - 1], 1e12),
        _ => (t, 1.0),
    };
    match number.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok((v * scale) as u64),
        _ => Err(format!("expected a size such as 500M, 20G or 2T, got `{s}`")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_parsed_and_printed_as_people_write_them() {
        assert_eq!(parse_size("20G"), Ok(20_000_000_000));
        assert_eq!(parse_size("500MB"), Ok(500_000_000));
        assert_eq!(parse_size("1234"), Ok(1234));
        assert!(parse_size("lots").is_err());
        assert_eq!(bytes_text(668e6), "668 MB");
        assert_eq!(bytes_text(1.5e3), "1.5 kB");
        assert_eq!(bytes_text(3e300), "3.0e300 B");
        assert_eq!(count_text(7000.0), "7000");
        assert_eq!(count_text(1e302), "1.0e302");
    }

    #[test]
    fn blocks_that_touch_share_no_surface() {
        use schemas::case::fluid::Aabb;
        let block = |x0: f64, x1: f64| Aabb {
            min: [x0, 0.0, 0.0],
            max: [x1, 1.0, 1.0],
        };
        // one unit cube: 6 m²; two side by side: a 2 × 1 × 1 box, 10 m²
        assert!((surface_area(&[block(0.0, 1.0)]) - 6.0).abs() < 1e-12);
        assert!((surface_area(&[block(0.0, 1.0), block(1.0, 2.0)]) - 10.0).abs() < 1e-12);
    }
}
