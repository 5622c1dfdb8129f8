//! The interface state of one window as one vector: every participant's output arrays at the
//! window's samples after its start, in blocks (participant × array) that are scaled and
//! checked for convergence separately.

use schemas::message::Fields;
use std::collections::BTreeMap;

/// One block of the flat vector: participant `p`'s array `array` over all samples.
#[derive(Debug, Clone)]
pub struct Block {
    pub participant: usize,
    pub array: usize,
    pub name: &'static str,
    pub range: std::ops::Range<usize>,
}

/// Flattens `outputs[p][j]` for samples `j ≥ 1` into one vector and its block layout.
pub fn flatten(outputs: &[Vec<Fields>]) -> (Vec<f64>, Vec<Block>) {
    let mut x = Vec::new();
    let mut blocks = Vec::new();
    for (p, samples) in outputs.iter().enumerate() {
        let arrays = samples.first().map(|f| f.arrays().len()).unwrap_or(0);
        for a in 0..arrays {
            let start = x.len();
            let mut name = "";
            for sample in samples.iter().skip(1) {
                let list = sample.arrays();
                name = list[a].0;
                x.extend_from_slice(list[a].1);
            }
            if x.len() > start {
                blocks.push(Block {
                    participant: p,
                    array: a,
                    name,
                    range: start..x.len(),
                });
            }
        }
    }
    (x, blocks)
}

/// Writes `x` back into `outputs` (the inverse of [`flatten`] for the same shapes).
pub fn unflatten(x: &[f64], blocks: &[Block], outputs: &mut [Vec<Fields>]) {
    for b in blocks {
        let mut at = b.range.start;
        for sample in outputs[b.participant].iter_mut().skip(1) {
            let mut arrays = sample.arrays_mut();
            let array = &mut arrays[b.array].1;
            let n = array.len();
            array.copy_from_slice(&x[at..at + n]);
            at += n;
        }
    }
}

/// Scale of each block: the largest RMS of `h` on it over the sweeps of this window so far (1
/// where it has been zero), so fields of different units weigh alike in the acceleration.
/// `scales` holds the earlier sweeps' scales (empty at the first sweep) and grows: a field that
/// is still at rest in the first sweep (a structure the fluid's answer reaches one sweep later)
/// must not keep a scale of round-off size, which would let its residual swamp every other field
/// and stall Aitken's and IQN-ILS's step.
pub fn grow_scales(scales: &mut Vec<f64>, h: &[f64], blocks: &[Block]) {
    scales.resize(blocks.len(), 0.0);
    for (s, b) in scales.iter_mut().zip(blocks) {
        let rms = rms(&h[b.range.clone()]);
        if rms.is_finite() {
            *s = s.max(rms);
        }
    }
}

/// One weight per entry of the flat vector: 1 / its block's scale (1 where the scale is 0).
pub fn weights(len: usize, blocks: &[Block], scales: &[f64]) -> Vec<f64> {
    let mut w = vec![1.0; len];
    for (b, &s) in blocks.iter().zip(scales) {
        if s > 0.0 {
            w[b.range.clone()].iter_mut().for_each(|v| *v = 1.0 / s);
        }
    }
    w
}

/// Fraction of a field's largest RMS so far below which its own magnitude no longer sets the
/// residual's scale (a field passing through zero is not held to a tighter absolute accuracy).
const FLOOR_FRACTION: f64 = 0.1;

/// Largest RMS of each participant's output arrays over the accepted windows.
#[derive(Debug, Default)]
pub struct Magnitudes {
    rms: BTreeMap<(usize, &'static str), f64>,
}

impl Magnitudes {
    /// Takes in an accepted window's outputs.
    pub fn observe(&mut self, outputs: &[Vec<Fields>]) {
        let (x, blocks) = flatten(outputs);
        for b in &blocks {
            let rms = rms(&x[b.range.clone()]);
            let entry = self.rms.entry((b.participant, b.name)).or_insert(0.0);
            *entry = entry.max(rms);
        }
    }

    /// Every magnitude as (participant, array name, RMS), for a checkpoint.
    pub fn saved(&self) -> Vec<(usize, String, f64)> {
        self.rms
            .iter()
            .map(|((p, name), v)| (*p, name.to_string(), *v))
            .collect()
    }

    /// Takes back what [`Magnitudes::saved`] gave (names that are no array are left out).
    pub fn restore(&mut self, saved: &[(usize, String, f64)]) {
        let names: Vec<&'static str> = Fields::default().arrays().iter().map(|(n, _)| *n).collect();
        self.rms = saved
            .iter()
            .filter_map(|(p, name, v)| names.iter().find(|n| **n == name).map(|n| ((*p, *n), *v)))
            .collect();
    }

    /// The norm below which block `b`'s residual is measured against this floor instead.
    fn floor(&self, b: &Block) -> f64 {
        let rms = self.rms.get(&(b.participant, b.name)).copied().unwrap_or(0.0);
        FLOOR_FRACTION * rms * (b.range.len() as f64).sqrt()
    }
}

fn rms(v: &[f64]) -> f64 {
    (v.iter().map(|x| x * x).sum::<f64>() / v.len().max(1) as f64).sqrt()
}

/// The largest relative residual `|h − x| / max(|h|, floor)` over the blocks, with its block;
/// `law_scales` (one per block, an RMS per value; see [`crate::laws::Law::field_scale`]) raise
/// the floor where a law sets one.
pub fn worst_residual<'a>(
    x: &[f64],
    h: &[f64],
    blocks: &'a [Block],
    magnitudes: &Magnitudes,
    law_scales: &[f64],
) -> (f64, Option<&'a Block>) {
    let mut worst: (f64, Option<&Block>) = (0.0, None);
    for (k, b) in blocks.iter().enumerate() {
        let law_floor = law_scales.get(k).copied().unwrap_or(0.0) * (b.range.len() as f64).sqrt();
        let r: f64 = b.range.clone().map(|i| (h[i] - x[i]).powi(2)).sum::<f64>().sqrt();
        let n: f64 = b
            .range
            .clone()
            .map(|i| h[i] * h[i])
            .sum::<f64>()
            .sqrt()
            .max(magnitudes.floor(b))
            .max(law_floor);
        let rel = if r == 0.0 {
            0.0
        } else if n > 0.0 {
            r / n
        } else {
            f64::INFINITY
        };
        if worst.1.is_none() || rel > worst.0 {
            worst = (rel, Some(b));
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use schemas::F64s;

    #[test]
    fn flatten_and_unflatten_are_inverse() {
        let f = |a: f64| Fields {
            point_displacement: F64s(vec![a, a + 1.0]),
            body_force: F64s(vec![a * 2.0]),
            ..Fields::default()
        };
        let outputs = vec![vec![f(0.0), f(1.0), f(2.0)], vec![f(10.0), f(11.0), f(12.0)]];
        let (x, blocks) = flatten(&outputs);
        assert_eq!(x.len(), 2 * 2 * 3);
        let mut back = vec![vec![Fields::default(); 3], vec![Fields::default(); 3]];
        for (p, s) in back.iter_mut().enumerate() {
            *s = outputs[p].clone();
            s[1].point_displacement.0.fill(0.0);
        }
        unflatten(&x, &blocks, &mut back);
        assert_eq!(back, outputs);
    }
}
