//! A body's inside for the instability detector, checked in the body's frame at its present
//! pose: a point `r` is taken back to the body's initial placement, `r₀ = c₀ + R(q)ᵀ (r − c)`
//! (pose: centre `c`, quaternion `q` relative to the initial placement; `c₀` the initial centre).
//! A box body's inside is its box shrunk by half a spacing (behind the centres of its outer
//! particle layer); a mesh body's is that of its lattice sites, by the rule of the mesh solids
//! ([`deep_inside_sites`]: the site holding `r₀` and its six face neighbours are all the body's),
//! "more than about half a spacing inside". A mesh body's bounding box may hold water (under a
//! deck's arch); its sites do not.

use crate::bodies::rotate;
use crate::particles::solid_sites::deep_inside_sites;
use schemas::geometry::{Lattice, SiteSet};

/// What is inside one body, about its initial centre.
#[derive(Debug, Clone, PartialEq)]
pub enum BodyInterior {
    /// A box body: its half extents less half a spacing.
    Box([f64; 3]),
    /// A mesh body: its sites, on the tank's lattice cropped to them, and its initial centre.
    Sites { sites: SiteSet, centre: [f64; 3] },
}

impl BodyInterior {
    /// The sites `set` of a mesh body of initial centre `centre`, kept on the smallest block of
    /// `set`'s lattice that holds them (the same sites, a smaller set).
    pub fn of_sites(set: &SiteSet, centre: [f64; 3]) -> BodyInterior {
        let l = set.lattice();
        let bounds = set.iter().fold(None, |b: Option<([usize; 3], [usize; 3])>, s| {
            Some(match b {
                None => (s, s.map(|v| v + 1)),
                Some((lo, hi)) => (
                    std::array::from_fn(|a| lo[a].min(s[a])),
                    std::array::from_fn(|a| hi[a].max(s[a] + 1)),
                ),
            })
        });
        let (lo, hi) = bounds.unwrap_or(([0; 3], [0; 3]));
        let cropped = Lattice {
            origin: std::array::from_fn(|a| l.origin[a] + lo[a] as f64 * l.spacing),
            spacing: l.spacing,
            n: std::array::from_fn(|a| hi[a] - lo[a]),
        };
        let mut sites = SiteSet::empty(&cropped);
        for s in set.iter() {
            sites.insert(s[0] - lo[0], s[1] - lo[1], s[2] - lo[2]);
        }
        BodyInterior::Sites { sites, centre }
    }

    /// Whether the point at `local` (in the body's frame about its centre, [`body_frame`]) is
    /// inside.
    pub fn holds(&self, local: [f64; 3]) -> bool {
        match self {
            BodyInterior::Box(half) => (0..3).all(|a| local[a].abs() < half[a]),
            BodyInterior::Sites { sites, centre } => {
                deep_inside_sites(sites, std::array::from_fn(|a| centre[a] + local[a]), false)
            }
        }
    }

    /// The rule [`BodyInterior::holds`] applies, in words.
    pub fn rule(&self) -> String {
        match self {
            BodyInterior::Box(half) => format!("within its half extents {half:?} less half a spacing"),
            BodyInterior::Sites { .. } => {
                "more than half a spacing inside its lattice sites (the site holding it and its six neighbours are the body's)".into()
            }
        }
    }
}

/// `r` in the frame of a body at `pose` (centre, quaternion w x y z), about its centre:
/// `R(q)ᵀ (r − c)`.
pub fn body_frame(r: [f64; 3], pose: [f64; 7]) -> [f64; 3] {
    let inverse = [pose[3], -pose[4], -pose[5], -pose[6]];
    rotate(inverse, [r[0] - pose[0], r[1] - pose[1], r[2] - pose[2]])
}
