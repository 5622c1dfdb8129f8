//! The lattice sites of a case's mesh solids (`[[solid]]`) and terrains (`[[terrain]]`) inside
//! the tank: a site whose centre is inside a closed mesh ([`sites_inside_mesh`]) or not above a
//! terrain's surface is solid; of those, the skin `wall_layers` sites deep (Chebyshev lattice
//! distance to a site that is not solid, [`SiteSet::within_layers_of_outside`]) become wall
//! particles, as the tank's walls are `wall_layers` deep, and the sites deeper inside get none.
//! The tank's walls surround the lattice, so its bounds count as solid: a terrain's cut faces at
//! the tank's sides are no surface.

use schemas::case::fluid::FluidConfig;
use schemas::geometry::{sites_below_surface, sites_inside_mesh, Lattice, SiteSet};

/// The solid sites of the tank's lattice and their skin.
#[derive(Debug, Clone, Default)]
pub struct SolidSites {
    sets: Option<(SiteSet, SiteSet)>,
}

impl SolidSites {
    /// The solid sites of `cfg` (on the lattice, with its files loaded) over the tank's `n`
    /// sites per axis.
    pub fn build(cfg: &FluidConfig, n: [i64; 3]) -> SolidSites {
        if cfg.solid.is_empty() && cfg.terrain.is_empty() {
            return SolidSites { sets: None };
        }
        let lattice = Lattice {
            origin: cfg.tank.min,
            spacing: cfg.spacing,
            n: n.map(|v| v.max(0) as usize),
        };
        let mut solid = SiteSet::empty(&lattice);
        for s in &cfg.solid {
            let mesh = s
                .placed
                .get()
                .expect("a solid's mesh is read when the case is loaded (FluidConfig::load_files)");
            solid.insert_all(&sites_inside_mesh(mesh, &lattice));
        }
        for t in &cfg.terrain {
            solid.insert_all(&sites_below_surface(|x, y| t.height_at(x, y), &lattice));
        }
        let skin = solid.within_layers_of_outside(cfg.wall_layers as usize, false);
        SolidSites {
            sets: Some((solid, skin)),
        }
    }

    /// Whether site `idx` (tank lattice indices) is in a solid's skin: a wall particle.
    pub fn holds(&self, idx: [i64; 3]) -> bool {
        self.sets.as_ref().is_some_and(|(_, skin)| at(skin, idx))
    }

    /// The solid sites, skin and buried (`None` without solids or terrains).
    pub fn solid(&self) -> Option<&SiteSet> {
        self.sets.as_ref().map(|(solid, _)| solid)
    }

    /// Whether site `idx` is solid but deeper than the skin: no particle.
    pub fn buries(&self, idx: [i64; 3]) -> bool {
        self.sets
            .as_ref()
            .is_some_and(|(solid, skin)| at(solid, idx) && !at(skin, idx))
    }
}

impl SolidSites {
    /// Whether `r` lies more than about half a spacing inside a solid ([`deep_inside_sites`];
    /// beyond the lattice is the tank's wall: solid). The stability monitor's "through a wall",
    /// as a wall box's is its box less half a spacing.
    pub fn deep_inside(&self, r: [f64; 3]) -> bool {
        self.sets
            .as_ref()
            .is_some_and(|(solid, _)| deep_inside_sites(solid, r, true))
    }
}

/// Whether `r` lies more than about half a spacing inside the sites of `set`: the site whose
/// cube holds it and that site's six face neighbours are all in `set` (a neighbour beyond the
/// lattice counts as in it when `beyond_is_in`).
pub fn deep_inside_sites(set: &SiteSet, r: [f64; 3], beyond_is_in: bool) -> bool {
    let l = set.lattice();
    let idx: [i64; 3] = std::array::from_fn(|a| ((r[a] - l.origin[a]) / l.spacing).floor() as i64);
    at(set, idx)
        && (0..3).all(|a| {
            [-1, 1].iter().all(|d| {
                let mut n = idx;
                n[a] += d;
                let beyond = n[a] < 0 || n[a] >= l.n[a] as i64;
                if beyond {
                    beyond_is_in
                } else {
                    at(set, n)
                }
            })
        })
}

fn at(set: &SiteSet, idx: [i64; 3]) -> bool {
    idx.iter().all(|&v| v >= 0) && set.contains(idx[0] as usize, idx[1] as usize, idx[2] as usize)
}
