//! Which body a lattice site belongs to: a box body takes the sites whose centre is inside its
//! box (faces included), a mesh body the sites whose centre is inside its closed mesh
//! ([`sites_inside_mesh`], the fill `[[solid]]`s use), all of them: a body is full of particles,
//! not a skin, so its particles' centroid and count are those of its volume.

use crate::particles::body_interior::BodyInterior;
use schemas::case::fluid::{Aabb, FluidConfig};
use schemas::geometry::{sites_inside_mesh, Lattice, SiteSet};

/// A body's shape on the lattice.
#[derive(Debug, Clone)]
enum Shape {
    Box(Aabb),
    Sites(SiteSet),
    /// A mesh body whose mesh was not read: no sites.
    Empty,
}

/// The shapes of a case's bodies, in the order of `[[body]]`.
#[derive(Debug, Clone)]
pub struct BodySites {
    shapes: Vec<Shape>,
}

impl BodySites {
    /// The bodies of `cfg` (on the lattice, with its files loaded) over the tank's `n` sites per
    /// axis.
    pub fn build(cfg: &FluidConfig, n: [i64; 3]) -> BodySites {
        let lattice = Lattice {
            origin: cfg.tank.min,
            spacing: cfg.spacing,
            n: n.map(|v| v.max(0) as usize),
        };
        let shapes = cfg
            .body
            .iter()
            .map(|b| match (b.box_bounds(), b.placed_mesh()) {
                (Some(bb), _) => Shape::Box(bb),
                (None, Some(mesh)) => Shape::Sites(sites_inside_mesh(mesh, &lattice)),
                (None, None) => Shape::Empty,
            })
            .collect();
        BodySites { shapes }
    }

    /// The index of the first body holding site `idx` (tank lattice indices) at `p`.
    pub fn body_at(&self, idx: [i64; 3], p: [f64; 3]) -> Option<usize> {
        self.shapes.iter().position(|s| match s {
            Shape::Box(b) => b.contains_point(p),
            Shape::Sites(set) => {
                idx.iter().all(|&v| v >= 0) && set.contains(idx[0] as usize, idx[1] as usize, idx[2] as usize)
            }
            Shape::Empty => false,
        })
    }

    /// Each body's inside for the instability detector ([`BodyInterior`]): a box body's box
    /// less half of `spacing`, a mesh body's sites about its initial centre (`centres`, in the
    /// order of the bodies); a mesh body whose mesh was not read has no sites.
    pub fn interiors(&self, centres: &[[f64; 3]], spacing: f64) -> Vec<BodyInterior> {
        let h = 0.5 * spacing;
        self.shapes
            .iter()
            .zip(centres)
            .map(|(s, &centre)| match s {
                Shape::Box(b) => BodyInterior::Box(std::array::from_fn(|a| 0.5 * (b.max[a] - b.min[a]) - h)),
                Shape::Sites(set) => BodyInterior::of_sites(set, centre),
                Shape::Empty => BodyInterior::Sites {
                    sites: SiteSet::empty(&Lattice {
                        origin: centre,
                        spacing,
                        n: [0; 3],
                    }),
                    centre,
                },
            })
            .collect()
    }
}
