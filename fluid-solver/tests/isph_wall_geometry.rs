//! ISPH (issue 12): the solids' normals and depths kept by particle id
//! ([`fluid_solver::isph::walls::WallFields::update_geometry`]) are the bits a fresh
//! computation gives ([`walls::normals`], [`walls::depths`]), after the water has moved and the
//! cell sort has reordered every particle.

mod common;
mod isph_slab;

use fluid_solver::isph::kernel::Wendland;
use fluid_solver::isph::neighbour_list::{cell_edge, NeighbourList};
use fluid_solver::isph::walls::{self, WallFields};
use fluid_solver::neighbour_search::CellGrid;
use fluid_solver::vector_field::VectorField;
use fluid_solver::{FluidSolver, Kind};
use std::collections::HashSet;

#[test]
fn kept_wall_normals_and_depths_equal_fresh_ones_after_the_water_moved() {
    let cfg = isph_slab::isph_slab();
    let radius = cfg.isph.as_ref().map_or(2.4, |s| s.influence_radius);
    let k = Wendland::new(cfg.spacing, radius);
    let mut solver = FluidSolver::new(&cfg);
    let mut fields = WallFields::default();
    let mut listed_before: HashSet<u32> = HashSet::new();
    for (t, expect_kept) in [(0.05, false), (0.2, true)] {
        solver.advance_to(t).unwrap_or_else(|e| panic!("{e}"));
        let mut p = solver.particles().clone();
        let d = solver.domain();
        let mut grid = CellGrid::with_cell(
            d.lo,
            [d.hi[0], d.hi[1], d.hi[2].max(1.0)],
            cell_edge(cfg.spacing, radius),
        );
        grid.sort(&mut p, &mut Vec::new());
        let mut list = NeighbourList::default();
        list.build(&grid, &p, &k);
        fields.update_geometry(&k, &list, &p);
        let mut normals = VectorField::default();
        let mut depths = Vec::new();
        walls::normals(&k, &list, &p, &mut normals);
        walls::depths(&k, &list, &p, &normals, &mut depths);
        let listed: Vec<usize> = (0..p.len())
            .filter(|&w| p.kind[w] != Kind::Fluid.code() && !list.of(w).is_empty())
            .collect();
        let kept = listed
            .iter()
            .filter(|&&w| listed_before.contains(&p.id[w]))
            .count();
        println!(
            "t = {t} s: {} solids with water near, {kept} of them kept from before",
            listed.len()
        );
        assert!(!listed.is_empty(), "no solid has water near at t = {t} s");
        if expect_kept {
            assert!(
                kept > 0,
                "no solid's geometry was kept from t = 0.05 s: the cache is not exercised"
            );
        }
        for (w, fresh_depth) in depths.iter().enumerate() {
            let got = [fields.normals.x[w], fields.normals.y[w], fields.normals.z[w]];
            let fresh = [normals.x[w], normals.y[w], normals.z[w]];
            assert!(
                got.iter().zip(&fresh).all(|(a, b)| a.to_bits() == b.to_bits())
                    && fields.depth[w].to_bits() == fresh_depth.to_bits(),
                "particle {} ({}) at t = {t} s: kept normal {got:?}, depth {} against fresh {fresh:?}, {fresh_depth}",
                p.id[w],
                Kind::from_code(p.kind[w]).name(),
                fields.depth[w],
            );
        }
        listed_before = listed.iter().map(|&w| p.id[w]).collect();
    }
}
