//! A pass over the particles that counts or reduces into the words past the cells' counts
//! (`cell_count[cells + k]`, [`super::buffers::OPEN_COUNTERS`] of them), cleared first and read
//! back after: what the escapes' removal and the probes' reductions share.

use super::buffers::{map_read, CELL_COUNT};
use super::kernels::{dispatch, WG};
use super::step::GpuEmps;
use std::ops::Range;
use std::sync::atomic::Ordering;

impl GpuEmps {
    /// Clears the words `clear` past the cells' counts, runs `pass` over the particles, and reads
    /// the words `read` back.
    pub(super) fn counter_pass(
        &self,
        pass: &wgpu::ComputePipeline,
        clear: Range<u64>,
        read: Range<u64>,
    ) -> Vec<u32> {
        let word = |k: u64| 4 * (u64::from(self.params.cells) + k);
        let bytes = word(read.end) - word(read.start);
        let staging = self.dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("counter pass"),
            size: bytes.max(4),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let counters = self.buffers.at(CELL_COUNT);
        let mut enc = self
            .dev
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("counter pass"),
            });
        enc.clear_buffer(
            counters,
            word(clear.start),
            Some(word(clear.end) - word(clear.start)),
        );
        {
            let mut p = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("counter pass"),
                timestamp_writes: None,
            });
            dispatch(&mut p, &self.kernels, pass, self.len() as u32, WG);
        }
        enc.copy_buffer_to_buffer(counters, word(read.start), &staging, 0, bytes);
        self.dev.queue.submit([enc.finish()]);
        self.gathered.fetch_add(bytes, Ordering::Relaxed);
        map_read(&self.dev, &staging.slice(..bytes))
    }
}
