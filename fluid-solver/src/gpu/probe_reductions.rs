//! What the global probes read, reduced on the device (`shaders/probe_reductions.wgsl`): the
//! water's extent along each axis (all a surge-front probe reads) and the highest water resting
//! on a solid (the run-up gauge's), over the fluid particles that are water, not spray
//! ([`crate::sensors::probes`]). A probe row then needs no copy of the particles: one pass over
//! them and a few bytes back.

use super::step::GpuEmps;

/// The words after the cells' counts the passes write (`OPEN_COUNTERS` counts them in): the
/// extent's six, the run-up's one.
const EXTENT_WORDS: (u64, u64) = (4, 6);
const RUN_UP_WORDS: (u64, u64) = (11, 1);

/// The f32 value of a key of the shader's `order_key`; `None` for the zero the host cleared it
/// to (no particle wrote one).
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
        let keys = self.reduce_keys(&self.kernels.water_extent, EXTENT_WORDS)?;
        let origin = self.frame.origin;
        let mut extent = [[0.0; 2]; 3];
        for a in 0..3 {
            let most = value_of_key(keys[2 * a])?;
            let least = value_of_key(keys[2 * a + 1])?;
            extent[a] = [origin[a] + f64::from(most), origin[a] - f64::from(least)];
        }
        Some(extent)
    }

    /// The highest z (in the case's frame) of the water resting on a wall or body particle, as
    /// the CPU's run-up gauge decides it; `Some(None)` when none rests, `None` with wide
    /// positions (the caller reads a light copy).
    pub fn run_up_top(&self) -> Option<Option<f64>> {
        let keys = self.reduce_keys(&self.kernels.run_up, RUN_UP_WORDS)?;
        Some(value_of_key(keys[0]).map(|z| self.frame.origin[2] + f64::from(z)))
    }

    /// Runs `pass` over the particles into the words `(first, count)` past the cells' counts and
    /// reads them; `None` with wide positions or no particles.
    fn reduce_keys(&self, pass: &wgpu::ComputePipeline, (first, count): (u64, u64)) -> Option<Vec<u32>> {
        if self.buffers.wide || self.is_empty() {
            return None;
        }
        let words = first..first + count;
        Some(self.counter_pass(pass, words.clone(), words))
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
