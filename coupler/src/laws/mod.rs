//! Interface laws as plug-ins of one trait: each turns the participants' outputs at one instant
//! into contributions to their inputs, and says what force it gave to each side.
//!
//! - [`spring`]: `[[coupling.spring]]`, a linear spring between two point masses.
//! - [`body`]: `[[coupling.body]]`, a resolved rigid body (force to the structure, motion to the fluid).
//! - [`drag`]: `[[coupling.drag]]`, unresolved drag and buoyancy on thin frame members (S2).
//! - [`reference`]: `participant/name` references of the case, bound to what participants declared.
//!
//! Each output array of the inputs (`point_force`, `body_force`, …) is written by one law only, so
//! a law can sum the arrays it owns to tell the ledger the force it gave.
//!
//! State across windows: a law changes only in [`Law::geometry`] and [`Law::accept`], which the
//! scheme calls once a window is accepted; the iterations of an implicit window use `&self`
//! only, so a checkpoint/restore of the participants never meets a law that moved on. What a law
//! keeps goes into the coupler's checkpoint manifest ([`Law::save`], [`Law::restore`]).

pub mod body;
pub mod drag;
pub mod reference;
pub mod spring;

use schemas::message::{Fields, Geometry};

/// The outputs of every participant at one instant.
#[derive(Clone, Copy)]
pub struct Instant<'a> {
    /// As they stood when the sweep began (two-sided laws read these, so both ends get `±f`).
    pub start: &'a [&'a Fields],
    /// With the fresh outputs of the participants already advanced in this sweep (one-way
    /// transfers read these, so the serial order passes fresh data on).
    pub current: &'a [&'a Fields],
}

/// An interface law between participants.
pub trait Law: Send {
    /// Adds this law's share of participant `p`'s inputs at one instant.
    fn add_inputs(&self, p: usize, at: Instant, inputs: &mut Fields);

    /// Checks that participant `p`'s outputs hold what this law reads, at the sizes it needs.
    fn check_outputs(&self, p: usize, outputs: &Fields) -> Result<(), String>;

    /// The force (3 components) this law gave participant `p` at one instant, from the inputs it
    /// handed over and the outputs in which `p` reports the reactions it took itself.
    fn force_given(&self, p: usize, inputs: &Fields, outputs: &Fields) -> [f64; 3];

    /// Work this law's forces did on participant `p` over a window (0 where it cannot tell).
    fn window_work(&self, p: usize, inputs: &[Fields], outputs: &[Fields]) -> f64;

    /// The energy account of one window (`inputs[p][j]`, `outputs[p][j]` at the window's
    /// sample `times[j]`, j = 0 the window start): the work this law's forces and motions did on each
    /// participant and the energy stored in the law itself. For the [`crate::stability`] detector.
    fn window_energy(&self, times: &[f64], inputs: &[Vec<Fields>], outputs: &[Vec<Fields>]) -> LawEnergy;

    /// The magnitude this law compares participant `p`'s output array `field` with, over the
    /// window's `outputs` (0 where it sets none): the implicit iteration measures that field's
    /// residual and weighs it in the acceleration against at least this, so a field the law
    /// reads only as a small correction (a member's velocity, subtracted from the flow's) is not
    /// held to its own, tiny, magnitude.
    fn field_scale(&self, _p: usize, _field: &str, _outputs: &[Vec<Fields>]) -> f64 {
        0.0
    }

    /// Participant `p` declared a (new) member geometry; `outputs` are its outputs as it did.
    fn geometry(&mut self, _p: usize, _geometry: &Geometry, _outputs: &Fields) -> Result<(), String> {
        Ok(())
    }

    /// Completes participant `p`'s outputs with the arrays this law reads that `p` cannot produce
    /// yet, at their neutral value: its initial outputs (t = 0, before its first window), and
    /// its last outputs after a geometry was re-declared (arrays whose length follows the
    /// geometry), so that every window of an implicit run has outputs of one shape.
    fn complete_outputs(&self, _p: usize, _outputs: &mut Fields) {}

    /// The window was accepted with these outputs (`outputs[p][j]`, j over the window's samples):
    /// the law updates what it keeps across windows.
    fn accept(&mut self, _outputs: &[Vec<Fields>]) {}

    /// What this law keeps across windows, for a checkpoint (empty for a law that keeps nothing
    /// beyond its binding).
    fn save(&self) -> Vec<u8> {
        Vec::new()
    }

    /// Puts back what [`Law::save`] gave, after the geometry of the checkpoint was declared again.
    fn restore(&mut self, _saved: &[u8]) -> Result<(), String> {
        Ok(())
    }
}

/// What a law knows of the energy at the interface over one window.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LawEnergy {
    /// Work done on each participant (by index) by what the law handed it, or, where the law
    /// hands a participant a motion, by the reaction that participant reports [J].
    pub work: Vec<f64>,
    /// Energy stored in the law at the window start and end [J] (a spring's ½ k d²; 0 else).
    pub stored: [f64; 2],
    /// Rounding of these sums [J]: ε Σ |f| |x| over the samples (see [`work_rounding`]).
    pub rounding: f64,
    /// Energy the law's forces exchanged with the flow in the window whatever its sign [J], for
    /// a law whose work sums alone give no physical scale (drag: its forces do work on the fluid
    /// as it moves past a fixed member, which the work sums count as created); 0 for the others.
    /// It does not grow with the structure's own motion, so an instability still outgrows it.
    pub exchanged: f64,
}

impl LawEnergy {
    /// Energy the coupling created in the window: Σ_p W_p + ΔE_stored. An exact (converged,
    /// conservative) interface gives 0; partitioned coupling's lag gives the "artificial
    /// interface energy" (Piperno & Farhat 2001).
    pub fn created(&self) -> f64 {
        self.work.iter().sum::<f64>() + self.stored[1] - self.stored[0]
    }
}

/// Rounding of a trapezoidal work sum (arguments as [`trapezoid_work`]): ε Σ_j Σ_k |f_jk| |x_jk|.
/// Positions are absolute, so a body held at 100 m under 1e8 N "moves" by 1e-14 m of rounding
/// and seems to take 1e-6 J of work per sample.
pub fn work_rounding(
    forces: &[&[f64]],
    positions: &[&[f64]],
    force_stride: usize,
    position_stride: usize,
) -> f64 {
    let norm = |v: &[f64]| v.iter().take(3).map(|a| a * a).sum::<f64>().sqrt();
    forces
        .iter()
        .zip(positions)
        .map(|(f, x)| {
            f.chunks_exact(force_stride)
                .zip(x.chunks_exact(position_stride))
                .map(|(f, x)| norm(f) * norm(x))
                .sum::<f64>()
        })
        .sum::<f64>()
        * f64::EPSILON
}

/// Σ over 3-vectors stored at `offset` in chunks of `stride`.
pub fn sum_vectors(values: &[f64], stride: usize, offset: usize) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for chunk in values.chunks_exact(stride) {
        (0..3).for_each(|c| sum[c] += chunk[offset + c]);
    }
    sum
}

/// Work of forces `f` (3 at the start of each chunk of `force_stride`) along positions `x` (3 at
/// the start of each chunk of `position_stride`) over the samples of a window:
/// Σ_j ½ (f_j + f_{j+1}) · (x_{j+1} − x_j) (trapezoidal rule).
pub fn trapezoid_work(
    forces: &[&[f64]],
    positions: &[&[f64]],
    force_stride: usize,
    position_stride: usize,
) -> f64 {
    let mut work = 0.0;
    for j in 0..forces.len().min(positions.len()).saturating_sub(1) {
        let (f0, f1, x0, x1) = (forces[j], forces[j + 1], positions[j], positions[j + 1]);
        for (k, (a, b)) in f0
            .chunks_exact(force_stride)
            .zip(f1.chunks_exact(force_stride))
            .enumerate()
        {
            let (Some(p0), Some(p1)) = (
                x0.get(k * position_stride..k * position_stride + 3),
                x1.get(k * position_stride..k * position_stride + 3),
            ) else {
                continue;
            };
            work += (0..3).map(|c| 0.5 * (a[c] + b[c]) * (p1[c] - p0[c])).sum::<f64>();
        }
    }
    work
}
