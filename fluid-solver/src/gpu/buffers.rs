//! The device arrays of the GPU step, their precision and the copies between host and device.
//!
//! Per particle: position + kind `vec4<f32>` (16 B), velocity `vec4<f32>` (16 B), id `u32`
//! (4 B), number density + pressure `vec2<f32>` (8 B), the pair pass's result `vec4<f32>` (16 B),
//! the force from non-fluid neighbours `vec4<f32>` (16 B), candidates `u32` (4 B), cell before and
//! after the sort and the permutation 3 × `u32` (12 B): 92 B (the sort gathers through the pair
//! pass's result and the permutation, free while it runs, so it needs no spare copies). Per
//! cell: start and count `u32` (8 B; the count's top bit flags a cell with fluid; after the
//! counts 16 B of the open boundaries' counters), and 4 B per 4096 cells of the scan's block
//! totals; with resolved bodies also the mask of bodies near it
//! (`u32`, 4 B: 12 B). Per 256 particles one reduction partial (48 B). Resolved bodies
//! (`shaders/bodies.wgsl`, `shaders/reaction.wgsl`): per body particle its offset from the
//! body's initial centre (f32), id and body (32 B); per body its pose and velocity (f32, 64 B),
//! its three sums (loads, the fluid-side reaction, the walls' contact; f32, 3 × 32 B) and three
//! partials per reduction group (f32, 3 × 32 B). A body particle's load of one exchange lives in
//! its `acc` slot and the walls' share in its `wallf` slot, so bodies add nothing per particle.
//! The wave maker's paddle keeps each of its particles' rest position in a row of the members'
//! buffer after the bodies' (32 B per paddle particle, `shaders/paddle.wgsl`).
//! With an inflow the particle arrays hold room for more particles than the start's
//! ([`super::open_boundary`]), and are regrown when the strip has added more.
//! Damping zones take 48 B each (`shaders/damping.wgsl`); mesh solids and terrains one bit per
//! site of the tank's lattice (`shaders/solids.wgsl`), followed in the same buffer by the
//! detector's 32 B per body and one bit per site of each mesh body's block of sites
//! (`shaders/body_inside.wgsl`). With wide positions ([`super::frame`]) each particle's position
//! has a low part too (`vec4<f32>`, 16 B: 108 B per particle), gathered by the sort through the
//! pair pass's result like the rest.

use super::device::GpuDevice;
use super::frame::Frame;
use super::reduce::Partial;
use crate::particles::Particles;
use bytemuck::{Pod, Zeroable};
use rayon::prelude::*;
use std::sync::mpsc;

/// Sums kept per body (`SUMS` in `shaders/common.wgsl`): the loads summed by body particle, the
/// reaction summed by fluid particle, the walls' contact.
pub const SUMS: u64 = 3;

/// Every storage buffer of the step, in binding order 1 … 23 (0 is the uniform block).
pub struct Buffers {
    pub params: wgpu::Buffer,
    pub storage: Vec<wgpu::Buffer>,
    /// Whether positions are wide (a low part per particle in [`POS_LO`]; [`super::frame`]).
    pub wide: bool,
    /// Particles the buffers hold room for.
    pub capacity: usize,
    /// Bytes copied host → device and device → host since the start.
    pub uploaded: u64,
    pub downloaded: u64,
}

/// Binding numbers (see `shaders/common.wgsl`).
pub const POS: usize = 1;
pub const VEL: usize = 2;
pub const ID: usize = 3;
pub const DENS: usize = 4;
pub const ACC: usize = 5;
pub const CELL_COUNT: usize = 11;
pub const PERM: usize = 9;
pub const CELL_START: usize = 10;
pub const BOXES: usize = 14;
pub const PARTIALS: usize = 15;
pub const MEMBERS: usize = 16;
pub const BODY_KIN: usize = 17;
pub const BODY_LOADS: usize = 19;
pub const DAMPING: usize = 21;
pub const SOLID_BITS: usize = 22;
pub const POS_LO: usize = 23;

/// Words after the cells' counts: the removed particles' count (`shaders/cell_sort.wgsl`), the
/// open boundaries' three counters (`shaders/open_boundary.wgsl`), the water's extent's six keys
/// (`shaders/probe_reductions.wgsl`), the escapes' count (`shaders/escape.wgsl`) and the
/// run-up's key (`shaders/probe_reductions.wgsl`).
pub const OPEN_COUNTERS: u64 = 12;

impl Buffers {
    /// Buffers for `n` particles (with low parts when `wide`), `cells` cells, `boxes` wall blocks, `groups` reduction groups,
    /// `bodies` bodies and `members` rows of body and paddle particles, `zones` damping zones and
    /// `solid_words` words of solid sites and the bodies' table ([`super::body_inside`]).
    pub fn new(
        dev: &GpuDevice,
        (n, wide): (usize, bool),
        cells: usize,
        boxes: usize,
        groups: usize,
        (bodies, members): (usize, usize),
        (zones, solid_words): (usize, usize),
    ) -> Buffers {
        let n = n.max(1) as u64;
        let block_sums = super::cell_sort::block_sum_entries(cells as u32);
        let cells = cells as u64;
        // the mask of bodies near each cell only when there are bodies
        let body_cells = if bodies > 0 { cells } else { 1 };
        // and the bodies' partials per reduction group
        let body_groups = if bodies > 0 { groups.max(1) as u64 } else { 1 };
        let (bodies, members) = (bodies.max(1) as u64, members.max(1) as u64);
        let sizes: [u64; 23] = [
            16 * n,                                                  // 1 pos
            16 * n,                                                  // 2 vel
            4 * n,                                                   // 3 id
            8 * n,                                                   // 4 dens
            16 * n,                                                  // 5 acc
            16 * n,                                                  // 6 wall force
            4 * n,                                                   // 7 candidates
            4 * n,                                                   // 8 cell_of
            4 * n,                                                   // 9 perm
            4 * (cells + 1),                                         // 10 cell_start
            4 * (cells + OPEN_COUNTERS),                             // 11 cell_count
            4 * block_sums,                                          // 12 block sums
            4 * n,                                                   // 13 cell_sorted
            32 * boxes.max(1) as u64,                                // 14 boxes
            (std::mem::size_of::<Partial>() * groups.max(1)) as u64, // 15 partials
            32 * members,                                            // 16 members
            80 * bodies,                                             // 17 body_kin
            32 * SUMS * bodies * body_groups,                        // 18 body_partials
            32 * SUMS * bodies,                                      // 19 body_loads
            4 * body_cells,                                          // 20 body_cells
            48 * zones.max(1) as u64,                                // 21 damping
            4 * solid_words.max(1) as u64,                           // 22 solid_bits
            if wide { 16 * n } else { 16 },                          // 23 pos_lo
        ];
        let storage = sizes
            .iter()
            .enumerate()
            .map(|(k, &size)| {
                dev.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(&format!("binding {}", k + 1)),
                    size,
                    usage: wgpu::BufferUsages::STORAGE
                        | wgpu::BufferUsages::COPY_SRC
                        | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            })
            .collect();
        let params = dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("params"),
            size: std::mem::size_of::<super::params::Params>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Buffers {
            params,
            storage,
            wide,
            capacity: n as usize,
            uploaded: 0,
            downloaded: 0,
        }
    }

    /// Bytes of device memory the buffers hold.
    pub fn device_bytes(&self) -> u64 {
        self.params.size() + self.storage.iter().map(wgpu::Buffer::size).sum::<u64>()
    }

    /// The buffer of binding `b`.
    pub fn at(&self, b: usize) -> &wgpu::Buffer {
        &self.storage[b - 1]
    }

    /// Writes `data` at the start of binding `b`'s buffer.
    pub fn write<T: Pod>(&mut self, dev: &GpuDevice, b: usize, data: &[T]) {
        self.write_at(dev, b, 0, data);
    }

    /// Writes `data` into binding `b`'s buffer from its element `first` on.
    pub fn write_at<T: Pod>(&mut self, dev: &GpuDevice, b: usize, first: usize, data: &[T]) {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        if !bytes.is_empty() {
            let offset = (first * std::mem::size_of::<T>()) as u64;
            dev.queue.write_buffer(self.at(b), offset, bytes);
            self.uploaded += bytes.len() as u64;
        }
    }

    /// Writes the uniform block.
    pub fn write_params(&mut self, dev: &GpuDevice, p: &super::params::Params) {
        dev.queue.write_buffer(&self.params, 0, bytemuck::bytes_of(p));
        self.uploaded += std::mem::size_of_val(p) as u64;
    }

    /// Copies the particles to the device (positions in `frame`, velocities and pressures in
    /// f32).
    pub fn upload(&mut self, dev: &GpuDevice, p: &Particles, frame: &Frame) {
        self.upload_at(dev, p, 0, frame);
    }

    /// Copies the particles to the device's slots `first` … `first + p.len()`.
    pub fn upload_at(&mut self, dev: &GpuDevice, p: &Particles, first: usize, frame: &Frame) {
        let n = p.len();
        let parts: Vec<([f32; 3], [f32; 3])> = (0..n).map(|i| frame.split(p.position(i))).collect();
        let pos: Vec<[f32; 4]> = (0..n)
            .map(|i| {
                let [x, y, z] = parts[i].0;
                [x, y, z, f32::from(p.kind[i])]
            })
            .collect();
        if self.wide {
            let lo: Vec<[f32; 4]> = parts.iter().map(|(_, [x, y, z])| [*x, *y, *z, 0.0]).collect();
            self.write_at(dev, POS_LO, first, &lo);
        }
        let vel: Vec<[f32; 4]> = (0..n)
            .map(|i| [p.vx[i] as f32, p.vy[i] as f32, p.vz[i] as f32, 0.0])
            .collect();
        let dens: Vec<[f32; 2]> = (0..n)
            .map(|i| [p.number_density[i] as f32, p.pressure[i] as f32])
            .collect();
        self.write_at(dev, POS, first, &pos);
        self.write_at(dev, VEL, first, &vel);
        self.write_at(dev, ID, first, &p.id);
        self.write_at(dev, DENS, first, &dens);
    }

    /// Copies the first `n` particles back into `p` (its arrays are replaced; kinds from the
    /// position's w; positions from `frame`): every array into one staging buffer, one
    /// submission and one mapping, the columns then filled in parallel.
    pub fn download(&mut self, dev: &GpuDevice, n: usize, p: &mut Particles, frame: &Frame) {
        // (binding, bytes per particle), in the staging buffer's order
        let mut arrays = vec![(POS, 16u64), (VEL, 16), (ID, 4), (DENS, 8)];
        if self.wide {
            arrays.push((POS_LO, 16));
        }
        if n == 0 {
            *p = Particles::default();
            return;
        }
        let bytes = self.read_arrays(dev, &arrays, n);
        self.downloaded += bytes.len() as u64;
        let (pos, rest) = bytes.split_at(16 * n);
        let (vel, rest) = rest.split_at(16 * n);
        let (id, rest) = rest.split_at(4 * n);
        let (dens, lo) = rest.split_at(8 * n);
        let pos: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(pos);
        let vel: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(vel);
        let dens: Vec<[f32; 2]> = bytemuck::pod_collect_to_vec(dens);
        // empty with plain positions (nothing was copied there)
        let lo: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(lo);
        let col = |v: &[[f32; 4]], a: usize| v.par_iter().map(|e| f64::from(e[a])).collect::<Vec<f64>>();
        [p.x, p.y, p.z] = frame.columns_back(&pos, &lo);
        p.kind = pos.par_iter().map(|e| e[3] as u8).collect();
        p.vx = col(&vel, 0);
        p.vy = col(&vel, 1);
        p.vz = col(&vel, 2);
        p.number_density = dens.par_iter().map(|e| f64::from(e[0])).collect();
        p.pressure = dens.par_iter().map(|e| f64::from(e[1])).collect();
        p.id = bytemuck::pod_collect_to_vec(id);
    }

    /// Reads the first `count` elements of binding `b`'s buffer.
    pub fn read<T: Pod + Zeroable>(&mut self, dev: &GpuDevice, b: usize, count: usize) -> Vec<T> {
        if count == 0 {
            return Vec::new();
        }
        let bytes = self.read_arrays(dev, &[(b, std::mem::size_of::<T>() as u64)], count);
        self.downloaded += bytes.len() as u64;
        bytemuck::pod_collect_to_vec(&bytes)
    }

    /// The first `n` elements of each binding of `arrays` ((binding, bytes per element), `n` > 0),
    /// one after the other: copied into one staging buffer in one submission and mapped once.
    /// The caller counts the bytes.
    pub fn read_arrays(&self, dev: &GpuDevice, arrays: &[(usize, u64)], n: usize) -> Vec<u8> {
        let total: u64 = arrays.iter().map(|&(_, size)| size * n as u64).sum();
        let staging = dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("download"),
            size: total,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = dev
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("download"),
            });
        let mut at = 0;
        for &(b, size) in arrays {
            enc.copy_buffer_to_buffer(self.at(b), 0, &staging, at, size * n as u64);
            at += size * n as u64;
        }
        dev.queue.submit([enc.finish()]);
        map_read(dev, &staging.slice(..))
    }
}

/// Maps a slice of a MAP_READ buffer, waits, and copies its contents out.
pub fn map_read<T: Pod + Zeroable>(dev: &GpuDevice, slice: &wgpu::BufferSlice<'_>) -> Vec<T> {
    let (tx, rx) = mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    dev.wait();
    match rx.recv() {
        Ok(Ok(())) => {}
        other => panic!("the GPU device was lost while reading a buffer back: {other:?}"),
    }
    let out = match slice.get_mapped_range() {
        Ok(view) => bytemuck::pod_collect_to_vec(&view),
        Err(e) => panic!("the GPU buffer could not be mapped: {e:?}"),
    };
    slice.buffer().unmap();
    out
}
