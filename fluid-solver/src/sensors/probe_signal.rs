//! Roughness measures of a probe's time series that compare methods with different time steps.
//!
//! The RMS of the step-to-step change favours the method with the more, smaller steps: a
//! smooth signal changes by `(dp/dt) Δt` per step. So besides it, each series is measured
//! - per unit time, `RMS(Δp/Δt)` over the steps, weighted by each step's length (a smooth signal
//!   reads its own `dp/dt` whatever the step; a step-to-step jitter σ reads σ/Δt);
//! - resampled (linear interpolation) on a common grid of spacing `h` (ISPH's Δt), as the RMS of
//!   the change from one grid point to the next;
//! - high-passed on that grid: the signal minus its centred moving average over
//!   `2 HALF_WINDOW + 1` points (about 10 ISPH steps), as an RMS: the part of the signal that
//!   varies faster than the window, whatever the step.

/// Points each side of the centre of the moving average of [`Series::high_pass_rms`].
pub const HALF_WINDOW: usize = 5;

/// A probe's reading after each step, `(time, value)`, times increasing; the reading before
/// the first step is the first entry.
#[derive(Debug, Clone, Default)]
pub struct Series(pub Vec<(f64, f64)>);

impl Series {
    /// RMS of the change from one step to the next (the measure).
    pub fn step_rms(&self) -> f64 {
        rms(self.0.windows(2).map(|w| w[1].1 - w[0].1))
    }

    /// Largest change from one step to the next.
    pub fn step_max(&self) -> f64 {
        self.0
            .windows(2)
            .map(|w| (w[1].1 - w[0].1).abs())
            .fold(0.0, f64::max)
    }

    /// `sqrt(Σ (Δp/Δt)² Δt / Σ Δt)` over the steps (steps of zero length left out).
    pub fn rate_rms(&self) -> f64 {
        let (mut s, mut t) = (0.0, 0.0);
        for w in self.0.windows(2) {
            let dt = w[1].0 - w[0].0;
            if dt > 0.0 {
                s += (w[1].1 - w[0].1).powi(2) / dt;
                t += dt;
            }
        }
        if t > 0.0 {
            (s / t).sqrt()
        } else {
            0.0
        }
    }

    /// The series interpolated linearly at `t0 + k h` for every k within its time span.
    pub fn resampled(&self, h: f64) -> Vec<f64> {
        let s = &self.0;
        let (Some(first), Some(last)) = (s.first(), s.last()) else {
            return Vec::new();
        };
        let n = ((last.0 - first.0) / h + 1e-9).floor() as usize;
        let mut out = Vec::with_capacity(n + 1);
        let mut j = 0;
        for k in 0..=n {
            let t = first.0 + k as f64 * h;
            while j + 2 < s.len() && s[j + 1].0 < t {
                j += 1;
            }
            let (a, b) = (s[j], s[(j + 1).min(s.len() - 1)]);
            let f = if b.0 > a.0 {
                ((t - a.0) / (b.0 - a.0)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            out.push(a.1 + f * (b.1 - a.1));
        }
        out
    }

    /// RMS of the change between consecutive points of [`Series::resampled`] at `h`.
    pub fn resampled_step_rms(&self, h: f64) -> f64 {
        rms(self.resampled(h).windows(2).map(|w| w[1] - w[0]))
    }

    /// RMS of the resampled signal minus its centred moving average (points whose window is
    /// whole).
    pub fn high_pass_rms(&self, h: f64) -> f64 {
        let s = self.resampled(h);
        let m = 2 * HALF_WINDOW + 1;
        rms(s
            .windows(m)
            .map(|w| w[HALF_WINDOW] - w.iter().sum::<f64>() / m as f64))
    }

    /// The readings with `lo ≤ t ≤ hi`.
    pub fn between(&self, lo: f64, hi: f64) -> Series {
        Series(
            self.0
                .iter()
                .copied()
                .filter(|r| r.0 >= lo && r.0 <= hi)
                .collect(),
        )
    }

    /// Time of the first reading above 0 (the probe wetted), if any.
    pub fn first_wet(&self) -> Option<f64> {
        self.0.iter().find(|r| r.1 > 0.0).map(|r| r.0)
    }

    /// Largest reading.
    pub fn max(&self) -> f64 {
        self.0.iter().map(|r| r.1).fold(f64::NEG_INFINITY, f64::max)
    }
}

/// Root mean square (0 for no values).
fn rms(values: impl Iterator<Item = f64>) -> f64 {
    let (mut s, mut n) = (0.0, 0usize);
    for v in values {
        s += v * v;
        n += 1;
    }
    if n > 0 {
        (s / n as f64).sqrt()
    } else {
        0.0
    }
}
