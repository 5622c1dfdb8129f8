//! `L Lᵀ x = b` with a supernodal sparse Cholesky factor of faer, for one right-hand side, in plain
//! loops over each supernode's dense column-major block. A frame's factor has many small supernodes
//! (a member's mid node is one of 6 columns): per supernode, faer's general solve calls dense
//! triangular-solve and matrix-product kernels whose set-up costs more than the arithmetic.

use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;

/// The reciprocals of L's diagonal, in column order (the solve multiplies by them: a division's
/// latency would sit in the solve's dependency chain once per column).
pub fn inverse_diagonal(symbolic: &SymbolicSupernodalCholesky<usize>, values: &[f64], out: &mut Vec<f64>) {
    out.clear();
    for s in 0..symbolic.n_supernodes() {
        let (_, ncols, pattern, l) = block(symbolic, values, s);
        let rows = ncols + pattern.len();
        out.extend((0..ncols).map(|j| 1.0 / l[j * rows + j]));
    }
}

/// Solves `L Lᵀ y = b` in place (`x` holds b, then y), L given by `symbolic` and its `values`,
/// `inverse` its [`inverse_diagonal`]; `scratch` is resized to hold the longest below-diagonal
/// pattern.
pub fn solve_in_place(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    values: &[f64],
    inverse: &[f64],
    x: &mut [f64],
    scratch: &mut Vec<f64>,
) {
    let supernodes = symbolic.n_supernodes();
    let block = |s: usize| block(symbolic, values, s);
    // forward: L z = b, column by column; the below-diagonal updates gather in `scratch` first
    for s in 0..supernodes {
        let (start, ncols, pattern, l) = block(s);
        let rows = ncols + pattern.len();
        scratch.clear();
        scratch.resize(pattern.len(), 0.0);
        for j in 0..ncols {
            let column = &l[j * rows..(j + 1) * rows];
            let xj = x[start + j] * inverse[start + j];
            x[start + j] = xj;
            for (i, lij) in column[j + 1..ncols].iter().enumerate() {
                x[start + j + 1 + i] -= lij * xj;
            }
            for (t, lij) in scratch.iter_mut().zip(&column[ncols..]) {
                *t += lij * xj;
            }
        }
        for (&r, t) in pattern.iter().zip(scratch.iter()) {
            x[r] -= t;
        }
    }
    // backward: Lᵀ y = z, the below-diagonal values gathered once per supernode
    for s in (0..supernodes).rev() {
        let (start, ncols, pattern, l) = block(s);
        let rows = ncols + pattern.len();
        scratch.clear();
        scratch.extend(pattern.iter().map(|&r| x[r]));
        for j in (0..ncols).rev() {
            let column = &l[j * rows..(j + 1) * rows];
            let below = dot(&column[ncols..], scratch);
            let inside = dot(&column[j + 1..ncols], &x[start + j + 1..start + ncols]);
            x[start + j] = (x[start + j] - below - inside) * inverse[start + j];
        }
    }
}

/// Supernode `s`: its first column, number of columns, below-diagonal row pattern and dense
/// column-major block of L (the diagonal block's rows first, then the pattern's).
fn block<'a>(
    symbolic: &'a SymbolicSupernodalCholesky<usize>,
    values: &'a [f64],
    s: usize,
) -> (usize, usize, &'a [usize], &'a [f64]) {
    let (start, end) = (symbolic.supernode_begin()[s], symbolic.supernode_end()[s]);
    let first = symbolic.col_ptr_for_row_idx()[s];
    let pattern = &symbolic.row_idx()[first..first + symbolic.nnz_per_super()[s]];
    let l = &values[symbolic.col_ptr_for_val()[s]..symbolic.col_ptr_for_val()[s + 1]];
    (start, end - start, pattern, l)
}

/// Dot product with four independent sums (lets the compiler use vector registers).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut sums = [0.0; 4];
    let (a4, b4) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = a4
        .remainder()
        .iter()
        .zip(b4.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in a4.zip(b4) {
        for k in 0..4 {
            sums[k] += x[k] * y[k];
        }
    }
    sums[0] + sums[1] + sums[2] + sums[3] + tail
}
