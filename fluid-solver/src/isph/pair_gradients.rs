//! The kernel gradients of every fluid particle's pairs, `V ∇W_ij = V (W'/r)(x_i − x_j)`, computed
//! once per step for the exact projection's operator ([`super::exact_projection`]), which applies
//! `G_x` and `G_xᵀ` about twenty times a step: with them stored the two passes read one vector
//! per pair instead of the neighbour's position and kind and the kernel.
//!
//! With `kernel_correction = "moment"` each vector is the corrected one of
//! [`super::kernel_correction`], as the gradient's pair terms are.
//!
//! Each pair's vector carries the symmetric form's factor for its neighbour: 1 for a fluid
//! neighbour, 2 for a wall (the `2 p_i` of the walls' term `V (2p_i + Δp_iw) ∇W_iw`), 0 for a body
//! particle (whose term is the face law's, added apart). With the unknowns' pressure 0 on every
//! particle that is not an unknown, `(G_x x)_i = Σ_j (x_i + x_j) c_ij` and
//! `(G_xᵀ y)_k = Σ_j (y_k − y_j)·c_kj` then hold for every neighbour alike. Beside each vector,
//! S2-9's weight `F_ij = −2 V W'/r` for a fluid neighbour (0 for a solid), rounded to f32 as
//! the assembled PPE rounds it ([`super::ppe`]), so the blend's share of S2-9's matrix is applied
//! in the same pass. Stored in f32 (relative rounding 6e-8, below the PPE's tolerance 1e-6): the
//! passes are memory-bound.

use super::kernel::Wendland;
use super::kernel_correction::PairVectors;
use super::neighbour_list::NeighbourList;
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;

/// `[c_ij, F_ij]` of every pair of every fluid particle, in the order of [`NeighbourList::of`].
#[derive(Debug, Clone, Default)]
pub struct PairGradients {
    /// Particle i's entries are `c[start[i] .. start[i + 1]]` (none for a solid).
    start: Vec<usize>,
    c: Vec<[f32; 4]>,
}

impl PairGradients {
    /// Computes the vectors for the particles and list of the present step.
    pub fn build(&mut self, k: &Wendland, list: &NeighbourList, p: &Particles, vectors: PairVectors) {
        let body = Kind::Body.code();
        self.start.clear();
        self.start.push(0);
        let mut n = 0;
        for i in 0..p.len() {
            if p.kind[i] == FLUID {
                n += list.of(i).len();
            }
            self.start.push(n);
        }
        self.c.resize(n, [0.0; 4]);
        // Each particle's slice, split off in order, then filled in parallel.
        let mut rest = &mut self.c[..];
        let mut slices = Vec::with_capacity(p.len());
        for i in 0..p.len() {
            let (mine, others) = std::mem::take(&mut rest).split_at_mut(self.start[i + 1] - self.start[i]);
            slices.push(mine);
            rest = others;
        }
        slices
            .into_par_iter()
            .enumerate()
            .with_min_len(256)
            .for_each(|(i, out)| {
                for (o, (j, q)) in out.iter_mut().zip(list.pairs(i)) {
                    let fluid = p.kind[j] == FLUID;
                    let factor = if fluid {
                        1.0
                    } else if p.kind[j] == body {
                        0.0
                    } else {
                        2.0
                    };
                    let w = k.volume * k.dw_over_r_at(q);
                    let laplacian = if fluid { (-2.0 * w) as f32 } else { 0.0 };
                    let w = factor * w;
                    let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
                    let c = vectors.pair(i, j, fluid, d.map(|v| w * v));
                    *o = [c[0] as f32, c[1] as f32, c[2] as f32, laplacian];
                }
            });
    }

    /// `[c_ij, F_ij]` of fluid particle i's pairs, in the order of [`NeighbourList::of`].
    #[inline(always)]
    pub fn of(&self, i: usize) -> &[[f32; 4]] {
        &self.c[self.start[i]..self.start[i + 1]]
    }
}
