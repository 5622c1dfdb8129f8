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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::f64s::F64s;

    fn wave(times: Vec<f64>, f: impl Fn(f64) -> f64) -> Waveform {
        let samples = times
            .iter()
            .map(|&t| Fields {
                point_force: F64s(vec![f(t), 2.0 * f(t)]),
                ..Fields::default()
            })
            .collect();
        Waveform { times, samples }
    }

    #[test]
    fn linear_data_are_extrapolated_exactly() {
        let w = wave(Waveform::grid(0.0, 1.0, 3), |t| 3.0 * t + 1.0);
        assert!((w.extrapolate(1.5).point_force[0] - 5.5).abs() < 1e-13);
    }

    #[test]
    fn grid_lands_exactly_on_the_end() {
        let g = Waveform::grid(0.1, 0.13, 3);
        assert_eq!(g.len(), 4);
        assert_eq!(g[3], 0.13);
        assert_eq!(g[0], 0.1);
    }

    #[test]
    fn two_samples_interpolate_linearly() {
        let w = wave(Waveform::grid(0.0, 1.0, 1), |t| 3.0 * t + 1.0);
        let f = w.at(0.25).unwrap_or_else(|e| panic!("{e}"));
        assert!((f.point_force[0] - 1.75).abs() < 1e-15);
        assert!((f.point_force[1] - 3.5).abs() < 1e-15);
    }

    #[test]
    fn cubic_data_are_reproduced_exactly_with_four_or_more_samples() {
        let cubic = |t: f64| 2.0 * t * t * t - t * t + 0.5 * t - 3.0;
        let w = wave(Waveform::grid(0.0, 1.0, 6), cubic);
        for t in [0.0, 0.05, 0.33, 0.5, 0.71, 0.99, 1.0] {
            let f = w.at(t).unwrap_or_else(|e| panic!("{e}"));
            assert!((f.point_force[0] - cubic(t)).abs() < 1e-13, "t = {t}");
        }
    }

    #[test]
    fn interpolation_error_falls_as_h_to_the_fourth() {
        // sin on [0, 1]: the max error with 8 and 16 samples should drop ~16× (order 4).
        let err = |n: u32| {
            let w = wave(Waveform::grid(0.0, 1.0, n), f64::sin);
            (0..=200)
                .map(|i| f64::from(i) / 200.0)
                .map(|t| (w.at(t).unwrap_or_else(|e| panic!("{e}")).point_force[0] - t.sin()).abs())
                .fold(0.0, f64::max)
        };
        let ratio = err(8) / err(16);
        assert!(ratio > 12.0, "error ratio {ratio} shows less than 4th order");
    }

    /// Issue 13: samples of one window whose array lengths differ (nodes added within it) are
    /// refused by name, not read with zeros for the missing values; equal lengths still pass.
    #[test]
    fn samples_of_different_lengths_are_refused() {
        let mut w = wave(Waveform::grid(0.0, 1.0, 2), |t| t);
        w.samples[2].point_force.0.push(7.0);
        let e = w.at(0.75).map(|_| ()).unwrap_err();
        assert!(
            e.contains("`point_force`") && e.contains("2 values") && e.contains("3 at t = 1"),
            "{e}"
        );
        w.samples[2].point_force.0.pop();
        assert!(w.at(0.75).is_ok());
    }
}
