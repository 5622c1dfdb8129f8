//! Fluid leaving through an open top, removed on the device ([`crate::boundaries::escape`] on the
//! GPU path; `shaders/escape.wgsl`): the step's scan counts the particles that left, and before
//! the next step a pass marks them by the same rule, 4 B of count come back, and the cell sort
//! drops them, as it drops the outflow's. No copy of the particles crosses.

use super::buffers::{map_read, CELL_COUNT, OPEN_COUNTERS};
use super::cell_sort;
use super::kernels::{dispatch, WG};
use super::step::GpuEmps;

/// The word after the cells' counts that the pass counts in (`OPEN_COUNTERS` counts it in).
const COUNTER: u64 = 10;

impl GpuEmps {
    /// Removes the fluid that left through the open top at the last step; returns how many.
    pub fn remove_escaped(&mut self) -> u64 {
        self.params.n = self.len() as u32;
        let (n, cells) = (self.params.n, self.params.cells);
        self.buffers.write_params(&self.dev, &self.params);
        let zeros = [0u32; OPEN_COUNTERS as usize];
        self.buffers
            .write_at(&self.dev, CELL_COUNT, cells as usize, &zeros);
        let staging = self.dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("escapes"),
            size: 4,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self
            .dev
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("escapes"),
            });
        {
            let mut p = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("escapes"),
                timestamp_writes: None,
            });
            dispatch(&mut p, &self.kernels, &self.kernels.remove_escaped, n, WG);
        }
        let at = 4 * (u64::from(cells) + COUNTER);
        enc.copy_buffer_to_buffer(self.buffers.at(CELL_COUNT), at, &staging, 0, 4);
        self.dev.queue.submit([enc.finish()]);
        let removed: Vec<u32> = map_read(&self.dev, &staging.slice(..));
        self.buffers.downloaded += 4;
        let removed = removed[0];
        if removed > 0 {
            // the sort with the count before the pass drops the removed particles past the rest
            let mut enc = self
                .dev
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("compaction"),
                });
            cell_sort::encode(&mut enc, &self.kernels, &self.buffers, n, cells);
            self.dev.queue.submit([enc.finish()]);
            self.shrink_by(removed as usize);
        }
        u64::from(removed)
    }
}
