//! A point reaction of the drag law spread over the fluid particles around its point (S2-24):
//! `f_k = F V_k W(x_c − x_k) / Σ_j V_j W(x_c − x_j)` over the fluid particles k within the
//! kernel's support of the sub-member centroid x_c, F the reaction (−f of the sub-member's
//! force). The shares sum to one, so `Σ_k f_k = F` to round-off wherever fluid is present — near
//! a wall or the free surface too.
//!
//! Where no fluid particle is within the support of the centroid (a sub-member just above the
//! water whose sample point upstream is wet), the reaction is spread the same way around its
//! paired sample point (reaction k pairs with sample point k), where the drag law found the
//! water. Where no fluid is near either point, nothing can take it: the reaction is not applied
//! and is returned as `unapplied`, which the solver adds up and the participant reports as a
//! warning with its impulse.
//!
//! The particles near a point come from the step's own cell list ([`CellGrid::for_each_near_point_trimmed`]),
//! so no second grid is built: see [`super`] for when that list is valid.

use super::kernel::Wendland;
use crate::kind::FLUID;
use crate::neighbour_search::{CellGrid, Rows};
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

/// Spreads `reactions` (6 per reaction: point, force) over the fluid particles of spacing
/// `spacing`; `sample_points` (3 per reaction, or empty) are the fall-back points; `grid` is the
/// cell list sorted for `p`.
pub fn spread(
    p: &Particles,
    grid: &CellGrid,
    spacing: f64,
    reactions: &[f64],
    sample_points: &[f64],
) -> Spread {
    spread_reusing(p, grid, spacing, reactions, sample_points, &[])
}

/// As [`spread`], taking reaction k's shares from `known[k]` where it holds them: those of
/// [`share_of`] for these particles, centroids and sample points (computed while sampling,
/// [`super::sampling::sample_with_shares`]), so the result is the same to the last bit. Only
/// the other reactions with a force search the cell list.
pub fn spread_reusing(
    p: &Particles,
    grid: &CellGrid,
    spacing: f64,
    reactions: &[f64],
    sample_points: &[f64],
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
            Some(share_of(p, grid, drift, &kernel, [r[0], r[1], r[2]], fallback))
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

/// The shares of a reaction at `centroid`: around it, or, where no fluid particle is within the
/// support, around its sample point `fallback` (moved).
pub fn share_of(
    p: &Particles,
    grid: &CellGrid,
    drift: f64,
    kernel: &Wendland,
    centroid: [f64; 3],
    fallback: Option<[f64; 3]>,
) -> Share {
    let around = shares_around(p, grid, drift, kernel, centroid);
    match fallback {
        Some(s) if around.is_empty() => (shares_around(p, grid, drift, kernel, s), true),
        _ => (around, false),
    }
}

/// The normalised shares `V_k W_ik / Σ_j V_j W_ij` of the fluid particles around `x` (equal
/// volumes cancel); empty when none is within the support.
pub(crate) fn shares_around(
    p: &Particles,
    grid: &CellGrid,
    drift: f64,
    kernel: &Wendland,
    x: [f64; 3],
) -> Vec<(u32, f64)> {
    // a full support holds about 60 particles: one allocation
    let mut share = Vec::with_capacity(96);
    let mut sum = 0.0;
    grid.for_each_near_point_trimmed(p, x, kernel.radius, drift, Rows::Fluid, |j, r2, _| {
        if p.kind[j] != FLUID {
            return;
        }
        let w = kernel.value(r2.sqrt());
        if w > 0.0 {
            share.push((j as u32, w));
            sum += w;
        }
    });
    share.iter_mut().for_each(|(_, w)| *w /= sum);
    share
}
