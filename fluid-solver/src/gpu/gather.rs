//! The device's particles in a box, copied back without the rest: what a filtered wall-pressure
//! sensor reads after every step on the GPU path ([`crate::sensors::probes::ProbeSet::observe`])
//! and a local probe at a row ([`crate::sensors::view`]); a standalone run's inflow balance (and
//! a global probe with wide positions) reads all of them, as light ([`GpuEmps::particles_all`]). A whole copy
//! comes only for frames ([`crate::FluidSolver::frame_particles`]), checkpoints and the
//! detector's findings ([`crate::FluidSolver::sync_host`]).
//!
//! The device keeps its particles in the order of the step's last cell sort (at r*): the
//! particles of cell c are the slots `cell_start[c] .. cell_start[c + 1]`, and a row of cells
//! along x is one run of slots. The box's cells, widened by [`MARGIN_CELLS`] cells each way for
//! what the particles moved after that sort (the correction and the collisions, well under a
//! cell in a step the detector lets pass), are such runs, one per row of cells: their two ends
//! come back first (8 B per row), then the runs' positions with their kinds and their number
//! densities and pressures (24 B per particle, f32 as the whole copy has them; 40 B with wide
//! positions' low parts, [`super::frame`]). What comes back
//! is a superset of the particles in the box, in the device's order; the caller picks from it by
//! its own rule (the CPU's sensor: [`crate::sensors::wall_sensor::Disc::pressure`]).

use super::buffers::{map_read, CELL_START, DENS, POS, POS_LO};
use super::step::GpuEmps;
use crate::particles::Particles;
use std::sync::atomic::Ordering;

/// Cells (1.05 Δs each) the box is widened by each way: a particle moves far less than 2.1 Δs
/// between the sort at r* and the step's end.
pub const MARGIN_CELLS: i64 = 2;

impl GpuEmps {
    /// The device's particles whose cell at the last sort lies within [`MARGIN_CELLS`] cells of
    /// the box `lo`–`hi` (velocities and ids are not copied: 0).
    pub fn particles_in(&self, lo: [f64; 3], hi: [f64; 3]) -> Particles {
        let prm = &self.params;
        let pad = i64::from(prm.pad);
        let frame = self.frame;
        let cell = |v: f64, a: usize, shift: i64| {
            let v = v - frame.origin[a];
            let c = (((v - f64::from(prm.origin[a])) * f64::from(prm.inv_cell)).floor() as i64)
                .saturating_add(shift);
            c.clamp(pad, i64::from(prm.dims[a]) - pad - 1) as u64
        };
        let c_lo: [u64; 3] = std::array::from_fn(|a| cell(lo[a], a, -MARGIN_CELLS));
        let c_hi: [u64; 3] = std::array::from_fn(|a| cell(hi[a], a, MARGIN_CELLS));
        let (nx, ny) = (u64::from(prm.dims[0]), u64::from(prm.dims[1]));
        let rows: Vec<u64> = (c_lo[2]..=c_hi[2])
            .flat_map(|z| (c_lo[1]..=c_hi[1]).map(move |y| c_lo[0] + nx * (y + ny * z)))
            .collect();
        let run = c_hi[0] - c_lo[0] + 1;
        // the runs' ends: cell_start of each row's first cell and of the cell past its last
        let ends_staging = self.staging_of(8 * rows.len() as u64);
        let starts = self.buffers.at(CELL_START);
        let mut enc = self.gather_encoder();
        for (r, &first) in rows.iter().enumerate() {
            let at = 8 * r as u64;
            enc.copy_buffer_to_buffer(starts, 4 * first, &ends_staging, at, 4);
            enc.copy_buffer_to_buffer(starts, 4 * (first + run), &ends_staging, at + 4, 4);
        }
        self.dev.queue.submit([enc.finish()]);
        let ends: Vec<u32> = map_read(&self.dev, &ends_staging.slice(..));
        // the runs, joined where one ends where the next begins
        let n = self.len() as u64;
        let mut runs: Vec<(u64, u64)> = Vec::new();
        for e in ends.chunks_exact(2) {
            let (s, e) = (u64::from(e[0]).min(n), u64::from(e[1]).min(n));
            if e <= s {
                continue;
            }
            match runs.last_mut() {
                Some(last) if last.1 == s => last.1 = e,
                _ => runs.push((s, e)),
            }
        }
        let count: u64 = runs.iter().map(|r| r.1 - r.0).sum();
        if count == 0 {
            self.gathered.fetch_add(8 * rows.len() as u64, Ordering::Relaxed);
            return Particles::default();
        }
        // per particle: position and kind, number density and pressure, and with wide positions
        // the position's low part
        let lows = if self.buffers.wide { 16 } else { 0 };
        let per = 24 + lows;
        let staging = self.staging_of(per * count);
        let mut enc = self.gather_encoder();
        let mut k = 0;
        for &(s, e) in &runs {
            let len = e - s;
            enc.copy_buffer_to_buffer(self.buffers.at(POS), 16 * s, &staging, 16 * k, 16 * len);
            enc.copy_buffer_to_buffer(
                self.buffers.at(DENS),
                8 * s,
                &staging,
                16 * count + 8 * k,
                8 * len,
            );
            if self.buffers.wide {
                enc.copy_buffer_to_buffer(
                    self.buffers.at(POS_LO),
                    16 * s,
                    &staging,
                    24 * count + 16 * k,
                    16 * len,
                );
            }
            k += len;
        }
        self.dev.queue.submit([enc.finish()]);
        self.gathered.fetch_add(8 * rows.len() as u64, Ordering::Relaxed);
        self.light(&map_read(&self.dev, &staging.slice(..)), count)
    }

    /// All the device's particles, as [`GpuEmps::particles_in`] copies them (positions and
    /// kinds, number densities and pressures: 24 B each, 40 with wide positions), in one copy
    /// per array: what the global probes of a row read.
    pub fn particles_all(&self) -> Particles {
        let n = self.len();
        if n == 0 {
            return Particles::default();
        }
        let mut arrays = vec![(POS, 16), (DENS, 8)];
        if self.buffers.wide {
            arrays.push((POS_LO, 16));
        }
        self.light(&self.buffers.read_arrays(&self.dev, &arrays, n), n as u64)
    }

    /// `count` particles from `bytes`, which hold their positions (16 B each), then their number
    /// densities and pressures (8 B), then with wide positions their low parts (16 B): as
    /// particles (velocities and ids 0).
    fn light(&self, bytes: &[u8], count: u64) -> Particles {
        self.gathered.fetch_add(bytes.len() as u64, Ordering::Relaxed);
        let (pos, rest) = bytes.split_at(16 * count as usize);
        let (dens, lo) = rest.split_at(8 * count as usize);
        let pos: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(pos);
        let dens: Vec<[f32; 2]> = bytemuck::pod_collect_to_vec(dens);
        let m = pos.len();
        // empty with plain positions (nothing was copied there)
        let lo: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(lo);
        let mut p = Particles::default();
        [p.x, p.y, p.z] = self.frame.columns_back(&pos, &lo);
        p.kind = pos.iter().map(|e| e[3] as u8).collect();
        (p.vx, p.vy, p.vz) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        p.number_density = dens.iter().map(|e| f64::from(e[0])).collect();
        p.pressure = dens.iter().map(|e| f64::from(e[1])).collect();
        p.id = vec![0; m];
        p
    }

    /// A buffer the host maps to read `size` bytes (at least 8).
    fn staging_of(&self, size: u64) -> wgpu::Buffer {
        self.dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sensor gather"),
            size: size.max(8),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    fn gather_encoder(&self) -> wgpu::CommandEncoder {
        self.dev
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("sensor gather"),
            })
    }
}
