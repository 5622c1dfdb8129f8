//! Probes declared in the case, sampled into one CSV: water height at a gauge, pressure at a
//! point, surge-front position.
//!
//! Droplets are left out of heights and fronts: a fluid particle counts only if its number
//! density is at least [`MIN_DENSITY_FRACTION`] of n0 (a lone particle in the air has far less).

use crate::emps::kernel::{weight, Kernel};
use crate::kind::{Kind, FLUID};
use crate::particles::Particles;
use schemas::case::fluid::{Aabb, ProbeConfig, ProbeKind};
use std::fs;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// Fraction of n0 below which a fluid particle is taken as spray, not as part of the water.
pub const MIN_DENSITY_FRACTION: f64 = 0.5;

/// Samples one probe on the current particles.
pub fn sample(probe: &ProbeConfig, p: &Particles, kernel: &Kernel, tank: &Aabb) -> f64 {
    let ds = kernel.spacing;
    let in_water = |i: usize| p.kind[i] == FLUID && p.number_density[i] >= MIN_DENSITY_FRACTION * kernel.n0;
    match probe.kind {
        ProbeKind::WaterHeight => {
            let (gx, gy) = (probe.position[0], probe.position[1]);
            (0..p.len())
                .filter(|&i| in_water(i))
                .filter(|&i| (p.x[i] - gx).powi(2) + (p.y[i] - gy).powi(2) <= ds * ds)
                .map(|i| p.z[i] + 0.5 * ds - tank.min[2])
                .fold(0.0, f64::max)
        }
        ProbeKind::Pressure => {
            let at = [probe.position[0], probe.position[1], probe.position[2]];
            let (mut pw, mut w) = (0.0, 0.0);
            for i in 0..p.len() {
                let k = p.kind_of(i);
                if k == Kind::Dummy || k == Kind::Gate {
                    continue;
                }
                let r =
                    ((p.x[i] - at[0]).powi(2) + (p.y[i] - at[1]).powi(2) + (p.z[i] - at[2]).powi(2)).sqrt();
                let wi = weight(r.max(1e-6 * ds), kernel.re_grad);
                pw += wi * p.pressure[i];
                w += wi;
            }
            if w > 0.0 {
                pw / w
            } else {
                0.0
            }
        }
        ProbeKind::SurgeFront => {
            let a = probe.axis_index();
            let coord = [&p.x, &p.y, &p.z][a];
            (0..p.len())
                .filter(|&i| in_water(i))
                .map(|i| coord[i] + 0.5 * ds - tank.min[a])
                .fold(0.0, f64::max)
        }
    }
}

/// The probe CSV: `time` then one column per probe.
pub struct ProbeFile {
    out: BufWriter<fs::File>,
}

impl ProbeFile {
    /// Creates the file with its header.
    pub fn create(path: &Path, probes: &[ProbeConfig]) -> io::Result<ProbeFile> {
        let mut out = BufWriter::new(fs::File::create(path)?);
        let names: Vec<&str> = probes.iter().map(|p| p.name.as_str()).collect();
        writeln!(out, "time,{}", names.join(","))?;
        out.flush()?;
        Ok(ProbeFile { out })
    }

    /// Appends one row.
    pub fn row(&mut self, time: f64, values: &[f64]) -> io::Result<()> {
        let cols: Vec<String> = values.iter().map(|v| format!("{v:.6e}")).collect();
        writeln!(self.out, "{time:.6},{}", cols.join(","))?;
        self.out.flush()
    }
}
