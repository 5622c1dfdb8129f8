//! Acceleration of the implicit coupling iteration `x ← H(x)` in one window.
//!
//! `x` is the interface data the sweep started from, `H(x)` what it produced, `r = H(x) − x`
//! the residual. Vectors come unscaled; `weights` (one per entry, see [`crate::state::weights`])
//! make fields of different units weigh alike in every inner product. The accelerators keep
//! their history unscaled and weigh it with the weights of the present iteration, so a field
//! whose magnitude is only known after a few sweeps (a structure that starts to move once the
//! fluid's answer reaches it) does not leave earlier iterations measured in a wrong unit.

mod aitken;
mod constant;
mod iqn_ils;

pub use aitken::Aitken;
pub use constant::ConstantRelaxation;
pub use iqn_ils::IqnIls;

use schemas::case::coupling::{AccelerationKind, CouplingConfig};

/// A rule giving the next iterate from the last input and output of the sweep.
pub trait Accelerator {
    /// The next `x` from `x` and `h = H(x)`; `iteration` counts from 0 in each window;
    /// `weights` scale each entry in inner products.
    fn next(&mut self, x: &[f64], h: &[f64], weights: &[f64], iteration: u32) -> Vec<f64>;
    /// The window converged.
    fn end_window(&mut self);
    /// What it keeps across windows (relaxation, reused secant pairs), for a checkpoint.
    fn save(&self) -> Vec<u8>;
    /// Takes back what [`Accelerator::save`] gave (a resumed run).
    fn restore(&mut self, bytes: &[u8]) -> Result<(), String>;
}

/// `a`'s state as bincode bytes.
fn save<A: serde::Serialize>(a: &A) -> Vec<u8> {
    // encoding plain numbers and vectors into a Vec cannot fail
    bincode::serde::encode_to_vec(a, bincode::config::standard()).unwrap_or_default()
}

/// `a`'s state from [`save`]'s bytes.
fn restore<A: serde::de::DeserializeOwned>(a: &mut A, bytes: &[u8]) -> Result<(), String> {
    let (back, _) = bincode::serde::decode_from_slice(bytes, bincode::config::standard())
        .map_err(|e| format!("the accelerator's saved state does not read back: {e}"))?;
    *a = back;
    Ok(())
}

/// The accelerator the case asks for.
pub fn from_config(c: &CouplingConfig) -> Box<dyn Accelerator> {
    match c.acceleration() {
        AccelerationKind::Constant => Box::new(ConstantRelaxation {
            omega: c.initial_relaxation,
        }),
        AccelerationKind::Aitken => Box::new(Aitken::new(c.initial_relaxation)),
        AccelerationKind::IqnIls => Box::new(IqnIls::new(c.initial_relaxation, c.reuse_windows as usize)),
    }
}

/// `x + ω (h − x)`.
fn relax(x: &[f64], h: &[f64], omega: f64) -> Vec<f64> {
    x.iter().zip(h).map(|(x, h)| x + omega * (h - x)).collect()
}

/// `Σ (w_i a_i)(w_i b_i)`.
fn weighted_dot(a: &[f64], b: &[f64], w: &[f64]) -> f64 {
    a.iter().zip(b).zip(w).map(|((a, b), w)| w * a * w * b).sum()
}

/// A change of residual `dr` below this fraction of the residual `r` (weighted norms) means the
/// sweep repeated the one before up to rounding (an input equal to the last but for the
/// rounding of the accelerator's own sums, 1e-16 of the data against a residual ≥ 1e-10 of it
/// while not converged): no new information, and a step that would not move the iteration.
const STALLED: f64 = 1e-6;

/// Whether the sweep that gave `r` repeated the one before (`dr`: the change of residual).
fn stalled(dr: &[f64], r: &[f64], weights: &[f64]) -> bool {
    weighted_dot(dr, dr, weights).sqrt() <= STALLED * weighted_dot(r, r, weights).sqrt()
}
