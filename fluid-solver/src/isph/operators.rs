//! The SPH operators of ISPH (S2-7 … S2-9) as passes over the step's neighbour list, with the
//! Wendland kernel of [`super::kernel`]. `∇_i W_ij = (W'/r)(x_i − x_j)`, and S2-9's Laplacian
//! weight is `F_ij = 2 V (x_j − x_i)·∇W_ij / r² = −2 V W'(r)/r ≥ 0`. Each pass is a gather
//! (particle i writes its own slot), in parallel without locks.

use super::body_completion::BodyCompletion;
use super::free_surface::{LAMBDA_INNER, LAMBDA_SPLASH};
use super::kernel::Wendland;
use super::neighbour_list::NeighbourList;
use super::pair_laws::{self, BodyFaces};
use super::walls::NeumannPair;
use crate::neighbours::moments::{inverse, smallest_eigenvalue_up_to, solve, OuterSum};
use crate::neighbours::vector_field::{add, PassTotals, VectorField};
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;
use schemas::case::fluid::PressureGradient;

/// S2-7 with φ = 1, normalised: `ρ̂_i/ρ0 = Σ_j V W_ij / Σ_lattice V W` (self included) over
/// every neighbour: the numerical density of S2-5 for fluid particles, reading 1 in a full
/// lattice, and the fill of a solid particle's support (1 for solids away from the water).
pub fn density_ratio(k: &Wendland, list: &NeighbourList, p: &Particles, out: &mut Vec<f64>) {
    out.resize(p.len(), 1.0);
    let self_term = k.volume * k.w(0.0);
    out.par_iter_mut()
        .enumerate()
        .with_min_len(512)
        .for_each(|(i, o)| {
            *o = if p.kind[i] == FLUID || !list.of(i).is_empty() {
                let mut s = self_term;
                for &q in list.q(i) {
                    s += k.volume * k.w_at(f64::from(q));
                }
                s / k.lattice_density
            } else {
                1.0
            };
        });
}

/// Below this λ_min the moment matrix that corrects the divergence is raised to it
/// ([`DivergenceSum::value`]): the correction multiplies the divergence by at most 1/0.8 = 1.25.
pub const DIVERGENCE_CORRECTION_FLOOR: f64 = 0.8;

/// The divergence of the projection's source (S2-5), for fluid i (0 elsewhere), with the
/// gradient's `form` and the free surface's λ_min (`lambda`, [`super::free_surface::lambda_min`])
/// ([`DivergenceSum`]). Solid neighbours take part through the Neumann differences of
/// [`super::walls`] instead.
pub fn divergence(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    form: PressureGradient,
    lambda: &[f64],
    out: &mut Vec<f64>,
) {
    out.resize(p.len(), 0.0);
    out.par_iter_mut()
        .enumerate()
        .with_min_len(512)
        .for_each(|(i, o)| {
            *o = if p.kind[i] == FLUID {
                let mut sum = DivergenceSum::new(form, lambda[i]);
                for (j, q) in list.pairs(i) {
                    sum.add(k, p, i, j, q);
                }
                sum.value(k)
            } else {
                0.0
            };
        });
}

/// S2-8's divergence at one fluid particle i, summed pair by pair: `⟨∇·v⟩_i = tr T_i` with the
/// velocity moment `T_i = Σ_{fluid j} V (v_j − v_i) ⊗ ∇W_ij`; with S2-8's corrected gradient
/// (the default), in Marrone's band (λ_min ≤ 0.9, S2-11, the free-surface stage's value),
/// corrected by the gradient's moment matrix, `⟨∇·v⟩_i = tr(T_i m_i⁻¹)`, m_i (S2-10) over every
/// listed neighbour as in [`pressure_gradient`]: exact for a linear velocity field where the
/// support is part empty, as the gradient is for a linear pressure.
///
/// Why: the projection's pressure does work `−Σ_i V v_i·⟨∇p⟩_i` on the water, which vanishes for
/// a velocity that D calls divergence-free only if D and the gradient agree. With the gradient
/// corrected and D not, they disagree wherever the support is part empty, and there the
/// pressure fed energy into the flow: the L/20 dam break (`tests/isph_dam_break.rs`) gained
/// 220.4 J/kg of 11 446 (1.9 %) from 0.10 to 0.16 s, at the surge's toe, where nothing feeds it.
/// The interior (λ_min > 0.9), where the gradient's correction only undoes the particles'
/// disorder, keeps S2-8's plain sum: there the two forms disagree without feeding energy (the
/// gradient corrected only above 0.9 gained 19.9 J/kg in the same test), and the correction in
/// every row took 15 of about 265 ms per step at S2's scale (`benches/isph_vs_emps.rs -- --s2`),
/// in the band only about 1.
///
/// The floor: the PPE's Laplacian (S2-9) is not corrected, so where both D and the gradient are
/// multiplied by up to 1/λ_min the projection answers a divergence by up to 1/λ_min² times the
/// velocity its matrix expects. With the full m_i⁻¹ down to λ_min = 0.2 (the gradient's splash
/// limit) that is up to 25 in the thin sheets of a run-up: the MARIN dam break at Δs = 0.04 m
/// (`cases/dam-break-obstacle`, correction in every row) was stopped by the detector at
/// t = 1.08 s (17.9 m/s). So m_i is raised to λ_min ≥ [`DIVERGENCE_CORRECTION_FLOOR`]
/// (`m_i + (F − λ_min) I`), and F is set by the two energy tests of `tests/isph_dam_break.rs`,
/// which pull opposite ways (J/kg gained; bounds 1 %: 114 before the impact at L/20, 14.3
/// through the impact at L/10, Δt = 4e-4 s, to 0.3 s):
///
/// | F | before the impact, L/20 | through the impact, L/10 |
/// |---|---|---|
/// | no correction | 220.4 | 1.1 |
/// | 0.5 | 18.9 | 16.2 |
/// | 0.7 | 25.4 | 11.6 |
/// | **0.8** | **38.6** | **6.2** |
/// | 0.9 | 57.0 | 3.7 |
///
/// 0.8 keeps both furthest inside their bounds (34 % and 43 % of them). Splash particles
/// (λ_min ≤ 0.2) keep the plain trace, as they keep the plain gradient. The symmetric gradient
/// is not corrected, nor is D with it.
#[derive(Debug, Clone, Copy)]
pub struct DivergenceSum {
    corrected: bool,
    t: [[f64; 3]; 3],
    /// `Σ_j (W'/r) d ⊗ d` over every neighbour (m_i up to the factor −V / lattice moment).
    m: OuterSum,
}

impl DivergenceSum {
    /// An empty sum for the gradient `form` at a particle whose free-surface λ_min is `lambda`.
    #[inline(always)]
    pub fn new(form: PressureGradient, lambda: f64) -> Self {
        DivergenceSum {
            corrected: form == PressureGradient::CorrectedDifference && lambda <= LAMBDA_INNER,
            t: [[0.0; 3]; 3],
            m: OuterSum::default(),
        }
    }

    /// Adds neighbour j of fluid particle i at `q = r / r_e`: to m_i, and to T_i if j is fluid
    /// (where uncorrected, only to the trace).
    #[inline(always)]
    pub fn add(&mut self, k: &Wendland, p: &Particles, i: usize, j: usize, q: f64) {
        let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
        let w = k.dw_over_r_at(q);
        let fluid = p.kind[j] == FLUID;
        if !self.corrected {
            if fluid {
                let dv = [p.vx[j] - p.vx[i], p.vy[j] - p.vy[i], p.vz[j] - p.vz[i]];
                self.t[0][0] += k.volume * w * (dv[0] * d[0] + dv[1] * d[1] + dv[2] * d[2]);
            }
            return;
        }
        self.m.add(w, d);
        if fluid {
            let c = k.volume * w;
            let dv = [
                c * (p.vx[j] - p.vx[i]),
                c * (p.vy[j] - p.vy[i]),
                c * (p.vz[j] - p.vz[i]),
            ];
            for (row, dva) in self.t.iter_mut().zip(dv) {
                (0..3).for_each(|b| row[b] += dva * d[b]);
            }
        }
    }

    /// The divergence (type doc).
    pub fn value(&self, k: &Wendland) -> f64 {
        let t = &self.t;
        let plain = t[0][0] + t[1][1] + t[2][2];
        if !self.corrected {
            return plain;
        }
        let scale = -k.volume / k.lattice_moment;
        let mut m = self.m.matrix().map(|row| row.map(|x| scale * x));
        let lambda = smallest_eigenvalue_up_to(&m, DIVERGENCE_CORRECTION_FLOOR);
        if lambda <= LAMBDA_SPLASH {
            return plain;
        }
        if lambda < DIVERGENCE_CORRECTION_FLOOR {
            (0..3).for_each(|a| m[a][a] += DIVERGENCE_CORRECTION_FLOOR - lambda);
        }
        match inverse(&m) {
            // tr(T m⁻¹) = Σ_ab T_ab (m⁻¹)_ba
            Some(inv) => (0..3)
                .map(|a| (0..3).map(|b| t[a][b] * inv[b][a]).sum::<f64>())
                .sum(),
            None => plain,
        }
    }
}

/// S2-9 on the velocity: `⟨∇²v⟩_i = Σ_j F_ij (v_j − v_i)` for fluid i over fluid neighbours and,
/// with `no_slip`, solid neighbours at their own velocity (free slip leaves them out). Writes
/// `out` (0 for solids); `from_non_fluid` is Σ_i of the solids' part.
pub fn laplacian(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    no_slip: bool,
    out: &mut VectorField,
) -> PassTotals {
    out.resize(p.len());
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(512)
        .map(|(i, (ox, oy, oz))| {
            let mut l = [0.0; 3];
            let mut wall = [0.0; 3];
            if p.kind[i] == FLUID {
                for (j, q) in list.pairs(i) {
                    let solid = p.kind[j] != FLUID;
                    if solid && !no_slip {
                        continue;
                    }
                    let f = -2.0 * k.volume * k.dw_over_r_at(q);
                    let d = [
                        f * (p.vx[j] - p.vx[i]),
                        f * (p.vy[j] - p.vy[i]),
                        f * (p.vz[j] - p.vz[i]),
                    ];
                    for a in 0..3 {
                        l[a] += d[a];
                        if solid {
                            wall[a] += d[a];
                        }
                    }
                }
            }
            (*ox, *oy, *oz) = (l[0], l[1], l[2]);
            PassTotals {
                from_non_fluid: wall,
                candidates: list.of(i).len() as u64,
            }
        })
        .reduce(PassTotals::default, add)
}

/// The pressure gradient of the momentum equation, for fluid i (0 elsewhere): S2-8's difference
/// form corrected by the particle's moment matrix (Bonet & Lok 1999),
/// `⟨∇p⟩_i = m_i⁻¹ Σ_j V (p_j − p_i) ∇W_ij` over every listed neighbour, fluid or solid, with
/// m_i (S2-10) over the same neighbours; a solid neighbour at the pressure `p_i + Δp_ij` this
/// particle's PPE saw ([`super::walls`]). Exact for a linear pressure field on any support, full
/// or half empty; splash particles (λ_min of this m_i ≤ 0.2) keep the uncorrected sum.
///
/// Every solid takes part, wet or dry, as in the PPE's Neumann differences (the wet/dry
/// distinction of [`super::free_surface`] is the detection's: whether a wall counts as water
/// when looking for air). A particle resting on dry wall particles then feels the wall's
/// hydrostatic difference ρ g·(x_w − x_f) through the corrected sum, which carries its weight
/// exactly whatever part of its support the wall fills (λ_min of a particle alone on a flat
/// wall is about 0.5), and the Neumann part stops its motion into the wall. With only the wet
/// solids, as before, such a particle felt no wall at all and was held only by the collision
/// stage: a drop on the top of a side wall sank into it after about 2 s (`tests/wall_top.rs`),
/// and a film on the dry floor ahead of the surge was held at the collision distance.
///
/// Not the symmetric form `Σ_j V (p_i + p_j) ∇W_ij`: it is the difference form plus
/// `2 p_i Σ_j V ∇W_ij`, a force proportional to the absolute pressure that vanishes only on the
/// exact lattice and that the PPE (built on the difference operators) does not see. In the
/// closed tank at Δs = 0.02 m it drove the hydrostatic error of the corner columns up by 0.3 %
/// in 0.3 s and then a column along the tank's vertical edge away at 5 % per step (stopped
/// near 0.9 s); with S2-8 the same tank holds ρgh to 0.01 %. Conservative variants measured
/// against this tank (Bonet & Lok's antisymmetrised corrected kernel gradient, their variational
/// form, hybrids with the walls booked with the rest, the walls' zero-order part projected):
/// none holds it; `tests/isph_momentum.rs` lists them with their numbers. Particle shifting
/// (Lind et al. 2012) does not rescue the symmetric form: it moves particles down the same
/// zero-order sum, which a line or plane of the lattice sliding along itself lowers at this
/// support (2.4 Δs); at 2.0 Δs that sum restores them and the symmetric form holds the tank
/// for 1 s (`tests/isph_lattice_modes.rs`).
///
/// `from_non_fluid` is Σ over fluid–wall pairs (bodies excluded: their load is the face law of
/// [`super::pair_laws`], which the step books) of the symmetric pair term
/// `V (p_i + p_j^(i)) ∇W_ij`, the walls' load by the pair law of [`super::pair_laws`] (the
/// difference form's solid part is not a load: its fluid pairs are not antisymmetric, so the
/// walls would not carry the water's weight).
///
/// With `form` = [`PressureGradient::Symmetric`] (case key `isph.pressure_gradient =
/// "symmetric"`) the gradient is instead the uncorrected symmetric form
/// `⟨∇p⟩_i = Σ_j V (p_i + p_j) ∇W_ij` over fluid neighbours plus `Σ_w V (2p_i + Δp_iw) ∇W_iw`
/// over solid ones (walls and bodies), each pair's term [`pair_laws::symmetric_term`], the same
/// function the walls' and bodies' loads are made of; `from_non_fluid` is then Σ of that term
/// over every fluid–solid pair, bodies included (their load is V times the same terms). It holds
/// the hydrostatic tank only at a support of 2.0 Δs, where the lattice sums that its zero-order
/// part `2 p_i Σ_j V ∇W_ij` acts on are restoring (docs/notes/isph-symmetric-gradient-and-shifting.md); at 2.4 Δs the tank's edge columns run away (above).
/// [`PressureGradient::Conservative`] moves the fluid by the same symmetric form with the
/// bodies' completion ([`super::body_completion`]) in place of the face law, and builds its PPE
/// from it ([`super::exact_projection`]).
pub fn pressure_gradient(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    walls: &NeumannPair,
    form: PressureGradient,
    bodies: (&BodyFaces, Option<&BodyCompletion>),
    out: &mut VectorField,
) -> PassTotals {
    if form.is_symmetric() {
        return symmetric_gradient(k, list, p, walls, bodies, out);
    }
    out.resize(p.len());
    let body = Kind::Body.code();
    let scale = -k.volume / k.lattice_moment;
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(512)
        .map(|(i, (ox, oy, oz))| {
            let mut g = [0.0; 3];
            let mut wall = [0.0; 3];
            if p.kind[i] == FLUID {
                let mut m = [[0.0; 3]; 3];
                for (j, q) in list.pairs(i) {
                    let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
                    let solid = p.kind[j] != FLUID;
                    // A solid neighbour's pressure as this particle's PPE saw it (walls.rs).
                    let dp = if solid {
                        walls.difference(i, j)
                    } else {
                        p.pressure[j] - p.pressure[i]
                    };
                    let w = k.dw_over_r_at(q);
                    let c = k.volume * w;
                    for a in 0..3 {
                        g[a] += c * dp * d[a];
                        for b in 0..3 {
                            m[a][b] += scale * w * d[a] * d[b];
                        }
                    }
                    if solid && p.kind[j] != body {
                        // The pair law of the walls' load (pair_laws.rs).
                        let pij = 2.0 * p.pressure[i] + dp;
                        (0..3).for_each(|a| wall[a] += c * pij * d[a]);
                    }
                }
                // m_i is −Σ V (W'/r) d ⊗ d; the sum above is m_i ∇p for a linear field. Splash
                // (λ_min ≤ 0.2, S2-11) keeps the plain S2-8 sum: m_i⁻¹ would multiply it by up to
                // 1/λ_min (unchecked, the CI dam break's impact jet reached 4.6 m/s, 1.35 × 2√(gH),
                // and the detector stopped it at t = 0.28 s).
                if smallest_eigenvalue_up_to(&m, LAMBDA_SPLASH) > LAMBDA_SPLASH {
                    if let Some(gc) = solve(&m, g) {
                        g = gc;
                    }
                }
            }
            (*ox, *oy, *oz) = (g[0], g[1], g[2]);
            PassTotals {
                from_non_fluid: wall,
                candidates: list.of(i).len() as u64,
            }
        })
        .reduce(PassTotals::default, add)
}

/// The symmetric form of [`pressure_gradient`]: `⟨∇p⟩_i = Σ_j t_ij` with
/// [`pair_laws::symmetric_term`] over every listed fluid and wall neighbour, for fluid i (0
/// elsewhere), no moment-matrix correction; a body neighbour j adds `F_ij / V`, its face-law
/// share [`pair_laws::face_share`] (the force on i from j is then `−F_ij`, the reverse of the
/// body's load from i), or with `completion` (the exact projection) i's body term
/// [`BodyCompletion::term`] once; `from_non_fluid` is the sum over the solid neighbours.
fn symmetric_gradient(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    walls: &NeumannPair,
    (faces, completion): (&BodyFaces, Option<&BodyCompletion>),
    out: &mut VectorField,
) -> PassTotals {
    let body = Kind::Body.code();
    out.resize(p.len());
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(512)
        .map(|(i, (ox, oy, oz))| {
            let mut g = [0.0; 3];
            let mut solids = [0.0; 3];
            if p.kind[i] == FLUID {
                if let Some(c) = completion {
                    let t = c.term(i, p.pressure[i]);
                    (0..3).for_each(|a| {
                        g[a] += t[a];
                        solids[a] += t[a];
                    });
                }
                for (j, q) in list.pairs(i) {
                    let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
                    let t = if p.kind[j] == body {
                        match completion {
                            Some(_) => continue,
                            None => pair_laws::face_share(k, faces, j, q).map(|f| f / k.volume),
                        }
                    } else {
                        pair_laws::symmetric_term(k, walls, i, j, d, q)
                    };
                    (0..3).for_each(|a| g[a] += t[a]);
                    if p.kind[j] != FLUID {
                        (0..3).for_each(|a| solids[a] += t[a]);
                    }
                }
            }
            (*ox, *oy, *oz) = (g[0], g[1], g[2]);
            PassTotals {
                from_non_fluid: solids,
                candidates: list.of(i).len() as u64,
            }
        })
        .reduce(PassTotals::default, add)
}
