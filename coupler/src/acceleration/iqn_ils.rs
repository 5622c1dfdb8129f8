//! Interface quasi-Newton with an inverse Jacobian from least squares (IQN-ILS,
//! Degroote et al. 2009, as in preCICE): with `V` the differences of residuals and `W` the
//! differences of outputs, `c = argmin |V c + r_k|`, `x ← H(x_k) + W c`. Columns that make
//! `V` nearly dependent are dropped by the QR2 filter of Haelterman et al. (2016): newest first,
//! a column goes when less than [`FILTER`] of its own (weighted) norm is independent of the
//! columns before it, `|R_jj| < ε |V_j|`; columns of `reuse` earlier windows are kept.
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

/// QR2's ε: a column whose part independent of the newer columns is below this fraction of
/// its norm is dropped (the limit preCICE's tutorials set for QR2). The earlier filter, |R_jj|
/// below 1e-10 of the largest |R_jj|, kept columns 1e-12 of their own norm independent (a
/// least-squares system of condition ~1e12 on the light floating box, whose coefficients threw
/// the iterate between the fluid's force branches) and could drop a small but independent one.
const FILTER: f64 = 1e-2;

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

/// The first column `j` of `v` (newest first) with `|R_jj| ≤ ε |v_j|` (QR2): what of it is
/// independent of the newer columns is below [`FILTER`] of its norm. `R_jj` depends only on the
/// columns up to `j`, so dropping the first such column and factoring again is the sequential
/// Gram–Schmidt filter.
fn first_dependent(v: &DMatrix<f64>, rr: &DMatrix<f64>) -> Option<usize> {
    (0..v.ncols()).find(|&j| rr[(j, j)].abs() <= FILTER * v.column(j).norm())
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
            let qr = v.clone().qr();
            let rr = qr.r();
            if let Some(weak) = first_dependent(&v, &rr) {
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
    use crate::acceleration::ConstantRelaxation;

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

    /// QR2 (Haelterman et al. 2016) judges a column by its own norm: of a newest column e1, a
    /// column 1e-4 off parallel to it (its independent part 1e-4 of its norm, below ε = 1e-2)
    /// is dropped, a column 1e-12 the size of the others but orthogonal to them is kept. The
    /// filter before (|R_jj| ≤ 1e-10 of the largest) did the opposite with both.
    #[test]
    fn qr2_drops_nearly_parallel_columns_and_keeps_small_independent_ones() {
        let v = DMatrix::from_columns(&[
            DVector::from_column_slice(&[1.0, 0.0, 0.0]),
            DVector::from_column_slice(&[1.0, 1e-4, 0.0]),
            DVector::from_column_slice(&[0.0, 0.0, 1e-12]),
        ]);
        let rr = v.clone().qr().r();
        assert_eq!(first_dependent(&v, &rr), Some(1));
        let v = v.remove_column(1);
        let rr = v.clone().qr().r();
        assert_eq!(
            first_dependent(&v, &rr),
            None,
            "the small orthogonal column stays"
        );
    }

    /// A body 20 times lighter than its added mass (the classic case where explicit partitioned
    /// coupling fails, e.g. Causin et al. 2005): per window of Δt the fluid answers the body's
    /// end velocity v with `F = −M_a (v − v0)/Δt − K x_mid` and the body takes
    /// `v = v0 + Δt F / m`, `x = x0 + Δt (v0 + v)/2`. The serial map's factor is −M_a/m (up to
    /// −20 here): plain iteration, also under-relaxed by ω = 0.5, diverges, while IQN-ILS
    /// reaches each window's fixed point, the monolithic implicit step
    /// `(m + M_a)(v − v0)/Δt = −K x_mid`, to the window tolerance 1e-10 in at most 8 sweeps
    /// (a 9-value linear interface).
    #[test]
    fn iqn_ils_holds_a_light_body_in_its_added_mass_where_plain_iteration_diverges() {
        let (m, k, dt) = (0.1, 50.0, 0.01);
        let ma = nalgebra::Matrix3::new(1.0, 0.3, 0.0, 0.3, 2.0, 0.1, 0.0, 0.1, 0.5);
        let sweep = |est: &[f64], x0: &[f64; 3], v0: &[f64; 3]| -> Vec<f64> {
            let v = nalgebra::Vector3::from_column_slice(&est[3..6]);
            let (x0v, v0v) = (nalgebra::Vector3::from(*x0), nalgebra::Vector3::from(*v0));
            let f = -(ma * (v - v0v)) / dt - k * (x0v + 0.5 * dt * (v0v + v));
            let v_new = v0v + dt * f / m;
            let x_new = x0v + 0.5 * dt * (v0v + v_new);
            [f.as_slice(), v_new.as_slice(), x_new.as_slice()].concat()
        };
        let relative = |est: &[f64], h: &[f64]| -> f64 {
            (0..3)
                .map(|b| {
                    let r: f64 = (3 * b..3 * b + 3).map(|i| (h[i] - est[i]).powi(2)).sum();
                    let n: f64 = (3 * b..3 * b + 3).map(|i| h[i] * h[i]).sum();
                    (r / n.max(1e-30)).sqrt()
                })
                .fold(0.0, f64::max)
        };
        let (x_start, v_start) = ([0.01, -0.02, 0.015], [0.0; 3]);
        // plain iteration from the window start: the velocity's residual grows every sweep
        let velocity_residual =
            |est: &[f64], h: &[f64]| -> f64 { (3..6).map(|i| (h[i] - est[i]).powi(2)).sum::<f64>().sqrt() };
        for omega in [1.0, 0.5] {
            let mut relaxed = ConstantRelaxation { omega };
            let mut est = [vec![0.0; 3], v_start.to_vec(), x_start.to_vec()].concat();
            let first = velocity_residual(&est, &sweep(&est, &x_start, &v_start));
            for it in 0..10 {
                let h = sweep(&est, &x_start, &v_start);
                est = relaxed.next(&est, &h, &[1.0; 9], it);
            }
            let last = velocity_residual(&est, &sweep(&est, &x_start, &v_start));
            assert!(
                last > 1e3 * first,
                "ω = {omega}: residual {first:.2e} → {last:.2e}"
            );
        }
        let mut iqn = IqnIls::new(0.5, 0);
        let (mut x0, mut v0) = (x_start, v_start);
        let mut worst_sweeps = 0;
        for window in 0..100 {
            let mut est = [vec![0.0; 3], v0.to_vec(), x0.to_vec()].concat();
            let mut sweeps = 0;
            loop {
                let h = sweep(&est, &x0, &v0);
                sweeps += 1;
                if relative(&est, &h) <= 1e-10 {
                    iqn.end_window();
                    est = h;
                    break;
                }
                assert!(sweeps < 50, "window {window} did not converge");
                let weights: Vec<f64> = (0..9)
                    .map(|i| {
                        let b = 3 * (i / 3);
                        1.0 / (h[b..b + 3].iter().map(|v| v * v).sum::<f64>() / 3.0)
                            .sqrt()
                            .max(1e-30)
                    })
                    .collect();
                est = iqn.next(&est, &h, &weights, sweeps - 1);
            }
            worst_sweeps = worst_sweeps.max(sweeps);
            let (x0v, v0v) = (nalgebra::Vector3::from(x0), nalgebra::Vector3::from(v0));
            let lhs = (nalgebra::Matrix3::identity() * m + ma) / dt
                + nalgebra::Matrix3::identity() * (0.5 * dt * k);
            let rhs = (nalgebra::Matrix3::identity() * m + ma) / dt * v0v - k * (x0v + 0.5 * dt * v0v);
            let monolithic = lhs.lu().solve(&rhs).expect("m + M_a is positive definite");
            let v = nalgebra::Vector3::from_column_slice(&est[3..6]);
            assert!(
                (v - monolithic).norm() <= 1e-8 * monolithic.norm().max(1e-3),
                "window {window}: {v:?} against {monolithic:?}"
            );
            v0.copy_from_slice(&est[3..6]);
            x0.copy_from_slice(&est[6..9]);
        }
        assert!(worst_sweeps <= 8, "{worst_sweeps} sweeps in a window");
    }
}
