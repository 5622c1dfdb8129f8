//! Geometry of any extent is placed on the particle lattice (issue 15, item 5): the tank,
//! water and obstacle of the dam-break-with-obstacle experiment (3.22 m tank, 1.228 × 0.55 m
//! column, 0.161 m box), none whole multiples of Δs = 0.02 m in every direction, are built
//! within half a layer of their sizes, with a message for every face that moved.

use crate::common;

use fluid_solver::layout;
use fluid_solver::Kind;
use schemas::case::fluid::Aabb;
use schemas::case::FluidConfig;

/// The built extent along `axis` of the particles of `kind` inside `region`: the outermost
/// centres ± Δs/2.
fn built(
    p: &fluid_solver::particles::Particles,
    kind: Kind,
    region: &Aabb,
    axis: usize,
    ds: f64,
) -> (f64, f64) {
    let coord = [&p.x, &p.y, &p.z][axis];
    let inside = (0..p.len()).filter(|&i| p.kind[i] == kind.code() && region.contains_point(p.position(i)));
    let (lo, hi) = inside.fold((f64::MAX, f64::MIN), |(lo, hi), i| {
        (lo.min(coord[i]), hi.max(coord[i]))
    });
    (lo - 0.5 * ds, hi + 0.5 * ds)
}

#[test]
fn a_tank_of_3_22_m_and_boxes_off_the_lattice_are_built_within_half_a_layer() {
    let (_, mut cfg): (_, FluidConfig) = common::load_case("hydrostatic-tank");
    let ds = 0.02;
    cfg.spacing = ds;
    cfg.time_step = 1.0e-3;
    // A 0.161 m wide slice of the experiment's tank (the width is the obstacle's, off the lattice).
    cfg.tank.min = [0.0, 0.0, 0.0];
    cfg.tank.max = [3.22, 0.161, 1.0];
    cfg.block = vec![Aabb {
        min: [3.22 - 1.228, 0.0, 0.0],
        max: [3.22, 0.161, 0.55],
    }];
    cfg.wall = vec![Aabb {
        min: [0.6635, 0.0, 0.0],
        max: [0.6635 + 0.161, 0.161, 0.161],
    }];
    cfg.validate("fluid.water")
        .unwrap_or_else(|e| panic!("a tank of any extent is accepted: {e:?}"));
    let built_layout = layout::build(&cfg);
    let p = &built_layout.particles;
    for note in &built_layout.notes {
        println!("{note}");
    }
    // The tank: its inner faces are half a spacing outside the outermost wall-free sites, i.e.
    // the inner face of the far wall is where its first wall layer's centres less Δs/2 are.
    let tank = built_layout.tank;
    for (a, want) in [(0, 3.22), (1, 0.161), (2, 1.0)] {
        let got = tank.max[a] - tank.min[a];
        println!("tank axis {a}: {want} m asked, {got:.4} m built");
        assert!(
            (got - want).abs() <= 0.5 * ds + 1e-12,
            "tank axis {a}: {got} m for {want} m"
        );
        // The first wall layer beyond the far face sits at the built face + Δs/2.
        let mut probe = [0.5 * ds; 3];
        probe[a] = tank.max[a] + 0.5 * ds;
        let wall_there = (0..p.len()).any(|i| {
            p.kind[i] == Kind::Wall.code() && (0..3).all(|b| (p.position(i)[b] - probe[b]).abs() < 1e-9)
        });
        if a < 2 {
            assert!(
                wall_there,
                "no wall particle at {probe:?}, just beyond the built face"
            );
        }
    }
    let whole = Aabb {
        min: [-1.0; 3],
        max: [4.0, 1.0, 2.0],
    };
    let water = built(p, Kind::Fluid, &whole, 0, ds);
    let water_h = built(p, Kind::Fluid, &whole, 2, ds);
    println!("water x {water:?}, z {water_h:?}");
    assert!(((water.1 - water.0) - 1.228).abs() <= 0.5 * ds + 1e-12);
    assert!(((water_h.1 - water_h.0) - 0.55).abs() <= 0.5 * ds + 1e-12);
    let obstacle_region = Aabb {
        min: [0.5, 0.0, 0.0],
        max: [1.0, 0.16, 0.3],
    };
    for a in [0, 2] {
        let (lo, hi) = built(p, Kind::Wall, &obstacle_region, a, ds);
        println!("obstacle axis {a}: {:.4} m built of 0.161 m", hi - lo);
        assert!(
            ((hi - lo) - 0.161).abs() <= 0.5 * ds + 1e-12,
            "obstacle axis {a}: {} m",
            hi - lo
        );
    }
    assert!(
        built_layout
            .notes
            .iter()
            .any(|n| n.starts_with("tank") && n.contains("max.y")),
        "the tank's rounding is reported: {:?}",
        built_layout.notes
    );
    assert!(built_layout.notes.iter().any(|n| n.starts_with("wall[0]")));
    assert!(built_layout.notes.iter().any(|n| n.starts_with("block[0]")));
}
