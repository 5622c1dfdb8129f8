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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn starts_at_rest_and_ends_at_one_with_zero_slope() {
        let ramp = Ramp::new(2.0).expect("valid");
        assert_eq!(ramp.factor(0.0), 0.0);
        assert_eq!(ramp.rate(0.0), 0.0);
        assert_eq!(ramp.factor(-1.0), 0.0);
        assert!((ramp.factor(1.0) - 0.5).abs() < 1e-15, "half way at T_r / 2");
        assert_eq!(ramp.factor(2.0), 1.0);
        assert_eq!(ramp.rate(2.0), 0.0);
        assert_eq!(ramp.factor(5.0), 1.0);
        // r' → 0 at both ends: continuous velocity at t = 0 and t = T_r.
        assert!(ramp.rate(1e-9) < 1e-8 && ramp.rate(2.0 - 1e-9) < 1e-8);
    }

    #[test]
    fn rate_is_the_derivative_of_factor() {
        // Central differences of r against r' (truncation h²/6 |r'''| ≤ h² π³/(12 T_r³) < 1e-9 here).
        let ramp = Ramp::new(1.5).expect("valid");
        let h = 1e-5;
        for i in 1..150 {
            let t = i as f64 * 0.01;
            let fd = (ramp.factor(t + h) - ramp.factor(t - h)) / (2.0 * h);
            assert!(
                (fd - ramp.rate(t)).abs() < 1e-8,
                "t = {t}: {fd} vs {}",
                ramp.rate(t)
            );
        }
    }

    #[test]
    fn apply_uses_the_product_rule() {
        // X₀ = sin t, X₀' = cos t: d/dt (r sin t) by central differences.
        let ramp = Ramp::new(3.0).expect("valid");
        let x = |t: f64| ramp.apply(t, t.sin(), t.cos());
        let h = 1e-5;
        for i in 1..30 {
            let t = i as f64 * 0.1;
            let fd = (x(t + h).0 - x(t - h).0) / (2.0 * h);
            assert!((fd - x(t).1).abs() < 1e-8, "t = {t}");
        }
    }

    #[test]
    fn no_ramp_is_one_and_bad_durations_are_refused() {
        assert_eq!(Ramp::NONE.factor(0.0), 1.0);
        assert_eq!(
            Ramp::new(0.0).expect("0 allowed").apply(0.3, 2.0, 5.0),
            (2.0, 5.0)
        );
        assert!(Ramp::new(-1.0).is_err());
        assert!(Ramp::new(f64::NAN).is_err());
        assert!(Ramp::new(f64::INFINITY).is_err());
    }
}
