//! Rebalancing the slabs as the water moves: every [`CHECK_EVERY`] steps the fluid's x is
//! counted in bins one spacing wide ([`XBins`], the lattice's faces from the tank's lower x
//! face, summed over the slabs: integer counts, the same on every rank), and when the fullest
//! slab holds more than [`LIMIT`] times the mean, the cuts move to the bin edges that split the
//! fluid into equal counts. Cuts that would leave a slab thinner than the halo or put an open
//! boundary within a halo of a cut are not taken (the slabs stay as they are). The slabs then
//! take the walls of their new reach ([`super::subdomain::Subdomain::recut`]), hand their fluid
//! over until each owns what lies between its cuts, and send their halos again; the probes that
//! read around a point go to the slab that holds the point now, with their filters' readings.

use super::slab_probes::SlabProbes;
use super::slabs::open_boundaries_fit;
use crate::particles::Particles;
use crate::sensors::probes::ProbeSet;
use std::collections::VecDeque;

/// Steps between two counts of the slabs' fluid.
pub const CHECK_EVERY: u64 = 25;

/// The fullest slab's fluid over the mean above which the slabs are cut again: 10 % more work
/// than its share on the rank every other rank waits for.
pub const LIMIT: f64 = 1.1;

/// A filtered probe's readings (time, value) in its window, per probe.
pub type Windows = Vec<Option<VecDeque<(f64, f64)>>>;

/// Bins of the fluid's x: `count` bins `width` wide from `x0`.
#[derive(Debug, Clone)]
pub struct XBins {
    x0: f64,
    width: f64,
    count: usize,
}

impl XBins {
    /// Bins one `spacing` wide over the tank's x extent `[x0, x1]` (the lattice's faces: no
    /// particle of the initial layout lies on an edge).
    pub fn new(x0: f64, x1: f64, spacing: f64) -> XBins {
        XBins {
            x0,
            width: spacing,
            count: (((x1 - x0) / spacing).ceil() as usize).max(1),
        }
    }

    /// The fluid particles of `p` that `owned` marks, counted by bin (a particle outside the
    /// tank in the end bin on its side).
    pub fn histogram(&self, p: &Particles, owned: impl Fn(usize) -> bool) -> Vec<u64> {
        let mut counts = vec![0u64; self.count];
        for i in (0..p.len()).filter(|&i| owned(i)) {
            let k = ((p.x[i] - self.x0) / self.width).floor().max(0.0) as usize;
            counts[k.min(self.count - 1)] += 1;
        }
        counts
    }

    /// The cuts of `parts` slabs that split the fluid of `counts` into equal counts, each at the
    /// first bin edge where the count before it reaches its share (slab r owns
    /// `cuts[r] ≤ x < cuts[r + 1]`, the ends at ±∞); `None` when a slab would be thinner than
    /// `min_width` (measured as [`super::slabs::cuts`] does) or the open boundaries' `planes`
    /// (inflow, outflow) would lie within `min_width` of a cut.
    pub fn cuts(
        &self,
        counts: &[u64],
        parts: usize,
        min_width: f64,
        planes: (Option<f64>, Option<f64>),
    ) -> Option<Vec<f64>> {
        let total: u64 = counts.iter().sum();
        let first = counts.iter().position(|&c| c > 0)?;
        let last = counts.iter().rposition(|&c| c > 0)?;
        let edge = |k: usize| self.x0 + k as f64 * self.width;
        let mut cuts = vec![f64::NEG_INFINITY];
        let mut before = 0u64;
        let mut k = 0;
        for r in 1..parts {
            let share = (r as u64 * total).div_ceil(parts as u64);
            while before < share && k < counts.len() {
                before += counts[k];
                k += 1;
            }
            cuts.push(edge(k));
        }
        cuts.push(f64::INFINITY);
        let (lo, hi) = (edge(first), edge(last + 1));
        let thin = (0..parts).any(|r| cuts[r + 1].min(hi) - cuts[r].max(lo) < min_width);
        let fits = open_boundaries_fit(planes.0, planes.1, &cuts, min_width).is_ok();
        (parts > 1 && !thin && fits).then_some(cuts)
    }
}

/// The fullest slab's count over the mean (1 for an even split; 0 without fluid).
pub fn imbalance(counts: &[u64]) -> f64 {
    let total: u64 = counts.iter().sum();
    match total {
        0 => 0.0,
        _ => *counts.iter().max().unwrap_or(&0) as f64 * counts.len() as f64 / total as f64,
    }
}

/// The fluid each slab cut at `cuts` owns, from the whole fluid's `counts` by bin (a cut lies on
/// a bin edge or, for the first cuts of a run, between two of them: the bin's particles go by
/// its centre).
pub fn slab_counts(bins: &XBins, counts: &[u64], cuts: &[f64]) -> Vec<u64> {
    let mut per_slab = vec![0u64; cuts.len() - 1];
    for (k, &c) in counts.iter().enumerate() {
        let centre = bins.x0 + (k as f64 + 0.5) * bins.width;
        let r = (1..cuts.len() - 1).take_while(|&r| cuts[r] <= centre).count();
        per_slab[r] += c;
    }
    per_slab
}

/// What cutting the slabs again needs: the fluid's bins, the whole domain's walls, the probes as
/// built on it, and the open boundaries' planes (inflow, outflow).
#[derive(Debug, Clone)]
pub struct Recut {
    pub bins: XBins,
    pub fixed: Particles,
    pub probes: ProbeSet,
    pub planes: (Option<f64>, Option<f64>),
    /// The halo's width [m] (`slabs::halo_width`): each slab sees this far past its cuts, and no
    /// slab is cut thinner nor an open boundary nearer a cut.
    pub halo: f64,
}

impl Recut {
    /// The new cuts of the slabs now cut at `cuts`, for the fluid counted by bin in `counts`
    /// (summed over the slabs): `None` when the fullest slab holds no more than [`LIMIT`] times
    /// the mean, or when no even cuts fit ([`XBins::cuts`]).
    pub fn new_cuts(&self, counts: &[u64], cuts: &[f64]) -> Option<Vec<f64>> {
        if imbalance(&slab_counts(&self.bins, counts, cuts)) <= LIMIT {
            return None;
        }
        self.bins.cuts(counts, cuts.len() - 1, self.halo, self.planes)
    }

    /// The probes over the slabs cut again at `new` (from the probes as built on the whole
    /// domain): the rules that combine the slabs' rows, and every slab's set with the filters'
    /// readings it needs from `old_windows` (every slab's, by slab, under the rules `old`): a
    /// probe read around a point takes its reader's readings, a probe over the whole fluid keeps
    /// the slab's own.
    pub fn probes_after(
        &self,
        old: &SlabProbes,
        old_windows: &[Windows],
        new: &[f64],
    ) -> (SlabProbes, Vec<ProbeSet>) {
        let (rules, mut sets) = SlabProbes::new(&self.probes, new);
        for (r, set) in sets.iter_mut().enumerate() {
            let windows = (0..self.probes.names().len())
                .map(|k| old_windows[old.reader(k).unwrap_or(r)][k].clone())
                .collect();
            set.set_windows(windows);
        }
        (rules, sets)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::kind::Kind;

    /// Fluid particles at the centres of `per_bin[k]` … in bins of 0.01 m from 0.
    fn fluid(per_bin: &[usize]) -> Particles {
        let mut p = Particles::default();
        for (k, &n) in per_bin.iter().enumerate() {
            for _ in 0..n {
                p.push([(k as f64 + 0.5) * 0.01, 0.0, 0.0], Kind::Fluid);
            }
        }
        p
    }

    #[test]
    fn cuts_split_the_counted_fluid_into_equal_shares_at_bin_edges() {
        let bins = XBins::new(0.0, 1.0, 0.01);
        let p = fluid(&[10; 100]);
        let counts = bins.histogram(&p, |_| true);
        assert_eq!(counts.iter().sum::<u64>(), 1000);
        let cuts = bins.cuts(&counts, 4, 0.1, (None, None)).unwrap_or_default();
        assert_eq!(cuts.len(), 5);
        for (c, want) in cuts[1..4].iter().zip([0.25, 0.5, 0.75]) {
            assert!((c - want).abs() < 1e-12, "{cuts:?}");
        }
        assert_eq!(slab_counts(&bins, &counts, &cuts), vec![250; 4]);
        assert!((imbalance(&[250, 250, 500]) - 1.5).abs() < 1e-12);
    }

    #[test]
    fn cuts_that_leave_a_slab_thinner_than_the_halo_or_near_an_open_boundary_are_not_taken() {
        let bins = XBins::new(0.0, 1.0, 0.01);
        // the water piled into the last 0.3 m: 4 slabs of it would be 0.075 m wide
        let mut per_bin = vec![0; 70];
        per_bin.extend([10; 30]);
        let counts = bins.histogram(&fluid(&per_bin), |_| true);
        assert!(bins.cuts(&counts, 4, 0.1, (None, None)).is_none());
        assert!(bins.cuts(&counts, 2, 0.1, (None, None)).is_some());
        assert!(
            bins.cuts(&counts, 2, 0.1, (None, Some(0.9))).is_none(),
            "the outflow 0.05 m behind the cut at 0.85 m"
        );
    }
}
