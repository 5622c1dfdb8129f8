//! The case's probes over the slabs of the fluid. A probe that reads around a point (pressure,
//! water height, a wall-pressure sensor) is read by the slab that owns the point: its halo holds
//! every particle the probe sees (a probe reaches r_e,grad, the halo five kernel reaches). A probe
//! over the whole fluid (surge front, run-up) is read by every slab on the particles it holds, and
//! the whole fluid's reading is the largest: both readings grow with the water's extreme position
//! (the front's farthest particle, the highest one resting on a solid), which lies in one slab's
//! owned fluid, and a slab's halo copies hold its neighbours' values exactly. The slabs of one
//! process and the MPI ranks combine their rows with the same rule, so both write the row the
//! undivided run would, within the round-off of the particles' own drift.

use crate::sensors::probes::ProbeSet;
use schemas::validation::largest;

/// How the whole fluid's reading of one probe comes from the slabs' rows.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Rule {
    /// The reading of the slab that owns the probe's point.
    Slab(usize),
    /// The largest reading (a NaN kept).
    Largest,
}

/// The rules that make the whole fluid's probe row from the slabs'.
#[derive(Debug, Clone)]
pub struct SlabProbes {
    rules: Vec<Rule>,
}

impl SlabProbes {
    /// The probes of `set` (built on the whole domain: discs placed, no reading yet) over the
    /// slabs cut at `cuts` (slab r owns `cuts[r] ≤ x < cuts[r + 1]`), and each slab's set, which
    /// reads the point probes it owns and every probe over the whole fluid.
    pub fn new(set: &ProbeSet, cuts: &[f64]) -> (SlabProbes, Vec<ProbeSet>) {
        let slabs = cuts.len() - 1;
        let rules: Vec<Rule> = set
            .points_x()
            .into_iter()
            .map(|x| match x {
                Some(x) => Rule::Slab((1..slabs).take_while(|&r| cuts[r] <= x).count()),
                None => Rule::Largest,
            })
            .collect();
        let sets = (0..slabs)
            .map(|r| {
                let reads = rules
                    .iter()
                    .map(|&rule| rule == Rule::Slab(r) || rule == Rule::Largest);
                set.clone().reading_only(reads.collect())
            })
            .collect();
        (SlabProbes { rules }, sets)
    }

    /// The slab that reads probe `k` (a probe read around a point); `None` for a probe every
    /// slab reads (over the whole fluid).
    pub fn reader(&self, k: usize) -> Option<usize> {
        match self.rules[k] {
            Rule::Slab(r) => Some(r),
            Rule::Largest => None,
        }
    }

    /// The whole fluid's row from the slabs' rows (`rows[r]`, slab r's, all of one length).
    pub fn combine(&self, rows: &[Vec<f64>]) -> Vec<f64> {
        self.rules
            .iter()
            .enumerate()
            .map(|(k, rule)| match *rule {
                Rule::Slab(r) => rows[r][k],
                Rule::Largest => largest(rows.iter().map(|row| row[k]), f64::NEG_INFINITY),
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_probe_is_read_by_its_slab_and_a_whole_fluid_probe_by_the_largest_reading() {
        let probes = SlabProbes {
            rules: vec![Rule::Slab(1), Rule::Largest, Rule::Largest],
        };
        let rows = vec![vec![0.0, 0.2, 1.0], vec![5.0, 0.7, f64::NAN], vec![0.0, 0.1, 2.0]];
        let row = probes.combine(&rows);
        assert_eq!(row[0], 5.0);
        assert_eq!(row[1], 0.7);
        assert!(row[2].is_nan(), "a NaN in one slab's reading is kept: {row:?}");
    }
}
