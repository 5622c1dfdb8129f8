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

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.81;

    /// Scenes from a small flume to a large basin, H/d from 0.05 to 0.6.
    fn cases() -> Vec<GoringSolitary> {
        [(0.02, 0.4), (0.1, 0.5), (0.3, 0.5), (1.0, 4.0)]
            .iter()
            .map(|&(h, d)| GoringSolitary::new(h, d, G).expect("valid"))
            .collect()
    }

    #[test]
    fn velocity_is_the_waves_depth_averaged_velocity_at_the_paddle() {
        // Goring's ODE: X' = c η(X, t) / (d + η(X, t)), η from the target wave at x = X(t).
        for m in cases() {
            let w = m.target_wave();
            let top = w.crest_velocity();
            for i in 0..=400 {
                let t = m.duration() * i as f64 / 400.0;
                let x = m.stroke(t);
                let ode = w.depth_averaged_velocity(x, t);
                assert!((m.velocity(t) - ode).abs() <= 1e-6 * top, "t = {t}");
            }
        }
    }

    #[test]
    fn the_closed_form_solves_the_ode() {
        // RK4 on dX/dt = c η(X, t) / (d + η(X, t)) from X(0) = 0, 20 000 steps over the duration
        // (global error O(Δt⁴): the steps' halving changes X by < 1e-12 S); the closed form
        // must agree to 1e-9 S, and its velocity with central differences of X to 1e-6 of the top.
        for m in cases() {
            let w = *m.target_wave();
            let rhs = |t: f64, x: f64| w.depth_averaged_velocity(x, t);
            let n = 20_000;
            let dt = m.duration() / n as f64;
            let mut x = 0.0;
            for i in 0..n {
                let t = i as f64 * dt;
                let k1 = rhs(t, x);
                let k2 = rhs(t + 0.5 * dt, x + 0.5 * dt * k1);
                let k3 = rhs(t + 0.5 * dt, x + 0.5 * dt * k2);
                let k4 = rhs(t + dt, x + dt * k3);
                x += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
                if (i + 1) % 500 == 0 {
                    let t1 = (i + 1) as f64 * dt;
                    let s = m.goring_stroke();
                    assert!(
                        (x - m.stroke(t1)).abs() <= 1e-9 * s,
                        "t = {t1}: {x} vs {}",
                        m.stroke(t1)
                    );
                }
            }
            let h = 1e-6 * m.duration();
            for i in 1..100 {
                let t = m.duration() * i as f64 / 100.0;
                let fd = (m.stroke(t + h) - m.stroke(t - h)) / (2.0 * h);
                assert!((fd - m.velocity(t)).abs() <= 1e-6 * w.crest_velocity(), "t = {t}");
            }
        }
    }

    #[test]
    fn starts_at_rest_and_ends_at_goring_stroke() {
        for m in cases() {
            let w = m.target_wave();
            let s = (16.0 * w.height() * w.depth() / 3.0).sqrt();
            assert!((m.goring_stroke() / s - 1.0).abs() < 1e-14);
            assert_eq!(m.stroke(0.0), 0.0);
            // Goring's cut at |θ| = 3.8: sech²(3.8) = 2.0e-3 of the top speed (times (d + H) /
            // d at most), and 1 / (e^7.6 + 1) = 5.0e-4 of the stroke short.
            assert!(m.velocity(0.0) <= 2.1e-3 * (1.0 + w.height() / w.depth()) * w.crest_velocity());
            assert!((m.final_stroke() / s - 1.0).abs() < 5.1e-4);
            // Nearly at rest again at `duration`, and at rest long after.
            assert!((m.stroke(m.duration()) / s - 1.0).abs() < 1.1e-3);
            assert!(m.velocity(m.duration()) <= 2.1e-3 * (1.0 + w.height() / w.depth()) * w.crest_velocity());
            assert_eq!(m.stroke(1e3 * m.duration()), m.final_stroke());
            assert_eq!((m.stroke(-1.0), m.velocity(-1.0)), (0.0, 0.0));
            // The paddle moves the wave's water: S d = ∫ η dx (both 2H / k).
            assert!((m.goring_stroke() * w.depth() / w.volume_per_width() - 1.0).abs() < 1e-14);
        }
    }

    #[test]
    fn the_top_speed_is_the_crest_velocity() {
        for m in cases() {
            let top = m.target_wave().crest_velocity();
            assert!((m.velocity(m.crest_time()) - top).abs() <= 1e-6 * top);
            let sampled = (0..=2000).map(|i| m.velocity(m.duration() * i as f64 / 2000.0));
            let sampled = crate::validation::largest(sampled, 0.0);
            assert!(
                sampled <= top * (1.0 + 1e-12) && sampled >= top * (1.0 - 1e-4),
                "{sampled}"
            );
            // The crest is at the paddle then.
            let crest_x = m.target_wave().crest_x0() + m.target_wave().celerity() * m.crest_time();
            assert!((crest_x - m.stroke(m.crest_time())).abs() <= 1e-12 * m.goring_stroke());
        }
    }

    #[test]
    fn goring_duration_covers_the_phases_within_3_8() {
        // θ runs from −3.8 to 3.8 in Goring's T: k c T = 7.6 + k ΔX (derivation in the doc).
        for m in cases() {
            let w = m.target_wave();
            let start = m.crest_time() - 0.5 * m.goring_duration();
            let end = m.crest_time() + 0.5 * m.goring_duration();
            let theta = |t: f64| w.wavenumber() * (w.celerity() * t - m.stroke(t)) - m.start_phase;
            // ΔX over T is S tanh 3.8, not S: the ends are within (1 − tanh 3.8) / 2 of ±3.8 in θ.
            assert!((theta(start) + 3.8).abs() < 1e-3, "{}", theta(start));
            assert!((theta(end) - 3.8).abs() < 1e-3, "{}", theta(end));
        }
    }

    #[test]
    fn range_is_from_rest_to_the_stroke_reached() {
        let m = GoringSolitary::new(0.1, 0.5, G).expect("valid");
        assert_eq!(m.range(m.crest_time()), (0.0, m.stroke(m.crest_time())));
        assert_eq!(m.range(0.0), (0.0, 0.0));
        assert!(GoringSolitary::new(-0.1, 0.5, G).is_err());
    }
}
