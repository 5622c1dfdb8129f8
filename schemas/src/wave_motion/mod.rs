//! The motions of a wave maker's paddle, as pure functions of time: a piston, a vertical paddle
//! across the tank that moves along +x (into the tank) by X(t) from its rest position, or a flap
//! that turns about a hinge so that its face moves by X(t) at the still-water level.
//!
//! - [`goring`]: Goring's (1978) motion for a solitary wave, [`solitary_wave`]: that wave;
//! - [`regular`]: regular waves by linear wave-maker theory (Biesel's transfer function);
//! - [`stroke_table`]: a stroke read from a CSV table;
//! - [`ramp`]: the raised-cosine start of the regular and table motions;
//! - [`flap`]: a flap's angle, its transfer function and its reading of Goring's motion.
//!
//! [`PistonMotion`] holds one of the first three; [`WaveMakerMotion`] a piston's or a flap's.
//! The solver moves the paddle's wall particles by [`PistonMotion::stroke`] at
//! [`PistonMotion::velocity`] (a flap's by [`FlapMotion::angle`]), and
//! [`PistonMotion::range`] says how far the paddle travels, to refuse one that would leave the
//! tank.

pub mod flap;
pub mod goring;
pub mod ramp;
pub mod regular;
pub mod solitary_wave;
pub mod stroke_table;

pub use flap::{FlapHinge, FlapMotion};
pub use goring::GoringSolitary;
pub use ramp::Ramp;
pub use regular::RegularWaves;
pub use solitary_wave::SolitaryWave;
pub use stroke_table::StrokeTable;

/// A wave maker's motion: a piston's stroke, or a flap's (its stroke at the still-water level
/// and the angle that gives it).
#[derive(Debug, Clone, PartialEq)]
pub enum WaveMakerMotion {
    /// A paddle that translates along +x by the stroke.
    Piston(PistonMotion),
    /// A paddle that turns about its hinge.
    Flap(FlapMotion),
}

impl WaveMakerMotion {
    /// X(t), m: a flap's at the still-water level.
    pub fn stroke(&self, t: f64) -> f64 {
        match self {
            Self::Piston(m) => m.stroke(t),
            Self::Flap(m) => m.stroke(t),
        }
    }

    /// X'(t), m/s.
    pub fn velocity(&self, t: f64) -> f64 {
        match self {
            Self::Piston(m) => m.velocity(t),
            Self::Flap(m) => m.velocity(t),
        }
    }

    /// (min, max) of X over [0, t_end], m.
    pub fn range(&self, t_end: f64) -> (f64, f64) {
        match self {
            Self::Piston(m) => m.range(t_end),
            Self::Flap(m) => m.range(t_end),
        }
    }
}

/// A piston paddle's motion: X(t) (m) from the rest position, +x into the tank, and X'(t) (m/s).
/// Every motion stands still at X(0) before t = 0.
#[derive(Debug, Clone, PartialEq)]
pub enum PistonMotion {
    /// One solitary wave (Goring 1978).
    Solitary(GoringSolitary),
    /// Regular waves by linear theory, ramped in.
    Regular(RegularWaves),
    /// A stroke from a CSV table, ramped in.
    Table(StrokeTable),
}

impl PistonMotion {
    /// X(t), m.
    pub fn stroke(&self, t: f64) -> f64 {
        match self {
            Self::Solitary(m) => m.stroke(t),
            Self::Regular(m) => m.stroke(t),
            Self::Table(m) => m.stroke(t),
        }
    }

    /// X'(t), m/s.
    pub fn velocity(&self, t: f64) -> f64 {
        match self {
            Self::Solitary(m) => m.velocity(t),
            Self::Regular(m) => m.velocity(t),
            Self::Table(m) => m.velocity(t),
        }
    }

    /// (min, max) of X over [0, t_end], m.
    pub fn range(&self, t_end: f64) -> (f64, f64) {
        match self {
            Self::Solitary(m) => m.range(t_end),
            Self::Regular(m) => m.range(t_end),
            Self::Table(m) => m.range(t_end),
        }
    }

    /// The time from which the paddle stands still, s; `None` for regular waves, which never stop.
    /// For the solitary motion, the time at which it is as slow as at the start
    /// ([`GoringSolitary::duration`]).
    pub fn duration(&self) -> Option<f64> {
        match self {
            Self::Solitary(m) => Some(m.duration()),
            Self::Regular(_) => None,
            Self::Table(m) => Some(m.duration()),
        }
    }
}

/// (min, max) of a motion `x` with velocity `v` over [0, t_end]: the largest and smallest of x at
/// 0, t_end, the `breaks` between them (kinks, where v jumps) and every zero of v between the
/// breaks. Each piece between breaks is sampled every `step` (at most 10⁷ samples a piece);
/// a sign change of v between samples is bisected to rounding. Only a pair of zeros closer than
/// `step` goes unseen, a wiggle of x smaller than |x''| step² / 8.
pub fn extremes(
    x: impl Fn(f64) -> f64,
    v: impl Fn(f64) -> f64,
    breaks: &[f64],
    t_end: f64,
    step: f64,
) -> (f64, f64) {
    let t_end = t_end.max(0.0);
    let mut knots: Vec<f64> = std::iter::once(0.0)
        .chain(breaks.iter().copied().filter(|&b| b > 0.0 && b < t_end))
        .chain(std::iter::once(t_end))
        .collect();
    knots.sort_by(f64::total_cmp);
    knots.dedup();
    let (mut lo, mut hi) = (x(0.0), x(0.0));
    let mut visit = |t: f64| {
        let value = x(t);
        lo = lo.min(value);
        hi = hi.max(value);
    };
    for piece in knots.windows(2) {
        let (a, b) = (piece[0], piece[1]);
        visit(b);
        let n = if step > 0.0 {
            ((b - a) / step).ceil().clamp(1.0, 1e7) as usize
        } else {
            1
        };
        // v at the piece's own side of a break: just inside its ends.
        let inset = 1e-9 * (b - a);
        let at = |i: usize| (a + (b - a) * i as f64 / n as f64).clamp(a + inset, b - inset);
        let mut s0 = at(0);
        let mut v0 = v(s0);
        for i in 1..=n {
            let s1 = at(i);
            let v1 = v(s1);
            if v0 == 0.0 {
                visit(s0);
            } else if v0 * v1 < 0.0 {
                let (mut l, mut r) = (s0, s1);
                for _ in 0..200 {
                    let m = 0.5 * (l + r);
                    if m <= l || m >= r {
                        break;
                    }
                    if v(m) * v0 > 0.0 {
                        l = m;
                    } else {
                        r = m;
                    }
                }
                visit(0.5 * (l + r));
            }
            (s0, v0) = (s1, v1);
        }
        if v0 == 0.0 {
            visit(s0);
        }
    }
    (lo, hi)
}
