//! Aitken's dynamic under-relaxation (Küttler & Wall 2008):
//! `ω_k = −ω_{k−1} r_{k−1}·(r_k − r_{k−1}) / |r_k − r_{k−1}|²`, `x ← x + ω_k r_k`;
//! the first iteration of every window uses the initial relaxation. Inner products are weighted
//! per field (see [`super`]); the residuals are kept unscaled.

use super::{relax, stalled, weighted_dot, Accelerator};

#[derive(serde::Serialize, serde::Deserialize)]
pub struct Aitken {
    initial: f64,
    omega: f64,
    last_residual: Option<Vec<f64>>,
}

impl Aitken {
    pub fn new(initial: f64) -> Self {
        Aitken {
            initial,
            omega: initial,
            last_residual: None,
        }
    }
}

impl Accelerator for Aitken {
    fn next(&mut self, x: &[f64], h: &[f64], weights: &[f64], iteration: u32) -> Vec<f64> {
        let r: Vec<f64> = h.iter().zip(x).map(|(h, x)| h - x).collect();
        self.omega = match (&self.last_residual, iteration) {
            (Some(prev), i) if i > 0 => {
                let dr: Vec<f64> = r.iter().zip(prev).map(|(a, b)| a - b).collect();
                let denom = weighted_dot(&dr, &dr, weights);
                if stalled(&dr, &r, weights) {
                    // the sweep repeated the last one's residual: ω had collapsed; start again
                    self.initial
                } else if denom > 0.0 {
                    -self.omega * weighted_dot(prev, &dr, weights) / denom
                } else {
                    self.omega
                }
            }
            _ => self.initial,
        };
        self.last_residual = Some(r);
        relax(x, h, self.omega)
    }

    fn save(&self) -> Vec<u8> {
        super::save(self)
    }

    fn restore(&mut self, bytes: &[u8]) -> Result<(), String> {
        super::restore(self, bytes)
    }

    fn end_window(&mut self) {
        self.last_residual = None;
    }
}
