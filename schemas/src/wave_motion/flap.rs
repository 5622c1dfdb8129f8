//! [`FlapMotion`]: a flap paddle, a wall that turns about a horizontal hinge along y, by the
//! stroke X(t) it makes at the still-water level.
//!
//! Geometry: the hinge lies l = floor − hinge_z at or below the flume floor under the paddle
//! (l = 0: hinged on the floor), the still water is d deep over the floor, so the still-water
//! level lies L = d + l above the hinge. A flap turned by θ (positive: its top into the tank)
//! moves its face at height s above the floor by (s + l) tan θ along x, a profile linear in s for
//! any θ; its stroke at the still-water level is X = L tan θ, so
//!
//!   θ(t) = atan(X(t) / L)   ([`FlapMotion::angle`]).
//!
//! **Regular waves** (linear wave-maker theory, Dean & Dalrymple 1991, "Water wave mechanics for
//! engineers and scientists", §6.3; derived here for any l). A paddle whose face moves by
//! (S(s)/2) sin ωt makes the progressive wave of height
//!
//!   H = 4 k sinh(kd) ∫₀ᵈ S(s) cosh(ks) ds / (sinh 2kd + 2kd)
//!
//! (the progressive mode cosh(ks) is orthogonal to the evanescent ones over the depth, with
//! ∫₀ᵈ cosh²(ks) ds = (sinh 2kd + 2kd)/(4k); η = (1/g) ∂φ/∂t at the surface, ω² = g k tanh kd).
//! A piston (S(s) = S) gives Biesel's 4 sinh² kd / (sinh 2kd + 2kd) ([`super::regular`]). A flap
//! has S(s) = S (s + l)/(d + l), and ∫₀ᵈ (s + l) cosh(ks) ds = ((d + l) sinh kd − (cosh kd − 1)/k)/k:
//!
//!   H/S = 4 sinh kd / (sinh 2kd + 2kd) · ((d + l) sinh kd − (cosh kd − 1)/k) / (d + l)
//!       = P(kd) · (1 − tanh(kd/2) / (kd (1 + l/d)))   ([`flap_height_to_stroke`]),
//!
//! P the piston's H/S, since (cosh x − 1)/sinh x = tanh(x/2); the second form has no
//! cancellation (tanh(x/2)/x ≤ ½). For l = 0 it is Dean & Dalrymple's flap,
//! 4 (sinh kd / kd) (kd sinh kd − cosh kd + 1)/(sinh 2kd + 2kd); as l → ∞ it tends to the
//! piston's. In shallow water (kd → 0) it tends to kd (d/2 + l)/(d + l): the piston's kd times
//! the flap's depth-averaged stroke over S.
//!
//! **Solitary wave** (our reading; Goring's (1978) method is a piston's): the flap's
//! depth-averaged displacement follows Goring's piston trajectory X_p(t), so it moves the same
//! water, X_p d = ∫₀ᵈ X (s + l)/(d + l) ds, and
//!
//!   X(t) = X_p(t) (d + l)/(d/2 + l)   ([`solitary_stroke_factor`]).
//!
//! It is an approximation: a solitary wave is a long wave, and in the long-wave limit a flap's
//! waves are those of a piston moved by its depth-averaged stroke (above), but near the paddle
//! the flap's flow is not the wave's depth-uniform one.
//!
//! **Table**: the CSV's X(t) is the stroke at the still-water level, ramped as a piston's.

use super::goring::GoringSolitary;
use super::regular::{height_to_stroke, RegularWaves};
use super::{PistonMotion, Ramp, StrokeTable};

/// The largest flap angle |θ| a case may ask for, degrees. Linear wave-maker theory, whose
/// transfer function the regular motion uses and on which Goring's reading rests, takes the
/// paddle's face as vertical and its displacement as small; a flap's face leans by θ and its
/// points rise or fall by a fraction 1 − cos θ of their distance from the hinge: 3.4 % at 15°,
/// 13 % at 30°, 29 % at 45°. Past 30° that is no longer a small correction.
pub const MAX_FLAP_ANGLE_DEG: f64 = 30.0;

/// H/S = P(kd) (1 − tanh(kd/2) / (kd (1 + l/d))) for kd > 0 and `hinge_below_over_depth` l/d ≥ 0:
/// the height of the waves a flap hinged l below the floor makes for a stroke S at the
/// still-water level, P the piston's [`height_to_stroke`] (module doc).
pub fn flap_height_to_stroke(kd: f64, hinge_below_over_depth: f64) -> f64 {
    height_to_stroke(kd) * (1.0 - (0.5 * kd).tanh() / (kd * (1.0 + hinge_below_over_depth)))
}

/// X / X_p = (d + l)/(d/2 + l): the flap's stroke at the still-water level for a depth-averaged
/// stroke X_p, with the still water `depth` d deep and the hinge `below` = l under the floor.
pub fn solitary_stroke_factor(depth: f64, below: f64) -> f64 {
    (depth + below) / (0.5 * depth + below)
}

/// Where a flap's hinge lies: `z` [m], `below` = l [m] under the floor, and the still water
/// `depth` = d [m] over the floor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlapHinge {
    z: f64,
    below: f64,
    depth: f64,
}

impl FlapHinge {
    /// The hinge at height `hinge_z` under a paddle whose bottom (the floor) is at `floor_z`, with
    /// `depth` of still water over the floor; refuses a hinge above the floor and a depth that is
    /// not finite and > 0.
    pub fn new(hinge_z: f64, floor_z: f64, depth: f64) -> Result<Self, String> {
        if !depth.is_finite() || depth <= 0.0 {
            return Err(format!(
                "the flap's still-water depth d must be finite and > 0, got {depth}"
            ));
        }
        if !hinge_z.is_finite() || !floor_z.is_finite() || hinge_z > floor_z {
            return Err(format!(
                "the flap's hinge must lie at or below the paddle's bottom z = {floor_z}, got {hinge_z}"
            ));
        }
        Ok(Self {
            z: hinge_z,
            below: floor_z - hinge_z,
            depth,
        })
    }

    /// z of the hinge, m.
    pub fn z(&self) -> f64 {
        self.z
    }

    /// l: the hinge's depth under the floor, m.
    pub fn below(&self) -> f64 {
        self.below
    }

    /// d: the still water's depth over the floor, m.
    pub fn depth(&self) -> f64 {
        self.depth
    }

    /// L = d + l: the still-water level's height above the hinge, m.
    pub fn lever(&self) -> f64 {
        self.depth + self.below
    }
}

/// A flap paddle's motion: its stroke X(t) at the still-water level (m, +x into the tank) as
/// `factor` times a piston motion's, and the angle that gives it (module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct FlapMotion {
    motion: PistonMotion,
    factor: f64,
    hinge: FlapHinge,
}

impl FlapMotion {
    /// The solitary wave of `height` H on the hinge's depth d under `gravity` g: Goring's piston
    /// motion for it, times [`solitary_stroke_factor`] (module doc).
    pub fn solitary(height: f64, gravity: f64, hinge: FlapHinge) -> Result<Self, String> {
        let goring = GoringSolitary::new(height, hinge.depth, gravity)?;
        Ok(Self {
            motion: PistonMotion::Solitary(goring),
            factor: solitary_stroke_factor(hinge.depth, hinge.below),
            hinge,
        })
    }

    /// Regular waves of `height` H and `period` T on the hinge's depth d under `gravity` g, by
    /// the flap's transfer function [`flap_height_to_stroke`], started by `ramp`.
    pub fn regular(
        height: f64,
        period: f64,
        gravity: f64,
        ramp: Ramp,
        hinge: FlapHinge,
    ) -> Result<Self, String> {
        let ratio = hinge.below / hinge.depth;
        let waves = RegularWaves::with_transfer(height, period, hinge.depth, gravity, ramp, |kd| {
            flap_height_to_stroke(kd, ratio)
        })?;
        Ok(Self {
            motion: PistonMotion::Regular(waves),
            factor: 1.0,
            hinge,
        })
    }

    /// The stroke at the still-water level from a table.
    pub fn table(table: StrokeTable, hinge: FlapHinge) -> Self {
        Self {
            motion: PistonMotion::Table(table),
            factor: 1.0,
            hinge,
        }
    }

    /// The hinge.
    pub fn hinge(&self) -> FlapHinge {
        self.hinge
    }

    /// X(t) at the still-water level, m.
    pub fn stroke(&self, t: f64) -> f64 {
        self.factor * self.motion.stroke(t)
    }

    /// X'(t), m/s.
    pub fn velocity(&self, t: f64) -> f64 {
        self.factor * self.motion.velocity(t)
    }

    /// (min, max) of X over [0, t_end], m.
    pub fn range(&self, t_end: f64) -> (f64, f64) {
        let (lo, hi) = self.motion.range(t_end);
        (self.factor * lo, self.factor * hi)
    }

    /// θ(t) = atan(X(t) / L), rad: positive turns the flap's top into the tank.
    pub fn angle(&self, t: f64) -> f64 {
        (self.stroke(t) / self.hinge.lever()).atan()
    }

    /// θ'(t) = X'(t) L / (L² + X(t)²), rad/s.
    pub fn angular_velocity(&self, t: f64) -> f64 {
        let (x, lever) = (self.stroke(t), self.hinge.lever());
        self.velocity(t) * lever / (lever * lever + x * x)
    }

    /// (min, max) of θ over [0, t_end], rad (θ increases with X).
    pub fn angle_range(&self, t_end: f64) -> (f64, f64) {
        let (lo, hi) = self.range(t_end);
        let lever = self.hinge.lever();
        ((lo / lever).atan(), (hi / lever).atan())
    }
}

/// Where the point at `rest` = (x, z) lies once turned by θ (`sin_cos` = (sin θ, cos θ)) about
/// the hinge `hinge` = (x_h, z_h), with r = rest − hinge:
///
///   x = x_h + r_x cos θ + r_z sin θ,   z = z_h − r_x sin θ + r_z cos θ.
pub fn turned(rest: [f64; 2], hinge: [f64; 2], (sin, cos): (f64, f64)) -> [f64; 2] {
    let r = [rest[0] - hinge[0], rest[1] - hinge[1]];
    [
        hinge[0] + r[0] * cos + r[1] * sin,
        hinge[1] - r[0] * sin + r[1] * cos,
    ]
}

/// ([x_min, z_min], [x_max, z_max]) that the rectangle `lo` … `hi` in the x–z plane sweeps as it
/// turns about `hinge` through every angle in [θ_lo, θ_hi] ⊂ (−π/2, π/2). Each corner's x and z
/// are sinusoids of θ, a cos θ + b sin θ, extreme at the interval's ends or where
/// tan θ = b / a; a rectangle's extent is its corners'.
pub fn swept_extent(
    lo: [f64; 2],
    hi: [f64; 2],
    hinge: [f64; 2],
    (theta_lo, theta_hi): (f64, f64),
) -> ([f64; 2], [f64; 2]) {
    let corners = [lo, [hi[0], lo[1]], [lo[0], hi[1]], hi];
    let mut angles = vec![theta_lo, theta_hi];
    for c in corners {
        let r = [c[0] - hinge[0], c[1] - hinge[1]];
        // x: r_x cos θ + r_z sin θ, stationary at tan θ = r_z / r_x; z: r_z cos θ − r_x sin θ,
        // at tan θ = −r_x / r_z.
        for (a, b) in [(r[0], r[1]), (r[1], -r[0])] {
            if a != 0.0 {
                angles.push((b / a).atan());
            }
        }
    }
    let (mut min, mut max) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for theta in angles.into_iter().filter(|t| (theta_lo..=theta_hi).contains(t)) {
        for c in corners {
            let p = turned(c, hinge, theta.sin_cos());
            for a in 0..2 {
                min[a] = min[a].min(p[a]);
                max[a] = max[a].max(p[a]);
            }
        }
    }
    (min, max)
}
