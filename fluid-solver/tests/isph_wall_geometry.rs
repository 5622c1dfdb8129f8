//! ISPH (issue 12): the solids' normals, depths and convexity flags kept by particle id
//! ([`fluid_solver::isph::walls::WallFields::update_geometry`]) are the bits a fresh
//! computation gives ([`walls::normals`], [`walls::depths`], [`walls::convex`]), after the water has moved and the
//! cell sort has reordered every particle.

use crate::isph_slab;

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
    let radius = cfg.isph.as_ref().map_or(2.4, |s| s.support());
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
        fields.update_geometry(&k, &list, &p, true);
        let mut normals = VectorField::default();
        let mut depths = Vec::new();
        walls::normals(&k, &list, &p, &mut normals);
        walls::depths(&k, &list, &p, &normals, &mut depths);
        let mut convex = Vec::new();
        walls::convex(&k, &list, &p, &mut convex);
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
                    && fields.depth[w].to_bits() == fresh_depth.to_bits()
                    && fields.convex[w] == convex[w],
                "particle {} ({}) at t = {t} s: kept normal {got:?}, depth {}, convex {} against fresh {fresh:?}, {fresh_depth}, {}",
                p.id[w],
                Kind::from_code(p.kind[w]).name(),
                fields.depth[w],
                fields.convex[w],
                convex[w],
            );
        }
        listed_before = listed.iter().map(|&w| p.id[w]).collect();
    }
}

/// A solid cube of 6³ lattice sites inside water: its edges and corners are convex, its face
/// centres and everything inside are not ([`walls::convex`], module doc of `isph::walls`: only a
/// convex solid releases the water it pulls).
#[test]
fn a_submerged_blocks_edges_and_corners_are_convex_and_its_faces_are_not() {
    let spacing = 0.01;
    let k = Wendland::new(spacing, 2.4);
    let limit = walls::convex_fill_limit(&k);
    println!("convex below a solid fill of {limit:.4}");
    // Lattice sums (module doc): midway between a flat wall's 0.813 and an edge's 0.659.
    assert!((limit - 0.736).abs() < 1e-3, "limit {limit}");
    let mut p = fluid_solver::particles::Particles::default();
    let block = 0..6;
    for i in -4..10 {
        for j in -4..10 {
            for l in -4..10 {
                let inside = block.contains(&i) && block.contains(&j) && block.contains(&l);
                let at = [i, j, l].map(|c| f64::from(c) * spacing);
                p.push(at, if inside { Kind::Wall } else { Kind::Fluid });
            }
        }
    }
    let mut grid = CellGrid::with_cell([-0.05; 3], [0.1; 3], cell_edge(spacing, 2.4));
    grid.sort(&mut p, &mut Vec::new());
    let mut list = NeighbourList::default();
    list.build(&grid, &p, &k);
    let mut convex = Vec::new();
    walls::convex(&k, &list, &p, &mut convex);
    let (mut wrong, mut edges) = (Vec::new(), 0);
    for (w, &flag) in convex.iter().enumerate() {
        if p.kind[w] != Kind::Wall.code() {
            assert_eq!(flag, 0, "a fluid particle flagged convex");
            continue;
        }
        let at = p.position(w).map(|c| (c / spacing).round() as i32);
        // On the cube's surface: how many coordinates sit on a face (0 or 5).
        let on_faces = at.iter().filter(|&&c| c == 0 || c == 5).count();
        let expect = on_faces >= 2;
        edges += usize::from(expect);
        if (flag == walls::CONVEX) != expect {
            wrong.push((at, on_faces, flag));
        }
    }
    println!("{edges} edge and corner sites of 216");
    assert_eq!(edges, 56, "12 edges of 4 sites and 8 corners");
    assert!(wrong.is_empty(), "flags wrong at {wrong:?}");
}
