//! Interface quasi-Newton with an inverse Jacobian from least squares (IQN-ILS,
//! Degroote et al. 2009, as in preCICE): with `V` the differences of residuals and `W` the
//! differences of outputs, `c = argmin |V c + r_k|`, `x ← H(x_k) + W c`. Columns that make
//! `V` nearly dependent are dropped (QR filter); columns of `reuse` earlier windows are kept.
//! Columns are kept unscaled; the least-squares problem weighs `V` and `r` by the present
//! iteration's field weights (see [`super`]), `W c` is applied unscaled. A sweep that returns
//! the residual of the sweep before (the model stepped back to an input it had tried: this
//! happens when a field responds by a jump one sweep late, as a structure does to the drag
//! law's wetting of a member) restarts the window's secant model with a relaxation step.

use super::{relax, stalled, Accelerator};
use nalgebra::{DMatrix, DVector};

#[derive(serde::Serialize, serde::Deserialize)]
pub struct IqnIls {
    initial: f64,
    reuse: usize,
    /// Residual and output of the previous iteration in this window.
    previous: Option<(Vec<f64>, Vec<f64>)>,
    /// Columns (ΔR, ΔH) of this window, newest last.
    columns: Vec<(Vec<f64>, Vec<f64>)>,
    /// Columns of earlier windows, newest window last.
    old: Vec<Vec<(Vec<f64>, Vec<f64>)>>,
}

/// Columns with |R_ii| below this fraction of the largest are dropped.
const FILTER: f64 = 1e-10;

impl IqnIls {
    pub fn new(initial: f64, reuse: usize) -> Self {
        IqnIls {
            initial,
            reuse,
            previous: None,
            columns: Vec::new(),
            old: Vec::new(),
        }
    }

    fn all_columns(&self, n: usize) -> Vec<&(Vec<f64>, Vec<f64>)> {
        let reused = self.old.iter().rev().flat_map(|w| w.iter().rev());
        self.columns
            .iter()
            .rev()
            .chain(reused)
            .filter(|(v, _)| v.len() == n)
            .collect()
    }
}

impl Accelerator for IqnIls {
    fn next(&mut self, x: &[f64], h: &[f64], weights: &[f64], iteration: u32) -> Vec<f64> {
        let r: Vec<f64> = h.iter().zip(x).map(|(h, x)| h - x).collect();
        if iteration == 0 {
            self.previous = None;
            self.columns.clear();
        }
        if let Some((r_prev, h_prev)) = self.previous.take() {
            let dv: Vec<f64> = r.iter().zip(&r_prev).map(|(a, b)| a - b).collect();
            if stalled(&dv, &r, weights) {
                // The sweep gave the residual of the one before: the secant model sent the
                // iteration back to an input it had tried, and would again. Restart it.
                self.columns.clear();
                self.previous = Some((r, h.to_vec()));
                return relax(x, h, self.initial);
            }
            let dw: Vec<f64> = h.iter().zip(&h_prev).map(|(a, b)| a - b).collect();
            self.columns.push((dv, dw));
        }
        self.previous = Some((r.clone(), h.to_vec()));
        let mut cols = self.all_columns(r.len());
        // more secant columns than interface values cannot be independent (and R of their QR
        // has only as many rows): keep the newest
        cols.truncate(r.len());
        if cols.is_empty() {
            return relax(x, h, self.initial);
        }
        loop {
            let v = DMatrix::from_fn(r.len(), cols.len(), |i, j| weights[i] * cols[j].0[i]);
            let qr = v.qr();
            let rr = qr.r();
            let largest = (0..cols.len()).map(|j| rr[(j, j)].abs()).fold(0.0, f64::max);
            if let Some(weak) = (0..cols.len())
                .rev()
                .find(|&j| rr[(j, j)].abs() <= FILTER * largest)
            {
                cols.remove(weak);
                if cols.is_empty() {
                    return relax(x, h, self.initial);
                }
                continue;
            }
            let weighted: Vec<f64> = r.iter().zip(weights).map(|(r, w)| r * w).collect();
            let rhs = -(qr.q().transpose() * DVector::from_column_slice(&weighted));
            let Some(c) = rr.solve_upper_triangular(&rhs) else {
                return relax(x, h, self.initial);
            };
            let mut next = h.to_vec();
            for (j, (_, w)) in cols.iter().enumerate() {
                next.iter_mut().zip(w).for_each(|(n, w)| *n += c[j] * w);
            }
            return next;
        }
    }

    fn save(&self) -> Vec<u8> {
        super::save(self)
    }

    fn restore(&mut self, bytes: &[u8]) -> Result<(), String> {
        super::restore(self, bytes)
    }

    fn end_window(&mut self) {
        if self.reuse > 0 {
            self.old.push(std::mem::take(&mut self.columns));
            while self.old.len() > self.reuse {
                self.old.remove(0);
            }
        }
        self.columns.clear();
        self.previous = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A one-value interface iterated past its second sweep holds more secant columns than
    /// values (a light floating box at 100 fluid steps per window panicked the coupler here): the
    /// step is still taken, from the newest columns, and reaches the fixed point.
    #[test]
    fn more_sweeps_than_interface_values_keep_the_newest_columns() {
        let map = |x: f64| 1.0 + 0.5 * x.sin();
        let mut iqn = IqnIls::new(0.5, 0);
        let mut x = vec![0.0];
        for k in 0..8 {
            let h = vec![map(x[0])];
            x = iqn.next(&x, &h, &[1.0], k);
        }
        assert!((x[0] - map(x[0])).abs() < 1e-12, "fixed point: {x:?}");
    }
}
