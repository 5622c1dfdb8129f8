//! [`GoringSolitary`]: the piston motion that makes a [`SolitaryWave`] (Goring 1978, "Tsunamis —
//! the propagation of long waves onto a shelf", Caltech report KH-R-38, §2).
//!
//! The paddle moves with the wave's depth-averaged velocity at its own position:
//!
//!   dX/dt = c η(X, t) / (d + η(X, t)),   η(X, t) = H sech² θ,   θ = k (c t − X) − a,
//!
//! with k, c of [`SolitaryWave`]. The ODE integrates in closed form (derived here): dθ = k (c dt −
//! dX), and the ODE reads d dX = η (c dt − dX) = (H / k) sech² θ dθ, so
//!
//!   X(t) = (H / (k d)) (tanh θ(t) + tanh a),
//!
//! which starts at X = 0 where θ = −a (t = 0) and tends to the stroke S = 2H / (k d) = √(16Hd/3)
//! (Goring 1978, §2). θ(t) is the root of F(θ) = θ + a − k c t + (H/d) (tanh θ + tanh a) = 0;
//! F' = 1 + (H/d) sech² θ ≥ 1, so the root is unique, and it lies in [k c t − a − 2H/d, k c t − a]
//! (0 ≤ k X ≤ 2H/d); a Newton iteration kept inside that bracket finds it to rounding. The
//! tests check the closed form against an RK4 integration of the ODE.
//!
//! Start: as Goring, the wave is cut at |θ| = a = 3.8 (η = sech²(3.8) H ≈ 0.002 H), and the paddle
//! moves for about T = 2 (3.8 + H/d) / (k c) ([`GoringSolitary::goring_duration`]): X(0) = 0, it
//! starts at 0.2 % of its top speed (a step in velocity of 0.4 mm/s for H/d = 0.2 on 0.1 m), and
//! its final stroke (H / (k d)) (1 + tanh a) falls short of S by 1 / (e^{2a} + 1) = 0.05 %. A
//! start further out (η = 10⁻⁶ H at a = 7.6) would smooth that step away, but it adds 3.8 / (k c)
//! of a barely moving paddle (0.9 s for that wave) that a run pays for in steps. The crest passes
//! the paddle's rest position at t ≈ a / (k c).

use super::solitary_wave::{sech_squared, SolitaryWave, GORING_PHASE};

/// Goring's (1978) solitary-wave piston motion (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GoringSolitary {
    wave: SolitaryWave,
    /// a: the phase distance of the start from the crest.
    start_phase: f64,
    /// H / d.
    relative_height: f64,
}

impl GoringSolitary {
    /// The motion for a solitary wave of `height` H on `depth` d under `gravity` g (all > 0).
    pub fn new(height: f64, depth: f64, gravity: f64) -> Result<Self, String> {
        let start_phase = GORING_PHASE;
        let wave = SolitaryWave::new(height, depth, gravity)?;
        Ok(Self {
            wave: wave.with_crest_at(-start_phase / wave.wavenumber()),
            start_phase,
            relative_height: height / depth,
        })
    }

    /// a: the phase distance of the start from the crest.
    pub fn start_phase(&self) -> f64 {
        self.start_phase
    }

    /// The wave this motion makes: crest at x = c t − a / k, x from the paddle's rest position.
    pub fn target_wave(&self) -> &SolitaryWave {
        &self.wave
    }

    /// S = 2H / (k d) = √(16 H d / 3), m: the stroke of the full motion (Goring 1978, §2).
    pub fn goring_stroke(&self) -> f64 {
        2.0 * self.relative_height / self.wave.wavenumber()
    }

    /// X(∞) = (H / (k d)) (1 + tanh a), m: where this paddle comes to rest (S to 0.05 %).
    pub fn final_stroke(&self) -> f64 {
        0.5 * self.goring_stroke() * (1.0 + self.start_phase.tanh())
    }

    /// T = 2 (3.8 + H/d) / (k c), s: Goring's (1978) duration of the motion (θ from −3.8 to 3.8:
    /// k c T = 7.6 + k S). Formula as coded in LEoPart's `SolitonPiston` (LEoPart-project/leopart,
    /// source/MeshVelocity.py, τ = 4 (3.8 + A/h) / (β c) with β = 2k); its form derived here.
    pub fn goring_duration(&self) -> f64 {
        2.0 * (GORING_PHASE + self.relative_height) / (self.wave.wavenumber() * self.wave.celerity())
    }

    /// The time at which θ = 0, the crest at the paddle, (a + (H/d) tanh a) / (k c), s; the
    /// velocity peaks there at c H / (d + H).
    pub fn crest_time(&self) -> f64 {
        let a = self.start_phase;
        (a + self.relative_height * a.tanh()) / (self.wave.wavenumber() * self.wave.celerity())
    }

    /// The time at which θ = +a, mirror of the start, 2 (a + (H/d) tanh a) / (k c), s: the paddle
    /// is then as slow as at t = 0 and within 0.05 % of S of [`Self::final_stroke`].
    pub fn duration(&self) -> f64 {
        2.0 * self.crest_time()
    }

    /// θ(t): the root of F(θ) = θ + a − k c t + (H/d)(tanh θ + tanh a) (module doc).
    fn phase(&self, t: f64) -> f64 {
        let (a, r) = (self.start_phase, self.relative_height);
        let kct = self.wave.wavenumber() * self.wave.celerity() * t;
        let f = |theta: f64| theta + a - kct + r * (theta.tanh() + a.tanh());
        let (mut lo, mut hi) = (kct - a - 2.0 * r, kct - a);
        let mut theta = hi - r * (1.0 + hi.tanh());
        for _ in 0..100 {
            let value = f(theta);
            let newton = theta - value / (1.0 + r * sech_squared(theta));
            if (newton - theta).abs() <= 4.0 * f64::EPSILON * theta.abs().max(1.0) {
                return newton;
            }
            // F increases: the root lies below θ where F(θ) > 0.
            if value > 0.0 {
                hi = theta;
            } else {
                lo = theta;
            }
            theta = if newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
        }
        theta
    }

    /// X(t) = (H / (k d)) (tanh θ(t) + tanh a), m; 0 for t ≤ 0.
    pub fn stroke(&self, t: f64) -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        0.5 * self.goring_stroke() * (self.phase(t).tanh() + self.start_phase.tanh())
    }

    /// X'(t) = c η / (d + η) with η = H sech² θ(t), m/s; 0 for t < 0.
    pub fn velocity(&self, t: f64) -> f64 {
        if t < 0.0 {
            return 0.0;
        }
        self.wave
            .velocity_under(self.wave.height() * sech_squared(self.phase(t)))
    }

    /// The range of X over [0, t_end]: (0, X(t_end)), the motion only moves forward.
    pub fn range(&self, t_end: f64) -> (f64, f64) {
        (0.0, self.stroke(t_end))
    }
}
