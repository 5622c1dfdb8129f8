//! Weight functions and operators on a lattice: the gradient (S1-3) of a linear field and the
//! Laplacian (S1-4) of a quadratic field are exact on a perfect lattice (n0_grad and λ0 are
//! computed on that lattice, so the truncation terms cancel by symmetry); on a jittered lattice
//! the MPS operators are only zero-order consistent and the error grows with the jitter.

use fluid_solver::emps::kernel::{weight, weight_grad, Kernel};
use fluid_solver::emps::operators;
use fluid_solver::neighbour_search::CellGrid;
use fluid_solver::particles::Particles;
use fluid_solver::vector_field::VectorField;
use fluid_solver::Kind;
use schemas::validation::{record, Record};
use std::time::Instant;

const DS: f64 = 0.01;
const N: i32 = 14;

/// A cube of N³ fluid particles on the lattice, each displaced by up to `jitter` Δs per axis.
fn lattice(jitter: f64) -> Particles {
    let mut p = Particles::default();
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for k in 0..N {
        for j in 0..N {
            for i in 0..N {
                let q = [i, j, k].map(|c| (f64::from(c) + 0.5) * DS);
                p.push(
                    [
                        q[0] + 2.0 * jitter * DS * rnd(),
                        q[1] + 2.0 * jitter * DS * rnd(),
                        q[2] + 2.0 * jitter * DS * rnd(),
                    ],
                    Kind::Fluid,
                );
            }
        }
    }
    p
}

fn sorted_grid(p: &mut Particles) -> CellGrid {
    let hi = f64::from(N) * DS;
    let mut grid = CellGrid::new([0.0; 3], [hi; 3], DS);
    grid.sort(p, &mut Vec::new());
    grid
}

/// True when particle i's whole r_e = 3.1 Δs support lies inside the cube (lattice coordinates).
fn interior(p: &Particles, i: usize) -> bool {
    let margin = 4.0 * DS;
    let hi = f64::from(N) * DS - margin;
    p.position(i).iter().all(|&c| c > margin && c < hi)
}

#[test]
fn weights_follow_s1_5_and_s1_6() {
    let re = 3.1 * DS;
    for r in [0.3 * DS, DS, 2.0 * DS, 3.0 * DS] {
        let printed = re / r + r / re - 2.0; // docs/physics.md's reading of S1-6
        assert!((weight(r, re) - printed).abs() < 1e-12 * printed.max(1.0));
        assert!(weight(r, re) >= 0.0);
        let g = 2.1 * DS;
        let expect = if r < g { g / r - r / g } else { 0.0 };
        assert!((weight_grad(r, g) - expect).abs() < 1e-12);
    }
    assert_eq!(weight(re, re), 0.0);
    assert_eq!(weight(0.0, re), 0.0, "no self-weight");
    // n0 is the lattice sum; for Δs = 1 it does not depend on the spacing (w is scale-free).
    let k1 = Kernel::new(1.0);
    let k = Kernel::new(DS);
    assert!((k1.n0 - k.n0).abs() < 1e-9 && (k1.n0_grad - k.n0_grad).abs() < 1e-9);
    assert!((k.lambda0 / (DS * DS) - k1.lambda0).abs() < 1e-9);
    println!(
        "n0 = {:.6}, n0_grad = {:.6}, λ0 = {:.6} Δs²",
        k.n0, k.n0_grad, k1.lambda0
    );
}

#[test]
fn cell_list_number_density_matches_brute_force() {
    let mut p = lattice(0.3);
    let kernel = Kernel::new(DS);
    let grid = sorted_grid(&mut p);
    operators::number_density(&grid, &kernel, &mut p);
    for i in (0..p.len()).step_by(37) {
        let mut n = 0.0;
        for j in 0..p.len() {
            let d: f64 = (0..3)
                .map(|a| (p.position(j)[a] - p.position(i)[a]).powi(2))
                .sum::<f64>()
                .sqrt();
            n += weight(d, kernel.re);
        }
        assert!(
            (n - p.number_density[i]).abs() < 1e-9 * n,
            "particle {i}: cells {} brute {n}",
            p.number_density[i]
        );
    }
    // The interior of a perfect lattice has n = n0 (S1-8).
    let mut q = lattice(0.0);
    let grid = sorted_grid(&mut q);
    operators::number_density(&grid, &kernel, &mut q);
    for i in (0..q.len()).filter(|&i| interior(&q, i)) {
        assert!((q.number_density[i] / kernel.n0 - 1.0).abs() < 1e-12);
    }
}

/// Largest relative error of ⟨∇f⟩ for f = a·r + b over interior particles.
fn gradient_error(jitter: f64) -> f64 {
    let mut p = lattice(jitter);
    let kernel = Kernel::new(DS);
    let grid = sorted_grid(&mut p);
    let a = [3.0, -2.0, 5.0];
    // Zero at the cube's centre, so |f_i| ≤ |a| · 3 Δs on the interior particles.
    let c = 0.5 * f64::from(N) * DS;
    let f: Vec<f64> = (0..p.len())
        .map(|i| a[0] * (p.x[i] - c) + a[1] * (p.y[i] - c) + a[2] * (p.z[i] - c))
        .collect();
    let mut out = VectorField::default();
    operators::gradient(&grid, &kernel, &p, &f, &mut out);
    let norm = (a.iter().map(|v| v * v).sum::<f64>()).sqrt();
    (0..p.len())
        .filter(|&i| interior(&p, i))
        .map(|i| {
            ((out.x[i] - a[0]).powi(2) + (out.y[i] - a[1]).powi(2) + (out.z[i] - a[2]).powi(2)).sqrt() / norm
        })
        .fold(0.0, schemas::validation::max_or_nan)
}

/// Largest relative error of ⟨∇²u⟩ for u = (x², y², z² + xy) (exact ∇²u = (2, 2, 2)).
fn laplacian_error(jitter: f64) -> f64 {
    let mut p = lattice(jitter);
    let kernel = Kernel::new(DS);
    let grid = sorted_grid(&mut p);
    for i in 0..p.len() {
        p.vx[i] = p.x[i] * p.x[i];
        p.vy[i] = p.y[i] * p.y[i];
        p.vz[i] = p.z[i] * p.z[i] + p.x[i] * p.y[i];
    }
    let mut out = VectorField::default();
    operators::laplacian(&grid, &kernel, &p, &mut out);
    (0..p.len())
        .filter(|&i| interior(&p, i))
        .map(|i| {
            ((out.x[i] - 2.0).powi(2) + (out.y[i] - 2.0).powi(2) + (out.z[i] - 2.0).powi(2)).sqrt()
                / 12f64.sqrt()
        })
        .fold(0.0, schemas::validation::max_or_nan)
}

/// Records the largest relative error of an operator on the cube, lattice jittered by `jitter`.
fn record_operator(operator: &str, jitter: f64, value: f64, bound: f64, bound_source: &str, run_time_s: f64) {
    let (name, capability, field, test) = match operator {
        "gradient" => (
            "gradient",
            "E-MPS gradient operator (S1-3)",
            "linear field f = a·r + b",
            "gradient_of_linear_field_is_exact_on_a_lattice",
        ),
        _ => (
            "Laplacian",
            "E-MPS Laplacian operator (S1-4)",
            "quadratic field u = (x², y², z² + xy)",
            "laplacian_of_quadratic_field_is_exact_on_a_lattice",
        ),
    };
    let tag = match jitter {
        0.0 => "lattice".to_string(),
        j => format!("jitter-{}", (100.0 * j).round()),
    };
    record(Record {
        id: format!("emps-operator-{operator}-{tag}"),
        capability: capability.into(),
        reference: format!("the exact {name} of a {field}"),
        case: format!(
            "a cube of {N}³ fluid particles, Δs = {DS} m, {}",
            match jitter {
                0.0 => "on the lattice".to_string(),
                j => format!("each displaced by up to {} % of Δs per axis", 100.0 * j),
            }
        ),
        resolution: "E-MPS weights, r_e = 2.1 Δs (gradient), 3.1 Δs (Laplacian)".into(),
        measure: "largest relative error over interior particles".into(),
        value,
        bound: Some(bound),
        bound_source: bound_source.into(),
        source: format!("fluid-solver/tests/operators.rs::{test}"),
        run_time_s,
        ..Default::default()
    });
}

#[test]
fn gradient_of_linear_field_is_exact_on_a_lattice() {
    let started = Instant::now();
    let e0 = gradient_error(0.0);
    println!("gradient of a linear field: lattice {e0:.2e}");
    // Round-off bound: sums of ~40 terms of size |f|/Δs ≈ 700/0.01 in f64.
    let round_off = "round-off: sums of ~40 terms of size |f|/Δs ≈ 700/0.01 in f64";
    record_operator(
        "gradient",
        0.0,
        e0,
        1e-9,
        round_off,
        started.elapsed().as_secs_f64(),
    );
    assert!(e0 < 1e-9, "lattice gradient error {e0}");
    let started = Instant::now();
    let e1 = gradient_error(0.01);
    let e5 = gradient_error(0.05);
    println!("gradient of a linear field: jitter 1 % {e1:.3e}, 5 % {e5:.3e}");
    // Zero-order consistency: the (P_i + P_j) form leaves 2 f_i d/n0_grad Σ r_ij/r² w_grad, which
    // vanishes only on a symmetric lattice; it grows with the jitter and with |f_i|/(|∇f| Δs)
    // (≤ 3 here). The bounds are the measured errors (0.15, 0.77) with a factor 2 margin.
    let jittered = "the measured error (0.15, 0.77) with a factor 2 margin: the operator is only \
                    zero-order consistent off the lattice";
    let run_time_s = started.elapsed().as_secs_f64() / 2.0;
    record_operator("gradient", 0.01, e1, 0.3, jittered, run_time_s);
    record_operator("gradient", 0.05, e5, 1.6, jittered, run_time_s);
    assert!(e1 < e5, "the error should grow with the jitter");
    assert!(e1 < 0.3 && e5 < 1.6, "jittered gradient errors {e1}, {e5}");
}

#[test]
fn laplacian_of_quadratic_field_is_exact_on_a_lattice() {
    let started = Instant::now();
    let e0 = laplacian_error(0.0);
    println!("laplacian of a quadratic field: lattice {e0:.2e}");
    let round_off = "round-off (the gradient test's bound)";
    record_operator(
        "laplacian",
        0.0,
        e0,
        1e-9,
        round_off,
        started.elapsed().as_secs_f64(),
    );
    assert!(e0 < 1e-9, "lattice Laplacian error {e0}");
    let started = Instant::now();
    let e1 = laplacian_error(0.01);
    let e5 = laplacian_error(0.05);
    println!("laplacian of a quadratic field: jitter 1 % {e1:.3e}, 5 % {e5:.3e}");
    // Measured 0.073 and 0.38: bounds with a margin of about 1.4.
    let jittered = "the measured error (0.073, 0.38) with a margin of about 1.4";
    let run_time_s = started.elapsed().as_secs_f64() / 2.0;
    record_operator("laplacian", 0.01, e1, 0.1, jittered, run_time_s);
    record_operator("laplacian", 0.05, e5, 0.5, jittered, run_time_s);
    assert!(e1 < e5, "the error should grow with the jitter");
    assert!(e1 < 0.1 && e5 < 0.5, "jittered Laplacian errors {e1}, {e5}");
}
