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
