//! Acceleration of the implicit coupling iteration `x ← H(x)` in one window.
//!
//! `x` is the interface data the sweep started from, `H(x)` what it produced, `r = H(x) − x`
//! the residual. Vectors come already scaled per field (see [`crate::state`]).

mod aitken;
mod constant;
mod iqn_ils;

pub use aitken::Aitken;
pub use constant::ConstantRelaxation;
pub use iqn_ils::IqnIls;

use schemas::case::coupling::{AccelerationKind, CouplingConfig};

/// A rule giving the next iterate from the last input and output of the sweep.
pub trait Accelerator {
    /// The next `x` from `x` and `h = H(x)`; `iteration` counts from 0 in each window.
    fn next(&mut self, x: &[f64], h: &[f64], iteration: u32) -> Vec<f64>;
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
    match c.acceleration {
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

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(a, b)| a * b).sum()
}
