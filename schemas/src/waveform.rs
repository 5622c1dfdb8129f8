//! Interpolation of interface data inside a coupling window.
//!
//! Data are exchanged at `samples + 1` equally spaced times of a window (start included).
//! Between them a solver reads its inputs at any time: linearly with two samples, by a
//! quadratic through three, and by a cubic through the four nearest samples otherwise
//! (local Lagrange interpolation: error O(h⁴) for smooth data, h the sample spacing).

use crate::message::{Fields, Waveform};

impl Waveform {
    /// Equally spaced times from `t0` to `t1`, `samples + 1` of them, ending exactly on `t1`.
    pub fn grid(t0: f64, t1: f64, samples: u32) -> Vec<f64> {
        let n = samples.max(1);
        (0..=n)
            .map(|j| {
                if j == n {
                    t1
                } else {
                    t0 + (t1 - t0) * f64::from(j) / f64::from(n)
                }
            })
            .collect()
    }

    /// The same `fields` at every time of `times` (data held constant over the window).
    pub fn constant(times: Vec<f64>, fields: &Fields) -> Waveform {
        let samples = vec![fields.clone(); times.len()];
        Waveform { times, samples }
    }

    /// Window start.
    pub fn start(&self) -> f64 {
        self.times.first().copied().unwrap_or(0.0)
    }

    /// Window end.
    pub fn end(&self) -> f64 {
        self.times.last().copied().unwrap_or(0.0)
    }

    /// The data at the window end.
    pub fn last(&self) -> Option<&Fields> {
        self.samples.last()
    }

    /// The data extrapolated to `t` (after the window) along the line through the last two
    /// samples; the last sample where there is only one, and for an array whose length differs
    /// between the two (a fracture re-declared the geometry in between: no line to extend).
    pub fn extrapolate(&self, t: f64) -> Fields {
        let n = self.times.len().min(self.samples.len());
        if n < 2 {
            return self.samples.first().cloned().unwrap_or_default();
        }
        let (t0, t1) = (self.times[n - 2], self.times[n - 1]);
        let weights = lagrange_weights(&[t0, t1], t);
        let sources = [self.samples[n - 2].arrays(), self.samples[n - 1].arrays()];
        let mut out = self.samples[n - 1].clone();
        for (a, (_, array)) in out.arrays_mut().into_iter().enumerate() {
            let (s0, s1) = (sources[0][a].1, sources[1][a].1);
            if s0.len() != s1.len() {
                continue;
            }
            for ((value, v0), v1) in array.iter_mut().zip(s0.iter()).zip(s1.iter()) {
                *value = weights[0] * v0 + weights[1] * v1;
            }
        }
        out
    }

    /// The data interpolated at time `t` (clamped to the window). Refused when an array's length
    /// differs between the samples interpolated (the contract: a fracture re-declares the geometry
    /// at a window's end, so every sample of one window has the same lengths), instead of reading
    /// the missing values as zeros.
    pub fn at(&self, t: f64) -> Result<Fields, String> {
        let n = self.times.len().min(self.samples.len());
        if n == 0 {
            return Ok(Fields::default());
        }
        if n == 1 {
            return Ok(self.samples[0].clone());
        }
        let t = t.clamp(self.times[0], self.times[n - 1]);
        let (first, count) = stencil(&self.times[..n], t);
        let weights = lagrange_weights(&self.times[first..first + count], t);
        let sources: Vec<_> = self.samples[first..first + count]
            .iter()
            .map(Fields::arrays)
            .collect();
        let mut out = self.samples[first].clone();
        for (a, (name, array)) in out.arrays_mut().into_iter().enumerate() {
            for (j, source) in sources.iter().enumerate().skip(1) {
                if source[a].1.len() != array.len() {
                    return Err(format!(
                        "interface window {} … {} s: `{name}` has {} values at t = {} s and {} at t = {} s; the samples of one window must have equal lengths (a re-declared geometry takes effect at a window's end)",
                        self.start(),
                        self.end(),
                        array.len(),
                        self.times[first],
                        source[a].1.len(),
                        self.times[first + j]
                    ));
                }
            }
            for (k, value) in array.iter_mut().enumerate() {
                *value = weights
                    .iter()
                    .zip(&sources)
                    .map(|(w, source)| w * source[a].1[k])
                    .sum();
            }
        }
        Ok(out)
    }
}

/// First index and length of the (up to 4) samples nearest to `t`.
fn stencil(times: &[f64], t: f64) -> (usize, usize) {
    let count = times.len().min(4);
    let interval = times
        .windows(2)
        .position(|w| t <= w[1])
        .unwrap_or(times.len() - 2);
    let first = interval.saturating_sub((count - 1) / 2).min(times.len() - count);
    (first, count)
}

/// Lagrange basis weights of the nodes `x` at `t`.
fn lagrange_weights(x: &[f64], t: f64) -> Vec<f64> {
    (0..x.len())
        .map(|i| {
            (0..x.len())
                .filter(|&j| j != i)
                .map(|j| (t - x[j]) / (x[i] - x[j]))
                .product()
        })
        .collect()
}
