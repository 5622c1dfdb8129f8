//! [`RegularWaves`]: a piston paddle making regular waves of height H and period T on depth d,
//! by linear (first-order) wave-maker theory (Dean & Dalrymple 1991, "Water wave mechanics for
//! engineers and scientists", §6.3; Biesel's transfer function):
//!
//! - the wavenumber k solves the linear dispersion relation ω² = g k tanh(k d), ω = 2π / T
//!   ([`wavenumber`]);
//! - height over stroke H / S = 2 (cosh 2kd − 1) / (sinh 2kd + 2kd), evaluated as
//!   2 tanh(kd) / (1 + 2kd / sinh 2kd) (the same, since cosh 2x − 1 = 2 sinh² x and
//!   sinh 2x = 2 sinh x cosh x; no cancellation at small kd, no overflow at large kd).
//!   It tends to 2 in deep water and to kd in shallow water (D&D §6.3);
//! - X(t) = r(t) (S / 2) sin ω t, with the [`Ramp`] r (product rule in the velocity).
//!
//! The transfer function was checked against its form in LEoPart's `PeriodicPiston`
//! (LEoPart-project/leopart, source/MeshVelocity.py: C = 4 sinh² kd / (2kd + sinh 2kd)), not
//! against the book itself; both limits are derived and tested below.

use super::ramp::Ramp;

/// Regular waves from a piston by linear wave-maker theory (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegularWaves {
    height: f64,
    period: f64,
    depth: f64,
    wavenumber: f64,
    stroke_length: f64,
    ramp: Ramp,
}

impl RegularWaves {
    /// Waves of `height` H (m) and `period` T (s) on `depth` d (m) under `gravity` g (m/s²),
    /// started by `ramp`; refuses values that are not finite and > 0.
    pub fn new(height: f64, period: f64, depth: f64, gravity: f64, ramp: Ramp) -> Result<Self, String> {
        Self::with_transfer(height, period, depth, gravity, ramp, height_to_stroke)
    }

    /// As [`RegularWaves::new`], with the paddle's transfer function H/S = `transfer`(kd) in
    /// place of the piston's: the stroke S = H / transfer(kd) (a flap's,
    /// [`super::flap::flap_height_to_stroke`], where S is its stroke at the still-water level).
    pub fn with_transfer(
        height: f64,
        period: f64,
        depth: f64,
        gravity: f64,
        ramp: Ramp,
        transfer: impl Fn(f64) -> f64,
    ) -> Result<Self, String> {
        for (name, v) in [
            ("wave height H", height),
            ("period T", period),
            ("depth d", depth),
            ("gravity g", gravity),
        ] {
            if !v.is_finite() || v <= 0.0 {
                return Err(format!(
                    "the regular waves' {name} must be finite and > 0, got {v}"
                ));
            }
        }
        let omega = 2.0 * std::f64::consts::PI / period;
        let k = wavenumber(omega, depth, gravity);
        Ok(Self {
            height,
            period,
            depth,
            wavenumber: k,
            stroke_length: height / transfer(k * depth),
            ramp,
        })
    }

    /// H, m.
    pub fn height(&self) -> f64 {
        self.height
    }

    /// T, s.
    pub fn period(&self) -> f64 {
        self.period
    }

    /// ω = 2π / T, rad/s.
    pub fn angular_frequency(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.period
    }

    /// k, 1/m: the root of ω² = g k tanh(k d).
    pub fn wavenumber(&self) -> f64 {
        self.wavenumber
    }

    /// L = 2π / k, m.
    pub fn wavelength(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.wavenumber
    }

    /// kd.
    pub fn relative_depth(&self) -> f64 {
        self.wavenumber * self.depth
    }

    /// S = H / (H/S), m: the paddle's excursion from end to end once the ramp is over (a flap's at
    /// the still-water level).
    pub fn stroke_length(&self) -> f64 {
        self.stroke_length
    }

    /// The start.
    pub fn ramp(&self) -> Ramp {
        self.ramp
    }

    /// X(t) = r(t) (S/2) sin ω t, m; 0 for t ≤ 0.
    pub fn stroke(&self, t: f64) -> f64 {
        self.motion(t).0
    }

    /// X'(t) = r'(t) (S/2) sin ω t + r(t) (S/2) ω cos ω t, m/s; 0 for t < 0.
    pub fn velocity(&self, t: f64) -> f64 {
        self.motion(t).1
    }

    fn motion(&self, t: f64) -> (f64, f64) {
        if t < 0.0 {
            return (0.0, 0.0);
        }
        let (omega, half) = (self.angular_frequency(), 0.5 * self.stroke_length);
        let (sin, cos) = (omega * t).sin_cos();
        self.ramp.apply(t, half * sin, half * omega * cos)
    }

    /// The range of X over [0, t_end]: X at the ends, at the ramp's end and at every zero of X'
    /// between, found on a grid of T / 64 (`extremes` in mod.rs).
    pub fn range(&self, t_end: f64) -> (f64, f64) {
        super::extremes(
            |t| self.stroke(t),
            |t| self.velocity(t),
            &[self.ramp.duration()],
            t_end,
            self.period / 64.0,
        )
    }
}

/// H / S = 2 (cosh 2kd − 1) / (sinh 2kd + 2kd) = 2 tanh kd / (1 + 2kd / sinh 2kd) for kd > 0
/// (Biesel's piston transfer function; Dean & Dalrymple 1991, §6.3).
pub fn height_to_stroke(kd: f64) -> f64 {
    2.0 * kd.tanh() / (1.0 + 2.0 * kd / (2.0 * kd).sinh())
}

/// k, 1/m: the root of the linear dispersion relation ω² = g k tanh(k d) (Dean & Dalrymple 1991,
/// §4), for ω, d, g > 0.
///
/// With x = k d and y = ω² d / g it is the root of G(x) = x − y coth x, which is increasing
/// (G' = 1 + y csch² x) and concave (G'' = −2 y csch² x coth x) on x > 0; Newton's iterates
/// from any x₀ with G(x₀) ≤ 0 rise monotonically to the root (each tangent lies above G). Both
/// x = y (tanh y < 1) and x = √y (tanh z < z) have x tanh x < y, i.e. G(x) < 0, so the start
/// x₀ = max(y, √y) is proven; it is also the deep- or shallow-water answer. The iteration stops
/// when a step is below 4 ε x (residual ~1e-15 relative).
pub fn wavenumber(omega: f64, depth: f64, gravity: f64) -> f64 {
    let y = omega * omega * depth / gravity;
    let mut x = y.max(y.sqrt());
    for _ in 0..100 {
        let sinh = x.sinh();
        let step = (x - y / x.tanh()) / (1.0 + y / (sinh * sinh));
        // Monotone from below: a step ≥ 0 until rounding; stop at rounding's level.
        x -= step;
        if -step <= 4.0 * f64::EPSILON * x {
            break;
        }
    }
    x / depth
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.81;

    #[test]
    fn the_wavenumber_solves_the_dispersion_relation() {
        // From kd ≈ 0.003 (a 200 s wave on 1 m) to kd ≈ 400 (0.3 s on 20 m).
        for &(period, depth) in &[
            (200.0, 1.0),
            (20.0, 0.5),
            (2.0, 0.5),
            (1.0, 0.5),
            (0.5, 2.0),
            (12.0, 30.0),
            (0.3, 20.0),
        ] {
            let omega = 2.0 * std::f64::consts::PI / period;
            let k = wavenumber(omega, depth, G);
            let residual = (G * k * (k * depth).tanh() - omega * omega).abs() / (omega * omega);
            assert!(residual < 1e-12, "T = {period}, d = {depth}: residual {residual}");
        }
    }

    #[test]
    fn the_wavenumber_tends_to_the_deep_and_shallow_water_limits() {
        // Deep: k → ω²/g, relative gap tanh(kd)⁻¹ − 1 ≈ 2 e^{−2kd} (below 1e-15 for kd > 18; rounding
        // of ω² d / g and k = x / d leaves a few ε).
        let omega = 2.0 * std::f64::consts::PI / 0.5;
        let k = wavenumber(omega, 10.0, G);
        assert!(k * 10.0 > 18.0 && (k * G / (omega * omega) - 1.0).abs() < 1e-14);
        // Shallow: k → ω / √(g d), relative gap ≈ (kd)² / 6 (x tanh x = x² (1 − x²/3 + …)).
        let omega = 2.0 * std::f64::consts::PI / 200.0;
        let (d, k) = (1.0, wavenumber(omega, 1.0, G));
        let shallow = omega / (G * d).sqrt();
        let gap = k / shallow - 1.0;
        assert!((gap / ((k * d).powi(2) / 6.0) - 1.0).abs() < 1e-3, "gap {gap}");
    }

    #[test]
    fn height_to_stroke_tends_to_2_in_deep_and_kd_in_shallow_water() {
        // Deep water: H/S = 2 − (4 + 8 kd) e^{−2kd} + … (expanding tanh and 1/sinh).
        for kd in [5.0f64, 10.0, 20.0] {
            let bound = (4.0 + 8.0 * kd) * (-2.0 * kd).exp() * 1.01 + 4.0 * f64::EPSILON;
            assert!((height_to_stroke(kd) - 2.0).abs() <= bound, "kd = {kd}");
        }
        assert_eq!(height_to_stroke(400.0), 2.0, "no overflow at large kd");
        // Shallow water: H/S = kd (1 + O((kd)⁴)): the (kd)² terms of tanh and 2kd / sinh 2kd
        // cancel; at kd = 0.01 the gap is below 1e-8.
        for kd in [1e-2f64, 1e-3, 1e-6] {
            assert!((height_to_stroke(kd) / kd - 1.0).abs() < 1e-8, "kd = {kd}");
        }
        // The book's form, where it is well conditioned.
        for kd in [0.3f64, 1.0, 2.5] {
            let book = 2.0 * ((2.0 * kd).cosh() - 1.0) / ((2.0 * kd).sinh() + 2.0 * kd);
            assert!((height_to_stroke(kd) / book - 1.0).abs() < 1e-14, "kd = {kd}");
        }
    }

    #[test]
    fn the_paddle_swings_by_s_after_a_smooth_start() {
        let ramp = Ramp::new(2.0).expect("valid");
        let w = RegularWaves::new(0.05, 1.2, 0.5, G, ramp).expect("valid");
        let s = w.stroke_length();
        assert!((w.height() / s - height_to_stroke(w.relative_depth())).abs() < 1e-15);
        assert_eq!((w.stroke(0.0), w.velocity(0.0)), (0.0, 0.0));
        // After the ramp, X = (S/2) sin ωt exactly; the velocity is X's derivative throughout.
        let t = 5.3;
        assert!((w.stroke(t) - 0.5 * s * (w.angular_frequency() * t).sin()).abs() < 1e-15);
        let h = 1e-6;
        for i in 1..200 {
            let t = i as f64 * 0.05;
            let fd = (w.stroke(t + h) - w.stroke(t - h)) / (2.0 * h);
            assert!((fd - w.velocity(t)).abs() < 1e-7, "t = {t}");
        }
        // Range: within the ramp, smaller than ±S/2; a period past it, exactly ±S/2.
        let (lo, hi) = w.range(1.0);
        assert!(lo > -0.5 * s && hi < 0.5 * s && hi > 0.0);
        let (lo, hi) = w.range(2.0 + w.period());
        assert!(
            (lo + 0.5 * s).abs() < 1e-12 * s && (hi - 0.5 * s).abs() < 1e-12 * s,
            "{lo} {hi}"
        );
    }

    #[test]
    fn range_finds_the_extremes_within_the_ramp() {
        // Against a dense sampling (10⁶ points over 3 s: X varies by < ω² S/2 Δt² / 8 ≈ 1e-12 m
        // between samples near an extreme).
        let w = RegularWaves::new(0.1, 1.0, 0.6, G, Ramp::new(2.5).expect("valid")).expect("valid");
        let t_end = 3.0;
        let n = 1_000_000;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..=n {
            let x = w.stroke(t_end * i as f64 / n as f64);
            lo = lo.min(x);
            hi = hi.max(x);
        }
        let (rlo, rhi) = w.range(t_end);
        assert!(
            (rlo - lo).abs() < 1e-11 && (rhi - hi).abs() < 1e-11,
            "{rlo} {lo} {rhi} {hi}"
        );
    }

    #[test]
    fn refuses_non_positive_values() {
        assert!(RegularWaves::new(0.1, 0.0, 1.0, G, Ramp::NONE).is_err());
        assert!(RegularWaves::new(-0.1, 1.0, 1.0, G, Ramp::NONE).is_err());
        let e = RegularWaves::new(0.1, 1.0, f64::NAN, G, Ramp::NONE).unwrap_err();
        assert!(e.contains("depth d"), "{e}");
    }
}
