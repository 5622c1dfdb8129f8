//! The water's extent on the device (`shaders/water_extent.wgsl`): the largest and smallest
//! coordinate along each axis over the fluid particles that are water, not spray, which is all a
//! surge-front probe reads ([`crate::sensors::probes`]). A probe row then needs no copy of the
//! particles: one pass over them and 24 B back.

use super::buffers::{map_read, CELL_COUNT};
use super::kernels::{dispatch, WG};
use super::step::GpuEmps;
use std::sync::atomic::Ordering;

/// First of the six words after the cells' counts that the pass writes (`OPEN_COUNTERS` counts
/// them in).
const FIRST: u64 = 4;

/// The f32 value of a key of `shaders/water_extent.wgsl`'s `order_key`; `None` for the zero
/// the host cleared it to (no water).
fn value_of_key(key: u32) -> Option<f32> {
    match key {
        0 => None,
        k if k & 0x8000_0000 != 0 => Some(f32::from_bits(k & 0x7fff_ffff)),
        k => Some(f32::from_bits(!k)),
    }
}

impl GpuEmps {
    /// Per axis, the largest and the smallest coordinate (in the case's frame) of the fluid
    /// particles whose number density is at least half of n0; `None` with wide positions (the
    /// caller reads a light copy) or when there is no such particle.
    pub fn water_extent(&self) -> Option<[[f64; 2]; 3]> {
        if self.buffers.wide || self.is_empty() {
            return None;
        }
        let cells = u64::from(self.params.cells);
        let offset = 4 * (cells + FIRST);
        let staging = self.dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("water extent"),
            size: 24,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let counters = self.buffers.at(CELL_COUNT);
        let mut enc = self
            .dev
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("water extent"),
            });
        enc.clear_buffer(counters, offset, Some(24));
        {
            let mut p = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("water extent"),
                timestamp_writes: None,
            });
            dispatch(
                &mut p,
                &self.kernels,
                &self.kernels.water_extent,
                self.len() as u32,
                WG,
            );
        }
        enc.copy_buffer_to_buffer(counters, offset, &staging, 0, 24);
        self.dev.queue.submit([enc.finish()]);
        let keys: Vec<u32> = map_read(&self.dev, &staging.slice(..));
        self.gathered.fetch_add(24, Ordering::Relaxed);
        let origin = self.frame.origin;
        let mut extent = [[0.0; 2]; 3];
        for a in 0..3 {
            let most = value_of_key(keys[2 * a])?;
            let least = value_of_key(keys[2 * a + 1])?;
            extent[a] = [origin[a] + f64::from(most), origin[a] - f64::from(least)];
        }
        Some(extent)
    }
}

#[cfg(test)]
mod tests {
    use super::value_of_key;

    /// The shader's key, written out on the host.
    fn order_key(v: f32) -> u32 {
        let b = v.to_bits();
        if b & 0x8000_0000 != 0 {
            !b
        } else {
            b | 0x8000_0000
        }
    }

    #[test]
    fn keys_keep_the_order_of_the_values_and_give_them_back() {
        let values = [-1e30f32, -2.5, -1e-30, -0.0, 0.0, 1e-30, 0.75, 3.0, 1e30];
        for w in values.windows(2) {
            assert!(order_key(w[0]) <= order_key(w[1]), "{} then {}", w[0], w[1]);
        }
        for v in values {
            assert_eq!(value_of_key(order_key(v)).map(f32::to_bits), Some(v.to_bits()));
        }
        assert_eq!(value_of_key(0), None);
    }
}
