//! The interacting-pair count (GPIPS' numerator) against lattice counting and a brute-force count:
//! on a simple cubic lattice a particle has 6, 12, 8 and 6 neighbours at squared distances 1, 2,
//! 3 and 4 Δs², so 18 within 1.5 Δs and 32 within 2.1 Δs.

use fluid_solver::neighbour_search::CellGrid;
use fluid_solver::neighbours::interacting_pairs::interacting_pairs;
use fluid_solver::particles::Particles;
use fluid_solver::Kind;

const DS: f64 = 0.01;

/// A 9 × 9 × 9 lattice whose particles are fluid where `fluid(i, j, k)`, walls elsewhere, sorted
/// by its grid.
fn lattice(fluid: impl Fn(i32, i32, i32) -> bool) -> (Particles, CellGrid) {
    let mut p = Particles::default();
    for i in 0..9 {
        for j in 0..9 {
            for k in 0..9 {
                let kind = if fluid(i, j, k) { Kind::Fluid } else { Kind::Wall };
                let at = [i, j, k].map(|c| f64::from(c) * DS);
                p.push_moving(at, [0.0; 3], kind, p.len() as u32);
            }
        }
    }
    let mut grid = CellGrid::new([0.0; 3], [8.0 * DS; 3], DS);
    grid.sort(&mut p, &mut Vec::new());
    (p, grid)
}

#[test]
fn one_fluid_particle_in_a_lattice_has_the_lattices_neighbour_counts() {
    let (p, grid) = lattice(|i, j, k| (i, j, k) == (4, 4, 4));
    assert_eq!(interacting_pairs(&p, &grid, 1.5 * DS), 18);
    assert_eq!(interacting_pairs(&p, &grid, 2.1 * DS), 32);
}

#[test]
fn a_block_of_fluid_counts_every_pair_a_brute_force_search_finds() {
    let (p, grid) = lattice(|i, j, k| i < 5 && j > 2 && k != 4);
    let radius = 2.4 * DS;
    let mut brute = 0u64;
    for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid.code()) {
        for j in (0..p.len()).filter(|&j| j != i) {
            let d2 = (p.x[j] - p.x[i]).powi(2) + (p.y[j] - p.y[i]).powi(2) + (p.z[j] - p.z[i]).powi(2);
            brute += u64::from(d2 < radius * radius);
        }
    }
    assert!(brute > 0);
    assert_eq!(interacting_pairs(&p, &grid, radius), brute);
}
