//! A reaction of the drag law spread over the fluid particles around its point (S2-24, widened
//! over the member's footprint):
//!
//! `f_k = F V_k W(ρ_k) / Σ_j V_j W(ρ_j)`,  `ρ_k = max(0, |x_k − x_c| − a)`,  `a = max(0, (D − Δs)/2)`,
//!
//! over the fluid particles k with `ρ_k` within the kernel's support R = 2.4 Δs, x_c the
//! sub-member's centroid, F the reaction (−f of the sub-member's force), D the width of its
//! member (`reaction_width` in the message, one per reaction) and Δs the particle spacing. For a
//! member no wider than a particle (D ≤ Δs: a = 0) this is S2-24 itself, to the last bit; a wider
//! member spreads its reaction with equal weight W(0) over the fluid within a of its centroid —
//! the water in its footprint, a sphere of the member's half-width less half a particle — and
//! the kernel's tail outside it, so the weights are continuous in D and in the particle's place.
//! Why: at Δs = 5 mm the 0.05 m prism of `cases/prism-dam-break` (10 particles wide) put up to
//! 4.5 N of reaction on the few particles within 12 mm of its axis (≈ 250 m/s² on them) and the
//! instability detector stopped the run; over its footprint the same force meets the water it
//! displaces (a = 22.5 mm: ~380 particles at full weight where the water fills it, against the
//! ~60 of a point's support, most of whose weight sits on the ~20 nearest). A sphere and not the sub-member's box: one value per reaction, no axis or
//! section orientation in the message; the slices of a member, a Δs apart, overlap into a
//! capsule around its axis, whose ends reach a past the member's (the box would not).
//!
//! The shares sum to one, so `Σ_k f_k = F` to round-off wherever fluid is present — near a wall
//! or the free surface too.
//!
//! Where no fluid particle is within the reach `a + R` of the centroid (a sub-member just above
//! the water whose sample point upstream is wet), the reaction is spread the same way around its
//! paired sample point (reaction k pairs with sample point k), where the drag law found the
//! water. Where no fluid is near either point, nothing can take it: the reaction is not applied
//! and is returned as `unapplied`, which the solver adds up and the participant reports as a
//! warning with its impulse.
//!
//! The particles near a point come from the step's own cell list ([`CellGrid::for_each_near_point_trimmed`]),
//! so no second grid is built: see [`super`] for when that list is valid.

use super::kernel::Wendland;
use crate::neighbours::neighbour_search::{CellGrid, Rows};
use crate::particles::kind::FLUID;
use crate::particles::Particles;
use rayon::prelude::*;

/// The forces of a set of point reactions on the fluid particles.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Spread {
    /// Force on each particle (3 per particle, in the particles' present order) [N].
    pub force: Vec<f64>,
    /// Σ of `force`.
    pub total: [f64; 3],
    /// Reactions spread around their sample point instead of their centroid.
    pub moved: usize,
    /// Reactions with no fluid near either point, and their sum: not applied.
    pub unapplied: usize,
    pub unapplied_force: [f64; 3],
}

/// The normalised shares of one reaction and whether they lie around its sample point instead of
/// its centroid (empty: no fluid near either).
pub type Share = (Vec<(u32, f64)>, bool);

/// The half-width `a = max(0, (D − Δs)/2)` of the flat part of the weights of a reaction from a
/// member `width` D wide, for particles of `spacing` Δs (0: a point, S2-24).
pub fn footprint_half_width(width: f64, spacing: f64) -> f64 {
    (0.5 * (width - spacing)).max(0.0)
}

/// The footprint half-width of reaction `k` of `widths` (1 per reaction, or empty: all points).
pub(crate) fn half_width_of(widths: &[f64], k: usize, spacing: f64) -> f64 {
    widths.get(k).map_or(0.0, |&w| footprint_half_width(w, spacing))
}

/// Spreads `reactions` (6 per reaction: point, force) over the fluid particles of spacing
/// `spacing`; `sample_points` (3 per reaction, or empty) are the fall-back points; `widths` (1
/// per reaction, or empty: all points) the widths of their members; `grid` is the cell list
/// sorted for `p`.
pub fn spread(
    p: &Particles,
    grid: &CellGrid,
    spacing: f64,
    reactions: &[f64],
    sample_points: &[f64],
    widths: &[f64],
) -> Spread {
    spread_reusing(p, grid, spacing, reactions, sample_points, widths, &[])
}

/// As [`spread`], taking reaction k's shares from `known[k]` where it holds them: those of
/// [`share_of`] for these particles, centroids, sample points and widths (computed while
/// sampling, [`super::sampling::sample_with_shares`]), so the result is the same to the last
/// bit. Only the other reactions with a force search the cell list.
pub fn spread_reusing(
    p: &Particles,
    grid: &CellGrid,
    spacing: f64,
    reactions: &[f64],
    sample_points: &[f64],
    widths: &[f64],
    known: &[Option<Share>],
) -> Spread {
    let kernel = Wendland::for_spacing(spacing);
    let paired = sample_points.len() * 2 == reactions.len();
    let loaded = |r: &[f64]| r[3..6].iter().any(|&f| f != 0.0);
    let searched = |k: usize, r: &[f64]| loaded(r) && known.get(k).is_none_or(Option::is_none);
    let search = reactions.chunks_exact(6).enumerate().any(|(k, r)| searched(k, r));
    // one pass over the particles, only when some reaction searches the cell list
    let drift = if search { grid.drift(p) } else { 0.0 };
    let found: Vec<Option<Share>> = reactions
        .par_chunks_exact(6)
        .enumerate()
        .with_min_len(64)
        .map(|(k, r)| {
            if !searched(k, r) {
                return None;
            }
            let fallback = paired.then(|| {
                [
                    sample_points[3 * k],
                    sample_points[3 * k + 1],
                    sample_points[3 * k + 2],
                ]
            });
            let a = half_width_of(widths, k, spacing);
            Some(share_of(p, grid, drift, &kernel, [r[0], r[1], r[2]], fallback, a))
        })
        .collect();
    let mut out = Spread {
        force: vec![0.0; 3 * p.len()],
        ..Spread::default()
    };
    for (k, r) in reactions.chunks_exact(6).enumerate() {
        let f = [r[3], r[4], r[5]];
        if !loaded(r) {
            continue;
        }
        let Some((share, moved)) = found[k]
            .as_ref()
            .or_else(|| known.get(k).and_then(Option::as_ref))
        else {
            continue;
        };
        if share.is_empty() {
            out.unapplied += 1;
            (0..3).for_each(|c| out.unapplied_force[c] += f[c]);
            continue;
        }
        out.moved += usize::from(*moved);
        for &(i, w) in share {
            for (c, fc) in f.iter().enumerate() {
                out.force[3 * i as usize + c] += w * fc;
                out.total[c] += w * fc;
            }
        }
    }
    out
}

/// The shares of a reaction at `centroid` from a member of footprint half-width `half_width`
/// ([`footprint_half_width`]): around it, or, where no fluid particle is within its reach, around
/// its sample point `fallback` (moved), over the same footprint.
pub fn share_of(
    p: &Particles,
    grid: &CellGrid,
    drift: f64,
    kernel: &Wendland,
    centroid: [f64; 3],
    fallback: Option<[f64; 3]>,
    half_width: f64,
) -> Share {
    let around = shares_around(p, grid, drift, kernel, centroid, half_width);
    match fallback {
        Some(s) if around.is_empty() => (shares_around(p, grid, drift, kernel, s, half_width), true),
        _ => (around, false),
    }
}

/// The normalised shares `V_k W(ρ_k) / Σ_j V_j W(ρ_j)`, `ρ = max(0, |x − x_k| − half_width)`, of
/// the fluid particles around `x` (equal volumes cancel); empty when none is within the reach
/// `half_width + R`. With `half_width` 0, S2-24's `W(|x − x_k|)` (the same operations).
pub(crate) fn shares_around(
    p: &Particles,
    grid: &CellGrid,
    drift: f64,
    kernel: &Wendland,
    x: [f64; 3],
    half_width: f64,
) -> Vec<(u32, f64)> {
    // a full support holds about 60 particles: one allocation (a footprint grows it)
    let mut share = Vec::with_capacity(96);
    let mut sum = 0.0;
    let reach = kernel.radius + half_width;
    grid.for_each_near_point_trimmed(p, x, reach, drift, Rows::Fluid, |j, r2, _| {
        if p.kind[j] != FLUID {
            return;
        }
        let w = kernel.value((r2.sqrt() - half_width).max(0.0));
        if w > 0.0 {
            share.push((j as u32, w));
            sum += w;
        }
    });
    share.iter_mut().for_each(|(_, w)| *w /= sum);
    share
}
