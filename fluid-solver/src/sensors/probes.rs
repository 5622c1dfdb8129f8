//! Probes declared in the case, sampled into one CSV: water height at a gauge, pressure at a
//! point, surge-front position, run-up on the solids, and wall-pressure sensors ([`crate::sensors::wall_sensor`]); the CSV's
//! last column counts the fluid particles removed so far (open top and outflow).
//!
//! Droplets are left out of heights and fronts: a fluid particle counts only if its number
//! density is at least [`MIN_DENSITY_FRACTION`] of n0 (a lone particle in the air has far less).
//! A gauge reads the top of the water column that stands on the bed below it: starting from its
//! lowest water particle, which must have a solid particle (floor, wall box, body) within
//! r_e,grad below it, it climbs while the next particle up is within r_e,grad (connected water),
//! so a drop against the lid, or spray above the column, is not read as water depth.

use crate::emps::kernel::{weight, Kernel};
use crate::emps::pair_laws;
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use crate::sensors::view::ParticleView;
use crate::sensors::wall_sensor::Disc;
use crate::solver::FluidSolver;
use schemas::case::fluid::{Aabb, ProbeConfig, ProbeKind};
use std::collections::{HashMap, VecDeque};
use std::fs;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// Fraction of n0 below which a fluid particle is taken as spray, not as part of the water.
pub const MIN_DENSITY_FRACTION: f64 = 0.5;

/// Samples one probe on the current particles (a wall-pressure sensor needs the method's pair
/// law: sample it through [`ProbeSet`]; here it reads NaN).
pub fn sample(probe: &ProbeConfig, p: &Particles, kernel: &Kernel, tank: &Aabb) -> f64 {
    let ds = kernel.spacing;
    let in_water = |i: usize| p.kind[i] == FLUID && p.number_density[i] >= MIN_DENSITY_FRACTION * kernel.n0;
    match probe.kind {
        ProbeKind::WaterHeight => water_height(probe, p, kernel, tank, in_water),
        ProbeKind::Pressure => {
            let at = [probe.position[0], probe.position[1], probe.position[2]];
            let (mut pw, mut w) = (0.0, 0.0);
            let re2 = kernel.re_grad * kernel.re_grad;
            for i in 0..p.len() {
                let k = p.kind_of(i);
                let r2 = (p.x[i] - at[0]).powi(2) + (p.y[i] - at[1]).powi(2) + (p.z[i] - at[2]).powi(2);
                // Beyond r_e the weight is 0: no square root for the particles there.
                if r2 >= re2 || k == Kind::Dummy || k == Kind::Gate {
                    continue;
                }
                let r = r2.sqrt();
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
            let coord = [&p.x, &p.y, &p.z][probe.axis_direction().0];
            let water = (0..p.len()).filter(|&i| in_water(i)).map(|i| coord[i]);
            // the largest and the smallest coordinate, a NaN kept
            let extent = water.fold(None, |e: Option<[f64; 2]>, x| {
                Some(e.map_or([x, x], |[most, least]| {
                    [
                        if x > most || x.is_nan() { x } else { most },
                        if x < least || x.is_nan() { x } else { least },
                    ]
                }))
            });
            surge_front_of(probe, extent, ds, tank)
        }
        ProbeKind::WallPressure => f64::NAN,
        ProbeKind::RunUp => run_up(p, kernel, tank, in_water),
    }
}

/// The surge front from the water's extent along the probe's axis (its largest and smallest
/// coordinate; `None`: no water): the distance the water reached from the face it starts at
/// (tank.min towards +, tank.max towards −) plus Δs/2; 0 with no water, NaN with a NaN position.
fn surge_front_of(probe: &ProbeConfig, extent: Option<[f64; 2]>, ds: f64, tank: &Aabb) -> f64 {
    let (a, sign) = probe.axis_direction();
    let Some([most, least]) = extent else {
        return 0.0;
    };
    let (reached, face) = match sign > 0.0 {
        true => (most, tank.min[a]),
        false => (least, tank.max[a]),
    };
    let front = sign * (reached - face) + 0.5 * ds;
    if front > 0.0 || front.is_nan() {
        front
    } else {
        0.0
    }
}

/// The run-up gauge: the highest water particle resting on a solid, plus Δs/2, above the tank
/// floor (0 when no water rests on a solid; NaN when a position is). Resting: a solid particle
/// lies below it within r_e,grad and within atan ½ ≈ 27° of the vertical (its horizontal
/// offset under half its depth below), as a beach's or a floor's top layer does; the side walls
/// of a narrow flume, beside the water at a horizontal offset of Δs, and vertical faces do not
/// hold it up. The solids are binned in cells of r_e,grad, so each water particle looks at the
/// 27 cells around it.
fn run_up(p: &Particles, kernel: &Kernel, tank: &Aabb, in_water: impl Fn(usize) -> bool) -> f64 {
    let reach = kernel.re_grad;
    let cell = |i: usize| [p.x[i], p.y[i], p.z[i]].map(|v| (v / reach).floor() as i64);
    let mut solids: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for i in (0..p.len()).filter(|&i| matches!(p.kind_of(i), Kind::Wall | Kind::Body)) {
        solids.entry(cell(i)).or_default().push(i);
    }
    let rests = |i: usize| {
        let c = cell(i);
        (0..27).any(|n| {
            let at = [c[0] + n % 3 - 1, c[1] + (n / 3) % 3 - 1, c[2] + n / 9 - 1];
            solids.get(&at).is_some_and(|js| {
                js.iter().any(|&j| {
                    let across = (p.x[j] - p.x[i]).powi(2) + (p.y[j] - p.y[i]).powi(2);
                    let below = p.z[i] - p.z[j];
                    below > 0.0 && 4.0 * across < below * below && across + below * below <= reach * reach
                })
            })
        })
    };
    let resting = (0..p.len()).filter(|&i| in_water(i) && rests(i)).map(|i| p.z[i]);
    // the highest, a NaN kept
    let top = resting.fold(None, |top: Option<f64>, z| {
        Some(top.map_or(z, |t| if z > t || z.is_nan() { z } else { t }))
    });
    run_up_of(top, kernel.spacing, tank)
}

/// The run-up gauge's reading from the highest water resting on a solid (`None`: none rests):
/// its height plus Δs/2 above the tank floor, 0 when none rests or below the floor.
fn run_up_of(top: Option<f64>, ds: f64, tank: &Aabb) -> f64 {
    top.map_or(0.0, |z| {
        schemas::validation::largest([z + 0.5 * ds - tank.min[2]], 0.0)
    })
}

/// The water-height gauge: the top of the connected column on the bed (see the module doc).
fn water_height(
    probe: &ProbeConfig,
    p: &Particles,
    kernel: &Kernel,
    tank: &Aabb,
    in_water: impl Fn(usize) -> bool,
) -> f64 {
    let ds = kernel.spacing;
    let reach = kernel.re_grad;
    let (gx, gy) = (probe.position[0], probe.position[1]);
    let near = |i: usize| (p.x[i] - gx).powi(2) + (p.y[i] - gy).powi(2) <= ds * ds;
    let mut column: Vec<f64> = (0..p.len())
        .filter(|&i| near(i) && in_water(i))
        .map(|i| p.z[i])
        .collect();
    column.sort_by(f64::total_cmp);
    let Some(&bottom) = column.first() else {
        return 0.0;
    };
    let solid = |i: usize| matches!(p.kind_of(i), Kind::Wall | Kind::Dummy | Kind::Body);
    let on_bed = (0..p.len()).any(|i| solid(i) && near(i) && p.z[i] < bottom && bottom - p.z[i] <= reach);
    if !on_bed {
        return 0.0;
    }
    let top = column
        .iter()
        .skip(1)
        .try_fold(bottom, |top, &z| if z - top <= reach { Ok(z) } else { Err(top) })
        .unwrap_or_else(|top| top);
    top + 0.5 * ds - tank.min[2]
}

/// The probes of a participant with their filters: samples rows for the CSV.
#[derive(Debug, Clone)]
pub struct ProbeSet {
    probes: Vec<ProbeConfig>,
    /// The wall-pressure sensors' discs, on the faces as built (see [`ProbeSet::new`]).
    discs: Vec<Option<Disc>>,
    /// Per filtered probe: the readings (time, value) of the steps inside its window.
    windows: Vec<Option<VecDeque<(f64, f64)>>>,
    /// Whether this set reads each probe: all of them, unless [`ProbeSet::reading_only`] left
    /// some to another part of the fluid.
    reads: Vec<bool>,
}

impl ProbeSet {
    /// The probes of a case section on `solver`'s initial layout. A wall-pressure disc is moved
    /// along its normal onto the nearest lattice face, where the face it is mounted on was built
    /// ([`crate::particles::lattice`]); a disc with no wall behind it is an error naming it.
    pub fn new(probes: &[ProbeConfig], solver: &FluidSolver) -> Result<ProbeSet, String> {
        let (ds, origin) = (solver.kernel().spacing, solver.tank().min);
        let discs: Vec<Option<Disc>> = probes
            .iter()
            .map(|p| {
                (p.kind == ProbeKind::WallPressure).then(|| {
                    let mut disc = Disc::of(p);
                    let a = disc.axis;
                    disc.centre[a] = origin[a] + ((disc.centre[a] - origin[a]) / ds).round() * ds;
                    disc
                })
            })
            .collect();
        for (probe, disc) in probes.iter().zip(&discs) {
            let Some(disc) = disc else { continue };
            let (_, first_layer) = disc.wall_particles(solver.particles(), ds);
            if first_layer == 0 {
                return Err(format!(
                    "probe `{}`: no wall or body particle lies behind the wall-pressure disc at {:?} with normal {}: put its centre on a face of the tank, a wall box or a body, with the normal pointing into the water",
                    probe.name,
                    probe.position,
                    probe.normal.as_deref().unwrap_or("?")
                ));
            }
        }
        Ok(ProbeSet {
            probes: probes.to_vec(),
            discs,
            windows: probes.iter().map(|p| p.window.map(|_| VecDeque::new())).collect(),
            reads: vec![true; probes.len()],
        })
    }

    /// The same probes, of which this set reads only those `reads` marks (a slab of the fluid
    /// reads the probes it owns, [`crate::ranks::slab_probes`]); the others read 0 and keep no
    /// readings.
    pub fn reading_only(mut self, reads: Vec<bool>) -> ProbeSet {
        assert_eq!(reads.len(), self.probes.len(), "one mark per probe");
        self.reads = reads;
        self
    }

    /// Where along x each probe reads around a point (a pressure probe's or a gauge's
    /// position, a wall-pressure disc's centre as placed); `None` for a probe over the whole
    /// fluid (surge front, run-up).
    pub fn points_x(&self) -> Vec<Option<f64>> {
        self.probes
            .iter()
            .zip(&self.discs)
            .map(|(probe, disc)| match (disc, probe.kind) {
                (Some(disc), _) => Some(disc.centre[0]),
                (None, ProbeKind::Pressure | ProbeKind::WaterHeight) => Some(probe.position[0]),
                (None, _) => None,
            })
            .collect()
    }

    /// The filtered probes' readings kept for their windows (a checkpoint keeps them).
    pub fn windows(&self) -> &[Option<VecDeque<(f64, f64)>>] {
        &self.windows
    }

    /// Takes over the readings of [`ProbeSet::windows`] (a resumed run).
    pub fn set_windows(&mut self, windows: Vec<Option<VecDeque<(f64, f64)>>>) {
        self.windows = windows;
    }

    /// The column names of the CSV rows.
    pub fn names(&self) -> Vec<&str> {
        self.probes.iter().map(|p| p.name.as_str()).collect()
    }

    /// After a step: a filtered probe whose window before the row at `next_row` has begun keeps
    /// this step's reading (windows longer than the row interval overlap: every step is kept).
    pub fn observe(&mut self, solver: &FluidSolver, next_row: f64) {
        let t = solver.time();
        let view = ParticleView::of(solver);
        let probes = self.probes.iter().zip(&self.discs).zip(&mut self.windows);
        for (((probe, disc), w), _) in probes.zip(&self.reads).filter(|(_, reads)| **reads) {
            if let (Some(window), Some(readings)) = (probe.window, w) {
                if t > next_row - window - 1e-12 {
                    readings.push_back((t, read(probe, disc, &view)));
                }
            }
        }
    }

    /// One row at the solver's time: instantaneous readings, and the filtered probes' means
    /// over the steps of their last `window` seconds (the instantaneous reading when no step
    /// fell in it yet).
    pub fn row(&mut self, solver: &FluidSolver) -> Vec<f64> {
        self.row_in(&ParticleView::of(solver))
    }

    /// [`ProbeSet::row`] read from `view` (which a caller shares with other readers of the row).
    pub fn row_in(&mut self, view: &ParticleView) -> Vec<f64> {
        let t = view.solver().time();
        self.probes
            .iter()
            .zip(&self.discs)
            .zip(&mut self.windows)
            .zip(&self.reads)
            .map(|(((probe, disc), w), &reads)| match (probe.window, w) {
                _ if !reads => 0.0,
                (Some(window), Some(readings)) => {
                    while readings.front().is_some_and(|r| r.0 <= t - window + 1e-12) {
                        readings.pop_front();
                    }
                    match readings.len() {
                        0 => read(probe, disc, view),
                        n => readings.iter().map(|r| r.1).sum::<f64>() / n as f64,
                    }
                }
                _ => read(probe, disc, view),
            })
            .collect()
    }
}

/// The instantaneous reading of one probe (`disc`: a wall-pressure sensor's, as placed) from
/// `view`: on the GPU path a sensor or a local probe reads the device's particles around it,
/// gathered without the rest, by the same rule (and the sensor by the E-MPS pair law); a global
/// probe reads the row's light copy of them all.
fn read(probe: &ProbeConfig, disc: &Option<Disc>, view: &ParticleView) -> f64 {
    let solver = view.solver();
    let (ds, reach) = (solver.kernel().spacing, solver.kernel().re_grad);
    let at: [f64; 3] = std::array::from_fn(|a| probe.position.get(a).copied().unwrap_or(0.0));
    let (lo, hi) = match (disc, probe.kind) {
        (Some(disc), _) => disc.bounds(reach, ds),
        (None, ProbeKind::WaterHeight) => (
            [at[0] - ds, at[1] - ds, f64::NEG_INFINITY],
            [at[0] + ds, at[1] + ds, f64::INFINITY],
        ),
        (None, ProbeKind::Pressure) => (at.map(|v| v - reach), at.map(|v| v + reach)),
        (None, ProbeKind::RunUp) if view.run_up_top().is_some() => {
            let top = view.run_up_top().flatten();
            return run_up_of(top, ds, &solver.tank());
        }
        (None, ProbeKind::SurgeFront) if view.water_extent().is_some() => {
            let along = view.water_extent().map(|e| e[probe.axis_direction().0]);
            return surge_front_of(probe, along, ds, &solver.tank());
        }
        (None, _) => return sample(probe, view.all(), solver.kernel(), &solver.tank()),
    };
    let near = view.around(lo, hi);
    match disc {
        // the GPU path reads wall-pressure sensors with E-MPS only (`FluidConfig::gpu_support`)
        Some(disc) if solver.device_ahead().is_some() => {
            disc.pressure(&near, &pair_laws::pressure(solver.kernel(), &near), ds)
        }
        Some(disc) => disc.pressure(&near, &solver.pressure_law(), ds),
        None => Some(sample(probe, &near, solver.kernel(), &solver.tank())),
    }
    .unwrap_or(f64::NAN)
}

/// The probe CSV: `time`, one column per probe, then `removed` (fluid particles removed so far
/// through the open top and the outflow).
pub struct ProbeFile {
    out: BufWriter<fs::File>,
}

impl ProbeFile {
    /// Creates the file with its header.
    pub fn create(path: &Path, names: &[&str]) -> io::Result<ProbeFile> {
        let mut out = BufWriter::new(fs::File::create(path)?);
        let sep = if names.is_empty() { "" } else { "," };
        writeln!(out, "time,{}{sep}removed", names.join(","))?;
        out.flush()?;
        Ok(ProbeFile { out })
    }

    /// Continues the file of a resumed run (header and earlier rows are there).
    pub fn append(path: &Path) -> io::Result<ProbeFile> {
        Ok(ProbeFile {
            out: BufWriter::new(schemas::checkpoint::append(path)?),
        })
    }

    /// Appends one row.
    pub fn row(&mut self, time: f64, values: &[f64], removed: u64) -> io::Result<()> {
        let mut cols: Vec<String> = values.iter().map(|v| format!("{v:.6e}")).collect();
        cols.push(removed.to_string());
        writeln!(self.out, "{time:.6},{}", cols.join(","))?;
        self.out.flush()
    }
}
