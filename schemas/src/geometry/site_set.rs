//! A set of lattice sites as a bitset, one bit a site (1e7 sites take 1.25 MB plus padding), and
//! the skin of such a set: its sites within a number of layers of the outside.
//!
//! Layout: column `(i, j)` (all `k` of one x, y) is `W = ⌈n_z / 64⌉` words from word
//! `(i + n_x j) W`; site `k` is bit `k mod 64` of the column's word `k / 64`. Columns are padded
//! to whole words so that each column (and each row of columns, fixed `j`) can be filled by one
//! thread; the padding bits are always zero.

use super::lattice::Lattice;
use rayon::prelude::*;

/// A set of sites of one [`Lattice`].
#[derive(Debug, Clone, PartialEq)]
pub struct SiteSet {
    lattice: Lattice,
    /// Words per column, `⌈n_z / 64⌉`.
    words_per_column: usize,
    bits: Vec<u64>,
}

impl SiteSet {
    /// The empty set of `lattice`'s sites (`⌈n_z / 64⌉ n_x n_y` words).
    pub fn empty(lattice: &Lattice) -> SiteSet {
        let words_per_column = lattice.n[2].div_ceil(64);
        let words = lattice.n[0]
            .checked_mul(lattice.n[1])
            .and_then(|c| c.checked_mul(words_per_column));
        SiteSet {
            lattice: *lattice,
            words_per_column,
            // a lattice whose word count overflows holds nothing (allocating it could not succeed)
            bits: vec![0; words.unwrap_or(0)],
        }
    }

    /// The lattice whose sites these are.
    pub fn lattice(&self) -> &Lattice {
        &self.lattice
    }

    /// Whether site `(i, j, k)` is in the set (`false` beyond the lattice).
    pub fn contains(&self, i: usize, j: usize, k: usize) -> bool {
        let [nx, ny, nz] = self.lattice.n;
        if i >= nx || j >= ny || k >= nz {
            return false;
        }
        let word = (i + nx * j) * self.words_per_column + k / 64;
        self.bits.get(word).is_some_and(|w| w >> (k % 64) & 1 == 1)
    }

    /// Adds site `(i, j, k)`; returns `false` (and adds nothing) beyond the lattice.
    pub fn insert(&mut self, i: usize, j: usize, k: usize) -> bool {
        let [nx, ny, nz] = self.lattice.n;
        if i >= nx || j >= ny || k >= nz {
            return false;
        }
        let word = (i + nx * j) * self.words_per_column + k / 64;
        match self.bits.get_mut(word) {
            Some(w) => {
                *w |= 1 << (k % 64);
                true
            }
            None => false,
        }
    }

    /// Adds every site of `other`, word by word (the union); `other` must be a set of the same
    /// lattice (nothing is added from one of another).
    pub fn insert_all(&mut self, other: &SiteSet) {
        if other.lattice == self.lattice {
            self.bits
                .par_iter_mut()
                .zip(&other.bits)
                .for_each(|(a, b)| *a |= b);
        }
    }

    /// Number of sites in the set.
    pub fn count(&self) -> usize {
        self.bits.par_iter().map(|w| w.count_ones() as usize).sum()
    }

    /// The sites `[i, j, k]` in the set, column by column (`k` fastest, then `i`, then `j`).
    pub fn iter(&self) -> impl Iterator<Item = [usize; 3]> + '_ {
        let w = self.words_per_column.max(1);
        let nx = self.lattice.n[0].max(1);
        self.bits.iter().enumerate().flat_map(move |(n, &word)| {
            let (column, k0) = (n / w, (n % w) * 64);
            let (i, j) = (column % nx, column / nx);
            BitIter(word).map(move |b| [i, j, k0 + b])
        })
    }

    /// The sites of each row of columns (fixed `j`), for filling in parallel: `(j, words)`, the
    /// row's `n_x` columns of [`words_per_column`](Self::words_per_column) words each.
    pub(crate) fn rows_mut(&mut self) -> impl IndexedParallelIterator<Item = (usize, &mut [u64])> {
        let row = (self.lattice.n[0] * self.words_per_column).max(1);
        self.bits.par_chunks_mut(row).enumerate()
    }

    /// Words per column, `⌈n_z / 64⌉`.
    pub(crate) fn words_per_column(&self) -> usize {
        self.words_per_column
    }

    /// The sites of this set that have a site NOT in the set within Chebyshev lattice distance
    /// `layers` (`max(|Δi|, |Δj|, |Δk|) ≤ layers`): the solid's skin, `layers` sites deep. With
    /// `outside_beyond_lattice`, the sites beyond the lattice's bounds count as outside (a body
    /// inside the tank); without, they count as inside (a terrain clipped by the tank, whose cut
    /// faces are not surface). `layers = 0` gives the empty set.
    ///
    /// Separable: the outside set is dilated by the cube of half-width `layers` as three 1-D
    /// dilations (along z within each column's words by bit shifts, then across columns along x
    /// and along y), each by doubling (`D_{r+s} = D_r ∪ (D_r + s) ∪ (D_r − s)` with `s ≤ 2r + 1`):
    /// `O(N log layers / 64)` word operations; then intersected with the set.
    pub fn within_layers_of_outside(&self, layers: usize, outside_beyond_lattice: bool) -> SiteSet {
        let [nx, ny, nz] = self.lattice.n;
        let w = self.words_per_column;
        let mut result = SiteSet::empty(&self.lattice);
        if layers == 0 || self.bits.is_empty() {
            return result;
        }
        let valid = column_mask(nz, w);
        // the outside within the lattice (padding bits stay zero)
        let mut outside: Vec<u64> = self
            .bits
            .par_iter()
            .enumerate()
            .map(|(n, b)| !b & valid[n % w])
            .collect();
        // along z: each column's bits
        outside
            .par_chunks_mut(w)
            .for_each(|column| dilate_bits(column, layers));
        // along x (neighbouring columns) and along y (neighbouring rows of columns)
        let outside = dilate_columns(&outside, w, 1, nx, layers);
        let outside = dilate_columns(&outside, w, nx, ny, layers);
        let ends: Vec<u64> = (0..w).map(|n| end_band(n, nz, layers)).collect();
        result.bits.par_chunks_mut(w).enumerate().for_each(|(c, out)| {
            let (i, j) = (c % nx, c / nx);
            let inside = &self.bits[c * w..(c + 1) * w];
            let near = &outside[c * w..(c + 1) * w];
            let band =
                outside_beyond_lattice && (i < layers || i + layers >= nx || j < layers || j + layers >= ny);
            for n in 0..w {
                let mut near_outside = near[n];
                if band {
                    near_outside = !0;
                } else if outside_beyond_lattice {
                    near_outside |= ends[n];
                }
                out[n] = inside[n] & near_outside;
            }
        });
        result
    }
}

/// Sets the bits `range` (site indices `k`) of one column's words; bits beyond the words are
/// ignored.
pub fn set_bits(column: &mut [u64], range: std::ops::Range<usize>) {
    let end = range.end.min(column.len() * 64);
    let mut k = range.start;
    while k < end {
        let (n, b) = (k / 64, k % 64);
        let take = (64 - b).min(end - k);
        let mask = if take == 64 { !0 } else { ((1u64 << take) - 1) << b };
        column[n] |= mask;
        k += take;
    }
}

/// For each word of a column, the bits that are sites (`k < nz`).
fn column_mask(nz: usize, w: usize) -> Vec<u64> {
    (0..w)
        .map(|n| {
            let used = nz.saturating_sub(n * 64).min(64);
            if used == 64 {
                !0
            } else {
                (1u64 << used) - 1
            }
        })
        .collect()
}

/// The bits of word `n` of a column whose sites are within `layers` of either end of the column
/// (`k < layers` or `k ≥ nz − layers`).
fn end_band(n: usize, nz: usize, layers: usize) -> u64 {
    let mut bits = 0u64;
    for b in 0..64 {
        let k = n * 64 + b;
        if k < nz && (k < layers || k + layers >= nz) {
            bits |= 1 << b;
        }
    }
    bits
}

/// Dilates the bits of one column along k by `radius` (bits shifted beyond the column's words
/// are dropped, i.e. nothing is set beyond it).
pub fn dilate_bits(column: &mut [u64], radius: usize) {
    let limit = column.len() * 64;
    let mut reach = 0;
    let mut shifted = vec![0u64; column.len()];
    while reach < radius && reach < limit {
        let step = (2 * reach + 1).min(radius - reach);
        shift_up(column, step, &mut shifted);
        let up = shifted.clone();
        shift_down(column, step, &mut shifted);
        for ((c, u), d) in column.iter_mut().zip(&up).zip(&shifted) {
            *c |= u | d;
        }
        reach += step;
    }
}

/// `out = bits << by` over the column's words (bit k to k + by).
fn shift_up(bits: &[u64], by: usize, out: &mut [u64]) {
    let (words, rest) = (by / 64, by % 64);
    for (n, o) in out.iter_mut().enumerate().take(bits.len()) {
        let low = n.checked_sub(words).map_or(0, |m| bits[m]);
        let lower = n.checked_sub(words + 1).map_or(0, |m| bits[m]);
        *o = if rest == 0 {
            low
        } else {
            (low << rest) | (lower >> (64 - rest))
        };
    }
}

/// `out = bits >> by` over the column's words (bit k to k − by).
fn shift_down(bits: &[u64], by: usize, out: &mut [u64]) {
    let (words, rest) = (by / 64, by % 64);
    for (n, o) in out.iter_mut().enumerate().take(bits.len()) {
        let high = bits.get(n + words).copied().unwrap_or(0);
        let higher = bits.get(n + words + 1).copied().unwrap_or(0);
        *o = if rest == 0 {
            high
        } else {
            (high >> rest) | (higher << (64 - rest))
        };
    }
}

/// Dilates by `radius` along the axis on which neighbouring columns are `stride` columns apart
/// and which has `len` positions (position of column `c`: `(c / stride) % len`); `w` words per
/// column. Nothing is set beyond the axis's ends.
fn dilate_columns(bits: &[u64], w: usize, stride: usize, len: usize, radius: usize) -> Vec<u64> {
    let mut current = bits.to_vec();
    let mut reach = 0;
    while reach < radius && reach + 1 < len {
        let step = (2 * reach + 1).min(radius - reach);
        let previous = &current;
        let next: Vec<u64> = (0..previous.len())
            .into_par_iter()
            .map(|n| {
                let c = n / w;
                let position = (c / stride) % len;
                let mut word = previous[n];
                if position >= step {
                    word |= previous[n - step * stride * w];
                }
                if position + step < len {
                    word |= previous[n + step * stride * w];
                }
                word
            })
            .collect();
        current = next;
        reach += step;
    }
    current
}

/// The indices of the set bits of a word, lowest first.
struct BitIter(u64);

impl Iterator for BitIter {
    type Item = usize;

    fn next(&mut self) -> Option<usize> {
        if self.0 == 0 {
            return None;
        }
        let b = self.0.trailing_zeros() as usize;
        self.0 &= self.0 - 1;
        Some(b)
    }
}
