//! The fluid's side of the unresolved drag coupling (issue 13): sampling at points (Shepard
//! velocity, λ_min of the moment matrix) and S2-24's spreading of point reactions, on hand-made
//! particle lattices: water below z = 0 (top particle layer at −Δs/2, so the free surface of the
//! particle water is at z = 0), a floor of wall particles below z = −H.

use fluid_solver::neighbour_search::{CellGrid, Rows};
use fluid_solver::particles::Particles;
use fluid_solver::unresolved::kernel::Wendland;
use fluid_solver::unresolved::sampling::{sample, smallest_eigenvalue};
use fluid_solver::unresolved::spreading::spread;
use fluid_solver::Kind;
use schemas::validation::{largest_abs, record, Record};

const DS: f64 = 0.01;
/// Water depth [spacings] and half-width [spacings].
const DEPTH: i32 = 8;
const HALF: i32 = 8;

/// What the records of this file's test `test` on the hand-made pool share; `place` says where
/// in the pool it looks.
fn pool_record(id: &str, test: &str, place: &str) -> Record {
    Record {
        id: format!("drag-fluid-side-{id}"),
        capability: "Unresolved drag, the fluid's side: sampling and spreading (S2-19 … S2-24)".into(),
        case: format!("a particle pool 16 × 16 × 8 Δs on a wall floor, {place}"),
        resolution: format!("Δs = {DS} m, Wendland kernel of support 2.4 Δs"),
        bound_source: "round-off, or the test's derivation (unresolved_fluid_side.rs)".into(),
        source: format!("fluid-solver/tests/unresolved_fluid_side.rs::{test}"),
        ..Default::default()
    }
}

/// Where the spreading tests put a reaction: at the surface, at the floor, at a side and the
/// surface, and inside the pool.
fn reaction_places() -> [(&'static str, [f64; 3]); 4] {
    [
        ("at the surface", [0.0, 0.0, -0.3 * DS]),
        ("at the floor", [0.2 * DS, 0.0, -f64::from(DEPTH) * DS + 0.1 * DS]),
        (
            "at a side and the surface",
            [f64::from(HALF) * DS - 0.2 * DS, 0.0, -0.1 * DS],
        ),
        ("inside", [0.0, 0.0, -4.0 * DS]),
    ]
}

/// Water in |x|, |y| < HALF Δs, −DEPTH Δs < z < 0, on a floor 3 layers thick; every fluid
/// particle moves with `velocity(position)`.
fn pool(velocity: impl Fn([f64; 3]) -> [f64; 3]) -> (Particles, CellGrid) {
    let mut p = Particles::default();
    let c = |i: i32| (f64::from(i) + 0.5) * DS;
    for i in -HALF..HALF {
        for j in -HALF..HALF {
            for k in -DEPTH - 3..0 {
                let x = [c(i), c(j), c(k)];
                if k < -DEPTH {
                    p.push(x, if k == -DEPTH - 1 { Kind::Wall } else { Kind::Dummy });
                } else {
                    p.push(x, Kind::Fluid);
                    let n = p.len() - 1;
                    let v = velocity(x);
                    (p.vx[n], p.vy[n], p.vz[n]) = (v[0], v[1], v[2]);
                }
            }
        }
    }
    // the cell list over the pool and the air above it (sorting reorders the particles)
    let (h, d) = (f64::from(HALF) * DS, f64::from(DEPTH + 3) * DS);
    let mut grid = CellGrid::new([-h, -h, -d], [h, h, 6.0 * DS], DS);
    grid.sort(&mut p, &mut Vec::new());
    (p, grid)
}

/// Points on a vertical line through the middle, from the floor to just over the surface.
fn column() -> Vec<f64> {
    (0..=2 * DEPTH + 1)
        .flat_map(|k| {
            [
                0.1 * DS,
                -0.2 * DS,
                -f64::from(DEPTH) * DS + 0.5 * f64::from(k) * DS,
            ]
        })
        .collect()
}

#[test]
fn a_uniform_field_is_sampled_exactly_at_the_surface_and_the_wall() {
    let u = [0.7, -0.3, 0.2];
    let (p, grid) = pool(|_| u);
    let points = column();
    let samples = sample(&p, &grid, DS, &points);
    let worst = largest_abs(
        samples
            .iter()
            .flat_map(|s| s.velocity.iter().zip(&u).map(|(a, b)| a - b)),
    );
    record(Record {
        reference: "the uniform velocity sampled".into(),
        measure: "largest |sampled − exact| velocity component (Shepard weights sum to one)".into(),
        value: worst,
        bound: Some(1e-14),
        unit: "m/s".into(),
        ..pool_record(
            "uniform-field",
            "a_uniform_field_is_sampled_exactly_at_the_surface_and_the_wall",
            "points from the floor to over the surface",
        )
    });
    for (s, x) in samples.iter().zip(points.chunks_exact(3)) {
        // Shepard weights sum to one: the error is the rounding of ~60 terms.
        let exact = s.velocity.iter().zip(&u).all(|(a, b)| (a - b).abs() <= 1e-14);
        assert!(exact, "at {x:?}: {:?}", s.velocity);
    }
}

/// Shift of the kernel-weighted centroid from a point on the flat surface of a half-space:
/// `2π ∫_0^R W(r) r³ dr` (midpoint rule, 10⁵ intervals: converged to 1e-10 relative).
fn half_space_shift(kernel: &Wendland) -> f64 {
    let n = 100_000;
    let h = kernel.radius / n as f64;
    2.0 * std::f64::consts::PI
        * (0..n)
            .map(|i| {
                let r = (i as f64 + 0.5) * h;
                kernel.value(r) * r.powi(3) * h
            })
            .sum::<f64>()
}

#[test]
fn a_linear_field_stays_within_the_centroid_shift_bound_near_the_surface_and_the_wall() {
    // u = G z: Shepard returns G z̄ (z̄ the weighted centroid of the water present), so the
    // error is G (z̄ − z). The worst case is a point on a flat boundary, whose missing half
    // shifts the centroid by the half-space value d; the particle water's boundary lies Δs/2
    // beyond its last particle layer, which adds at most Δs/2, and a point a height h over the
    // surface is h farther from the water: |e| ≤ G (d + Δs/2 + max(h, 0)).
    let g = 2.0;
    let (p, grid) = pool(|x| [g * x[2], 0.0, 0.0]);
    let kernel = Wendland::for_spacing(DS);
    let d = half_space_shift(&kernel);
    let bound = g * (d + 0.5 * DS);
    let points = column();
    let mut worst: f64 = 0.0;
    let mut inside: f64 = 0.0;
    for (s, x) in sample(&p, &grid, DS, &points).iter().zip(points.chunks_exact(3)) {
        let e = (s.velocity[0] - g * x[2]).abs();
        worst = worst.max(e);
        if x[2] > -f64::from(DEPTH) * DS + kernel.radius && x[2] < -kernel.radius {
            inside = inside.max(e);
        }
        let bound = bound + g * x[2].max(0.0);
        assert!(
            e <= bound,
            "at z = {:.4}: error {e:.3e} above G (d + Δs/2 + h) = {bound:.3e}",
            x[2]
        );
    }
    eprintln!("linear field: worst error {worst:.3e} m/s, bound {bound:.3e} (d = {d:.4e} m), full support {inside:.3e}");
    record(Record {
        reference: "the linear velocity u = G z, G = 2 /s".into(),
        measure: "largest |sampled − exact| (a full, symmetric support has its centroid on the point)".into(),
        value: inside,
        bound: Some(1e-12),
        unit: "m/s".into(),
        ..pool_record(
            "linear-field-full-support",
            "a_linear_field_stays_within_the_centroid_shift_bound_near_the_surface_and_the_wall",
            "points whose support is full of water",
        )
    });
    assert!(
        inside <= 1e-12,
        "a full, symmetric support has its centroid on the point: {inside:.3e}"
    );
}

#[test]
fn lambda_min_is_one_inside_one_half_on_the_surface_and_zero_in_the_air() {
    let (p, grid) = pool(|_| [0.0; 3]);
    let at = |z: f64| sample(&p, &grid, DS, &[0.1 * DS, -0.2 * DS, z])[0].lambda_min;
    let (inside, surface, floor, air) = (at(-4.0 * DS), at(0.0), at(-f64::from(DEPTH) * DS), at(3.0 * DS));
    eprintln!(
        "λ_min: inside {inside:.4}, on the surface {surface:.4}, on the floor {floor:.4}, in the air {air}"
    );
    // The lattice sums of a Wendland kernel of support 2.4 Δs differ from the integrals by a
    // few per cent (measured: see the printout); S2-20's thresholds 0.5 and 0.9 sit well apart.
    for (id, place, value) in [
        ("inside", "inside the water", inside - 1.0),
        ("surface", "on the surface", surface - 0.5),
    ] {
        record(Record {
            reference: "the moment matrix's integral: λ_min = 1 in a full support, 1/2 on a flat surface"
                .into(),
            measure: "λ_min − its integral value".into(),
            value,
            bound: Some(0.05),
            ..pool_record(
                &format!("lambda-min-{id}"),
                "lambda_min_is_one_inside_one_half_on_the_surface_and_zero_in_the_air",
                place,
            )
        });
    }
    assert!((inside - 1.0).abs() < 0.05, "inside: {inside}");
    assert!((surface - 0.5).abs() < 0.05, "surface: {surface}");
    assert!(
        floor > 0.9,
        "the floor's wall particles fill the support: {floor}"
    );
    assert_eq!(air, 0.0, "no water within the support is dry");
}

#[test]
fn a_spread_reaction_sums_to_the_reaction_near_a_wall_and_the_surface() {
    let (p, grid) = pool(|_| [0.0; 3]);
    let f = [3.0, -1.5, 40.0];
    let mut worst: f64 = 0.0;
    for (what, x) in reaction_places() {
        let reactions = [x[0], x[1], x[2], f[0], f[1], f[2]];
        let s = spread(&p, &grid, DS, &reactions, &[], &[]);
        let mut sum = [0.0; 3];
        for (i, fi) in s.force.chunks_exact(3).enumerate() {
            if p.kind[i] != Kind::Fluid.code() {
                assert_eq!(fi, [0.0; 3], "{what}: a wall particle got a share");
            }
            (0..3).for_each(|c| sum[c] += fi[c]);
        }
        worst = largest_abs((0..3).map(|c| sum[c] - f[c]).chain([worst]));
        record(Record {
            reference: "the point reaction spread (its shares must sum to it)".into(),
            measure: "largest |Σ shares − reaction| over components and places".into(),
            value: worst,
            bound: Some(1e-13 * 40.0),
            unit: "N".into(),
            ..pool_record(
                "spread-sum",
                "a_spread_reaction_sums_to_the_reaction_near_a_wall_and_the_surface",
                "a reaction of 40 N at the surface, the floor, a side and inside",
            )
        });
        for c in 0..3 {
            // shares normalised to one: round-off of ~100 terms
            assert!(
                (sum[c] - f[c]).abs() <= 1e-13 * 40.0,
                "{what}: Σ f_k = {sum:?}, reaction {f:?}"
            );
        }
        assert_eq!((s.moved, s.unapplied), (0, 0));
    }
}

#[test]
fn a_reaction_with_no_water_near_its_centroid_goes_to_its_sample_point_or_is_reported() {
    let (p, grid) = pool(|_| [0.0; 3]);
    let f = [1.0, 2.0, 3.0];
    let dry = [0.0, 0.0, 5.0 * DS];
    let wet = [0.0, 0.0, -2.0 * DS];
    let s = spread(
        &p,
        &grid,
        DS,
        &[dry[0], dry[1], dry[2], f[0], f[1], f[2]],
        &wet,
        &[],
    );
    let sum: Vec<f64> = (0..3)
        .map(|c| s.force.chunks_exact(3).map(|fi| fi[c]).sum())
        .collect();
    assert_eq!(s.moved, 1);
    assert!(
        sum.iter().zip(&f).all(|(a, b)| (a - b).abs() <= 1e-14 * 3.0),
        "{sum:?}"
    );
    let s = spread(
        &p,
        &grid,
        DS,
        &[dry[0], dry[1], dry[2], f[0], f[1], f[2]],
        &dry,
        &[],
    );
    assert_eq!((s.unapplied, s.unapplied_force), (1, f));
    assert!(s.force.iter().all(|&v| v == 0.0));
}

#[test]
fn the_closed_form_smallest_eigenvalue_matches_a_symmetric_eigensolver() {
    let mut worst: f64 = 0.0;
    for m in [
        [1.0, 0.0, 0.0, 1.0, 0.0, 1.0],
        [0.5, 0.0, 0.0, 1.0, 0.0, 1.0],
        [1.0, 0.2, -0.1, 0.7, 0.05, 0.5],
        [2.0, 1.0, 1.0, 2.0, 1.0, 2.0],
        [0.0; 6],
    ] {
        let full = nalgebra::Matrix3::new(m[0], m[1], m[2], m[1], m[3], m[4], m[2], m[4], m[5]);
        let reference = nalgebra::SymmetricEigen::new(full).eigenvalues.min();
        let got = smallest_eigenvalue(&m);
        worst = largest_abs([worst, got - reference]);
        record(Record {
            id: "drag-fluid-side-lambda-min-closed-form".into(),
            capability: "Unresolved drag, the fluid's side: λ_min of the moment matrix in closed form".into(),
            reference: "nalgebra's symmetric eigensolver".into(),
            case: "five symmetric 3 × 3 matrices (identity, diagonal, full, singular, zero)".into(),
            resolution: "closed form (trigonometric)".into(),
            measure: "largest |closed form − eigensolver| of the smallest eigenvalue".into(),
            value: worst,
            bound: Some(1e-12),
            bound_source: "round-off".into(),
            source: "fluid-solver/tests/unresolved_fluid_side.rs::the_closed_form_smallest_eigenvalue_matches_a_symmetric_eigensolver"
                .into(),
            ..Default::default()
        });
        assert!((got - reference).abs() <= 1e-12, "{m:?}: {got} vs {reference}");
    }
}

/// The trimmed point query (cells within reach of the kernel given how far particles drifted
/// from their cells since the sort) visits the same particles in the same order as the 7³ block,
/// so sampling and spreading sums are equal to the last bit: particles moved after the sort by up
/// to 0.3 Δs (one by 0.7 Δs), points inside, on the surface, in the air, off the grid's side.
#[test]
fn the_trimmed_point_query_sees_what_the_full_block_sees_after_particles_drifted() {
    let (mut p, grid) = pool(|_| [0.0; 3]);
    // a fixed pseudo-random shift per particle (Weyl sequence), after the sort
    for j in 0..p.len() {
        let f = |k: f64| ((j as f64 * k).fract() - 0.5) * 0.6 * DS;
        p.x[j] += f(0.618_034);
        p.y[j] += f(0.414_214);
        p.z[j] += f(0.732_051);
    }
    p.z[7] += 0.4 * DS;
    let drift = grid.drift(&p);
    assert!(drift > 0.2 * DS && drift < 0.71 * DS, "drift {drift}");
    let radius = Wendland::for_spacing(DS).radius;
    let mut points = 0;
    for i in -12..=12 {
        for k in -14..=8 {
            let at = [f64::from(i) * 0.77 * DS, 0.31 * DS, f64::from(k) * 0.83 * DS];
            let mut full = Vec::new();
            grid.for_each_near_point(&p, at, radius, |j, r2| full.push((j, r2)));
            let mut trimmed = Vec::new();
            grid.for_each_near_point_trimmed(&p, at, radius, drift, Rows::All, |j, r2, _| {
                trimmed.push((j, r2))
            });
            assert_eq!(full, trimmed, "at {at:?}");
            let fluid: Vec<_> = full
                .into_iter()
                .filter(|&(j, _)| p.kind[j] == Kind::Fluid.code())
                .collect();
            let mut rows = Vec::new();
            grid.for_each_near_point_trimmed(&p, at, radius, drift, Rows::Fluid, |j, r2, _| {
                if p.kind[j] == Kind::Fluid.code() {
                    rows.push((j, r2))
                }
            });
            assert_eq!(fluid, rows, "fluid rows at {at:?}");
            // the sampling's query: the same particles, none only where no water is within reach
            let mut sampled = Vec::new();
            let wet =
                grid.for_each_near_point_trimmed(&p, at, radius, drift, Rows::AllIfFluid, |j, r2, _| {
                    sampled.push((j, r2))
                });
            if wet {
                assert_eq!(sampled, trimmed, "at {at:?}");
            } else {
                assert!(fluid.is_empty() && sampled.is_empty(), "water missed near {at:?}");
            }
            points += usize::from(!trimmed.is_empty());
        }
    }
    assert!(points > 300, "{points} points saw particles");
}

/// The total of a spread, per axis, and whether any wall particle got a share.
fn spread_total(p: &Particles, force: &[f64]) -> ([f64; 3], bool) {
    let mut sum = [0.0; 3];
    let mut on_walls = false;
    for (i, fi) in force.chunks_exact(3).enumerate() {
        on_walls |= p.kind[i] != Kind::Fluid.code() && fi != [0.0; 3];
        (0..3).for_each(|c| sum[c] += fi[c]);
    }
    (sum, on_walls)
}

#[test]
fn a_wide_members_reaction_is_spread_flat_over_its_footprint_and_sums_to_itself() {
    let (p, grid) = pool(|_| [0.0; 3]);
    let f = [3.0, -1.5, 40.0];
    // a member 5 particles wide: flat within a = 2 Δs of the centroid, the kernel's tail to a + R
    let width = 5.0 * DS;
    let a = 2.0 * DS;
    let reach = a + Wendland::for_spacing(DS).radius;
    for (what, x) in reaction_places() {
        let reactions = [x[0], x[1], x[2], f[0], f[1], f[2]];
        let s = spread(&p, &grid, DS, &reactions, &[], &[width]);
        let (sum, on_walls) = spread_total(&p, &s.force);
        assert!(!on_walls, "{what}: a wall particle got a share");
        for c in 0..3 {
            // shares normalised to one: round-off of ~600 terms
            assert!(
                (sum[c] - f[c]).abs() <= 1e-13 * 40.0,
                "{what}: Σ f_k = {sum:?}, reaction {f:?}"
            );
        }
        assert_eq!((s.moved, s.unapplied), (0, 0));
        // the z share of each fluid particle against its distance from the centroid
        let shares: Vec<(f64, f64)> = (0..p.len())
            .filter(|&i| p.kind[i] == Kind::Fluid.code())
            .map(|i| {
                let r = ((p.x[i] - x[0]).powi(2) + (p.y[i] - x[1]).powi(2) + (p.z[i] - x[2]).powi(2)).sqrt();
                (r, s.force[3 * i + 2] / f[2])
            })
            .collect();
        let flat: Vec<f64> = shares.iter().filter(|(r, _)| *r <= a).map(|s| s.1).collect();
        let top = flat.iter().copied().fold(0.0, schemas::validation::max_or_nan);
        println!(
            "{what}: {} particles in the flat part, share {top:.3e} each",
            flat.len()
        );
        assert!(flat.len() >= 8, "{what}: the footprint holds water");
        // equal weights W(0), normalised: the same share to round-off
        assert!(
            flat.iter().all(|w| (w - top).abs() <= 1e-14),
            "{what}: the footprint's shares differ"
        );
        for (r, w) in &shares {
            if *r > a {
                assert!(*w <= top, "{what}: a share beyond the footprint is larger");
            }
            if *r >= reach {
                assert_eq!(*w, 0.0, "{what}: a share beyond a + R at r = {r}");
            }
        }
    }
}

#[test]
fn a_member_no_wider_than_a_particle_spreads_as_s2_24_and_a_wider_one_departs_continuously() {
    let (p, grid) = pool(|_| [0.0; 3]);
    let f = [3.0, -1.5, 40.0];
    let reactions = [
        0.0,
        0.0,
        -0.3 * DS,
        f[0],
        f[1],
        f[2], //
        0.2 * DS,
        0.0,
        -7.9 * DS,
        f[0],
        f[1],
        f[2],
    ];
    let point = spread(&p, &grid, DS, &reactions, &[], &[]);
    // D ≤ Δs: a = 0, S2-24 to the last bit
    for widths in [[DS, 0.5 * DS], [0.0, DS]] {
        assert_eq!(spread(&p, &grid, DS, &reactions, &[], &widths), point);
    }
    // D just over Δs: the weights move by little (continuous in D)
    let near = spread(&p, &grid, DS, &reactions, &[], &[1.0001 * DS, 1.0001 * DS]);
    let largest = point.force.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let moved = near
        .force
        .iter()
        .zip(&point.force)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    println!("D = 1.0001 Δs: largest change {moved:.3e} of {largest:.3e}");
    assert!(moved > 0.0 && moved < 1e-3 * largest, "{moved} of {largest}");
}

#[test]
fn a_wide_members_reaction_with_no_water_in_its_reach_goes_to_its_sample_point_or_is_reported() {
    let (p, grid) = pool(|_| [0.0; 3]);
    let f = [1.0, 2.0, 3.0];
    let width = 5.0 * DS;
    // 5.5 Δs over the surface: beyond a + R = 4.4 Δs of the top layer at −0.5 Δs
    let dry = [0.0, 0.0, 5.5 * DS];
    let wet = [0.0, 0.0, -2.0 * DS];
    let reaction = [dry[0], dry[1], dry[2], f[0], f[1], f[2]];
    let s = spread(&p, &grid, DS, &reaction, &wet, &[width]);
    let (sum, _) = spread_total(&p, &s.force);
    assert_eq!((s.moved, s.unapplied), (1, 0));
    assert!(
        sum.iter().zip(&f).all(|(a, b)| (a - b).abs() <= 1e-14 * 3.0),
        "{sum:?}"
    );
    // the point's own footprint is the same at the sample point: equal to a reaction there
    let there = spread(
        &p,
        &grid,
        DS,
        &[wet[0], wet[1], wet[2], f[0], f[1], f[2]],
        &[],
        &[width],
    );
    assert_eq!(s.force, there.force);
    let s = spread(&p, &grid, DS, &reaction, &dry, &[width]);
    assert_eq!((s.unapplied, s.unapplied_force), (1, f));
    assert!(s.force.iter().all(|&v| v == 0.0));
    // a point reaction at 2.5 Δs over the water is dry; the wide member's reach finds water there
    let low = [0.0, 0.0, 2.5 * DS, f[0], f[1], f[2]];
    assert_eq!(spread(&p, &grid, DS, &low, &dry, &[]).unapplied, 1);
    assert_eq!(spread(&p, &grid, DS, &low, &dry, &[width]).unapplied, 0);
}
