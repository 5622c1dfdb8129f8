//! [`Ramp`]: a smooth start for a paddle motion, r(t) = ½(1 − cos(π t / T_r)) for 0 ≤ t < T_r.
//!
//! The raised-cosine ramp is the usual start of a laboratory or numerical wave maker: it takes
//! the paddle from rest (r = r' = 0 at t = 0) to the full motion (r = 1, r' = 0 at t = T_r)
//! with a continuous velocity. A ramped motion is X(t) = r(t) X₀(t), so its velocity is, by the
//! product rule, X'(t) = r'(t) X₀(t) + r(t) X₀'(t) with r'(t) = (π / (2 T_r)) sin(π t / T_r);
//! [`Ramp::apply`] returns both.

/// A raised-cosine start of `duration` seconds (0: no ramp, r ≡ 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ramp {
    duration: f64,
}

impl Ramp {
    /// No ramp: the motion starts at full amplitude (an impulsive start when X₀'(0) ≠ 0).
    pub const NONE: Ramp = Ramp { duration: 0.0 };

    /// A ramp of `duration` s; refuses a negative or non-finite duration.
    pub fn new(duration: f64) -> Result<Self, String> {
        if !duration.is_finite() || duration < 0.0 {
            return Err(format!(
                "the ramp must be a finite duration ≥ 0 s, got {duration}"
            ));
        }
        Ok(Self { duration })
    }

    /// T_r, s (0 for none).
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// r(t) = ½(1 − cos(π t / T_r)) on [0, T_r), 0 before, 1 after (1 everywhere when T_r = 0).
    pub fn factor(&self, t: f64) -> f64 {
        if self.duration == 0.0 || t >= self.duration {
            1.0
        } else if t <= 0.0 {
            0.0
        } else {
            0.5 * (1.0 - (std::f64::consts::PI * t / self.duration).cos())
        }
    }

    /// r'(t) = (π / (2 T_r)) sin(π t / T_r) on (0, T_r), 0 elsewhere.
    pub fn rate(&self, t: f64) -> f64 {
        if self.duration == 0.0 || t <= 0.0 || t >= self.duration {
            0.0
        } else {
            let w = std::f64::consts::PI / self.duration;
            0.5 * w * (w * t).sin()
        }
    }

    /// The ramped motion (r X₀, r' X₀ + r X₀') from the unramped stroke `x` and velocity `v` at `t`.
    pub fn apply(&self, t: f64, x: f64, v: f64) -> (f64, f64) {
        let r = self.factor(t);
        (r * x, self.rate(t) * x + r * v)
    }
}
