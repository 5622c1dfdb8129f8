//! Before a run starts: how many windows it has and how much it will write — a lower bound, from
//! the case alone — printed, and a run refused when that is more than the disk has free or more
//! than `--max-output` allows.
//!
//! What is counted (each the least the run writes):
//! - fluid frames: `floor(end_time / output_interval) + 1` VTU files of 78 bytes per written particle
//!   (position and velocity as 3 × f64, pressure f64, kind u8, id u32, and a vertex cell: i64
//!   connectivity and offset, u8 type; `fluid-solver/src/vtu.rs`); written particles are the
//!   blocks' water, the bodies and the two wall layers next to the tank (the outer ones are not
//!   written); inflow particles and free-surface meshes come on top;
//! - the recording: per window and participant one request and one answer, each about 40 bytes
//!   plus, per sample, 8 bytes of time, 14 array lengths and 8 bytes per interface value (a fluid
//!   body: 25 values; a structure body 19, point mass 9, frame node 15); implicit windows repeat
//!   this per sweep (counted once);
//! - the ledger: per window about 30 bytes of window, time, iterations and residual, then 19 bytes
//!   per `{:.12e}` number: 4 per participant and the net force's 3.
//!
//! Measured on the floating box at Δs = 2 cm, 0.2 s (400 windows): VTU frames 876 kB each against
//! 875 kB estimated (11 215 particles; the first frame also holds the gate), ledger 97.5 kB against
//! 95.6 kB, recording 418 kB against 240 kB (the lower bound leaves out the handshake and message
//! framing).
//! - structure histories: one row per interval per file, at least 10 bytes per value;
//! - `interface_energy.csv` (coupled runs): about 100 bytes per window;
//! - checkpoints (`coupling.checkpoint_interval`): the last two are kept, each at least 86 bytes
//!   per written fluid particle (measured: 1.9 MB for 21 919 particles, docs/guide/checkpoint-resume.md) and the coupler's manifest, about 1 kB; the structure's are small.

use crate::error::CouplerError;
use schemas::case::{Case, FluidConfig};
use std::path::Path;

/// Bytes per written particle in a VTU frame.
const VTU_BYTES_PER_PARTICLE: f64 = 78.0;

/// Bytes per fluid particle in a checkpoint.
const CHECKPOINT_BYTES_PER_PARTICLE: f64 = 86.0;

/// Bytes of the coupler's manifest in a checkpoint (measured: about 1 kB).
const CHECKPOINT_MANIFEST_BYTES: f64 = 1000.0;

/// Bytes per window of `interface_energy.csv`.
const INTERFACE_ENERGY_BYTES_PER_WINDOW: f64 = 100.0;

/// What a run will write, at least.
#[derive(Debug, Clone, Default)]
pub struct Estimate {
    /// Coupling windows (none for a solver run alone).
    pub windows: Option<f64>,
    /// Fluid VTU frames: (frames, written particles per frame, bytes).
    pub fluid: Vec<(f64, f64, f64)>,
    pub surface_meshes: bool,
    pub recording: f64,
    /// `ledger.csv` and `interface_energy.csv`.
    pub ledger: f64,
    pub histories: f64,
    /// The checkpoints kept at once ([`crate::checkpoint::KEEP`]).
    pub checkpoints: f64,
}

impl Estimate {
    /// The estimate for `case`.
    pub fn of(case: &Case) -> Estimate {
        let end = case.info.end_time;
        let mut e = Estimate::default();
        for f in case.fluid.values() {
            let frames = (end / f.output_interval).floor() + 1.0;
            let particles = written_particles(f);
            e.fluid
                .push((frames, particles, frames * particles * VTU_BYTES_PER_PARTICLE));
            e.surface_meshes |= f.surface_mesh;
        }
        for s in case.structure.values() {
            if let Some(h) = &s.history {
                let rows = (end / h.interval).ceil();
                let values = 7 * h.points.len() + 15 * h.bodies.len() + 10 * h.nodes.len();
                e.histories += rows * values as f64 * 10.0;
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
            let per_window = participants * 2.0 * (40.0 + samples * 22.0) + samples * 8.0 * values as f64;
            e.windows = Some(windows);
            e.recording = windows * per_window;
            e.ledger = windows * (30.0 + 19.0 * (4.0 * participants + 3.0))
                + windows * INTERFACE_ENERGY_BYTES_PER_WINDOW;
            if c.checkpoint_interval.is_some() {
                let particles: f64 = e.fluid.iter().map(|f| f.1).sum();
                e.checkpoints = crate::checkpoint::KEEP as f64
                    * (CHECKPOINT_MANIFEST_BYTES + particles * CHECKPOINT_BYTES_PER_PARTICLE);
            }
        }
        e
    }

    /// Bytes in all.
    pub fn total(&self) -> f64 {
        self.fluid.iter().map(|f| f.2).sum::<f64>()
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
                "fluid frames {} ({} × {} particles × 78 B{})",
                bytes_text(*bytes),
                count_text(*frames),
                count_text(*particles),
                if self.surface_meshes {
                    ", plus free-surface meshes"
                } else {
                    ""
                }
            ));
        }
        if self.windows.is_some() {
            parts.push(format!("recording {}", bytes_text(self.recording)));
            parts.push(format!("ledger and interface energy {}", bytes_text(self.ledger)));
        }
        if self.checkpoints > 0.0 {
            parts.push(format!("checkpoints {}", bytes_text(self.checkpoints)));
        }
        if self.histories > 0.0 {
            parts.push(format!("structure histories {}", bytes_text(self.histories)));
        }
        let windows = self
            .windows
            .map(|w| format!("{} windows; ", count_text(w)))
            .unwrap_or_default();
        format!(
            "{windows}at least {} of output ({})",
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
    let ds = f.spacing;
    let count = |min: [f64; 3], max: [f64; 3]| -> f64 {
        (0..3)
            .map(|a| ((max[a] - min[a]) / ds).round().max(0.0))
            .product()
    };
    let water: f64 = f.block.iter().map(|b| count(b.min, b.max)).sum();
    let bodies: f64 = f.body.iter().map(|b| count(b.min, b.max)).sum();
    let layers = 2.0_f64.min(f64::from(f.wall_layers)) * ds;
    let t = &f.tank;
    let outer_min = [t.min[0] - layers, t.min[1] - layers, t.min[2] - layers];
    let outer_max = [
        t.max[0] + layers,
        t.max[1] + layers,
        t.max[2] + if t.lid { layers } else { 0.0 },
    ];
    let walls = count(outer_min, outer_max) - count(t.min, t.max);
    water + bodies + walls.max(0.0)
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
}
