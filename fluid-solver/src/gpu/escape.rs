//! Fluid leaving through an open top, removed on the device ([`crate::boundaries::escape`] on the
//! GPU path; `shaders/escape.wgsl`): the step's scan counts the particles that left, and before
//! the next step a pass marks them by the same rule, 4 B of count come back, and the cell sort
//! drops them, as it drops the outflow's. No copy of the particles crosses.

use super::buffers::OPEN_COUNTERS;
use super::cell_sort;
use super::step::GpuEmps;

/// The word after the cells' counts that the pass counts in (`OPEN_COUNTERS` counts it in).
const COUNTER: u64 = 10;

impl GpuEmps {
    /// Removes the fluid that left through the open top at the last step; returns how many.
    pub fn remove_escaped(&mut self) -> u64 {
        self.params.n = self.len() as u32;
        let (n, cells) = (self.params.n, self.params.cells);
        self.buffers.write_params(&self.dev, &self.params);
        // every counter cleared: the compaction sort's count of removed particles too
        let counted = self.counter_pass(
            &self.kernels.remove_escaped,
            0..OPEN_COUNTERS,
            COUNTER..COUNTER + 1,
        );
        let removed = counted[0];
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
