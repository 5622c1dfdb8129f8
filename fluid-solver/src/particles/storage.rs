//! Particle storage as a structure of arrays.
//!
//! Memory per particle of the state: positions 3 × 8 B, velocities 3 × 8 B, pressure 8 B,
//! number density 8 B, kind 1 B, id 4 B = 69 B. The step adds a 3 × 8 B acceleration buffer,
//! the cell list 2 × 4 B (cell index, permutation) and one 8 B reorder scratch: 109 B per
//! particle, plus 8 B per grid cell (cell start, fluid count; one to three cells per particle,
//! depending on how much of the grid is headroom above the water).

use crate::particles::kind::Kind;
use rayon::prelude::*;

/// Every particle's state, one array per quantity; index `i` is the same particle in each.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Particles {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub z: Vec<f64>,
    pub vx: Vec<f64>,
    pub vy: Vec<f64>,
    pub vz: Vec<f64>,
    /// P [Pa] (S1-14).
    pub pressure: Vec<f64>,
    /// Particle number density n_i = Σ_j w(r_ij) (S1-15 without ρ0/n0).
    pub number_density: Vec<f64>,
    /// [`Kind`] codes.
    pub kind: Vec<u8>,
    /// Stable identity: the index in the initial layout (the arrays are reordered every step).
    pub id: Vec<u32>,
}

/// Bytes of state per particle (see the module doc).
pub const STATE_BYTES_PER_PARTICLE: usize = 8 * 8 + 1 + 4;

impl Particles {
    /// Number of particles.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// True when there are no particles.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// Appends a particle at rest at `p`.
    pub fn push(&mut self, p: [f64; 3], kind: Kind) {
        let id = self.x.len() as u32;
        self.x.push(p[0]);
        self.y.push(p[1]);
        self.z.push(p[2]);
        self.vx.push(0.0);
        self.vy.push(0.0);
        self.vz.push(0.0);
        self.pressure.push(0.0);
        self.number_density.push(0.0);
        self.kind.push(kind.code());
        self.id.push(id);
    }

    /// Appends a particle at `p` moving with `v`, with identity `id` (for particles added during
    /// a run, e.g. by an inflow; the caller keeps ids unique).
    pub fn push_moving(&mut self, p: [f64; 3], v: [f64; 3], kind: Kind, id: u32) {
        self.push(p, kind);
        let i = self.len() - 1;
        (self.vx[i], self.vy[i], self.vz[i]) = (v[0], v[1], v[2]);
        self.id[i] = id;
    }

    /// Position of particle `i`.
    pub fn position(&self, i: usize) -> [f64; 3] {
        [self.x[i], self.y[i], self.z[i]]
    }

    /// Velocity of particle `i`.
    pub fn velocity(&self, i: usize) -> [f64; 3] {
        [self.vx[i], self.vy[i], self.vz[i]]
    }

    /// Kind of particle `i`.
    pub fn kind_of(&self, i: usize) -> Kind {
        Kind::from_code(self.kind[i])
    }

    /// Number of particles of `kind`.
    pub fn count(&self, kind: Kind) -> usize {
        self.kind.iter().filter(|&&k| k == kind.code()).count()
    }

    /// Every `f64` array (positions, velocities, pressure, number density).
    fn f64_arrays_mut(&mut self) -> [&mut Vec<f64>; 8] {
        [
            &mut self.x,
            &mut self.y,
            &mut self.z,
            &mut self.vx,
            &mut self.vy,
            &mut self.vz,
            &mut self.pressure,
            &mut self.number_density,
        ]
    }

    /// Puts particle `perm[i]` at index `i` in every array, using `scratch` as the spare buffer.
    pub fn permute(&mut self, perm: &[u32], scratch: &mut Vec<f64>) {
        for v in self.f64_arrays_mut() {
            gather(v, perm, scratch);
        }
        let mut k = Vec::new();
        gather(&mut self.kind, perm, &mut k);
        let mut id = Vec::new();
        gather(&mut self.id, perm, &mut id);
    }

    /// The particles at `indices`, in that order.
    pub fn subset(&self, indices: &[u32]) -> Particles {
        let pick = |v: &[f64]| indices.iter().map(|&i| v[i as usize]).collect::<Vec<f64>>();
        Particles {
            x: pick(&self.x),
            y: pick(&self.y),
            z: pick(&self.z),
            vx: pick(&self.vx),
            vy: pick(&self.vy),
            vz: pick(&self.vz),
            pressure: pick(&self.pressure),
            number_density: pick(&self.number_density),
            kind: indices.iter().map(|&i| self.kind[i as usize]).collect(),
            id: indices.iter().map(|&i| self.id[i as usize]).collect(),
        }
    }

    /// Appends every particle of `other` (ids as they are).
    pub fn append(&mut self, other: &Particles) {
        for (v, w) in self.f64_arrays_mut().into_iter().zip(other.f64_arrays()) {
            v.extend_from_slice(w);
        }
        self.kind.extend_from_slice(&other.kind);
        self.id.extend_from_slice(&other.id);
    }

    /// Every `f64` array, read only (in [`Particles::f64_arrays_mut`]'s order).
    fn f64_arrays(&self) -> [&Vec<f64>; 8] {
        [
            &self.x,
            &self.y,
            &self.z,
            &self.vx,
            &self.vy,
            &self.vz,
            &self.pressure,
            &self.number_density,
        ]
    }

    /// Releases spare capacity (after building or removing particles).
    pub fn shrink_to_fit(&mut self) {
        for v in self.f64_arrays_mut() {
            v.shrink_to_fit();
        }
        self.kind.shrink_to_fit();
        self.id.shrink_to_fit();
    }

    /// Removes every particle of `kind` (keeps the order of the others); returns how many.
    pub fn remove_kind(&mut self, kind: Kind) -> usize {
        let keep: Vec<u32> = (0..self.len() as u32)
            .filter(|&i| self.kind[i as usize] != kind.code())
            .collect();
        let removed = self.len() - keep.len();
        if removed > 0 {
            let mut scratch = Vec::new();
            self.permute(&keep, &mut scratch);
            self.shrink_to_fit();
        }
        removed
    }
}

/// `v[i] = old v[perm[i]]`; `perm` may be shorter than `v` (then `v` shrinks).
fn gather<T: Copy + Send + Sync + Default>(v: &mut Vec<T>, perm: &[u32], scratch: &mut Vec<T>) {
    scratch.resize(perm.len(), T::default());
    let src = &*v;
    scratch
        .par_iter_mut()
        .zip(perm.par_iter())
        .with_min_len(4096)
        .for_each(|(s, &p)| *s = src[p as usize]);
    std::mem::swap(v, scratch);
}
