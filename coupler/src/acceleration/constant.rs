//! Constant under-relaxation: `x ← x + ω r`.

use super::{relax, Accelerator};

#[derive(serde::Serialize, serde::Deserialize)]
pub struct ConstantRelaxation {
    pub omega: f64,
}

impl Accelerator for ConstantRelaxation {
    fn next(&mut self, x: &[f64], h: &[f64], _weights: &[f64], _iteration: u32) -> Vec<f64> {
        relax(x, h, self.omega)
    }

    fn save(&self) -> Vec<u8> {
        super::save(self)
    }

    fn restore(&mut self, bytes: &[u8]) -> Result<(), String> {
        super::restore(self, bytes)
    }

    fn end_window(&mut self) {}
}
