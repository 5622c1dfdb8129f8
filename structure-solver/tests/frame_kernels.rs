//! The frame's building blocks checked against exact identities: the rotation-vector log map, the
//! moment transfer of ASI-Gauss elements, the closest-point return and the Newmark update.

use crate::frame_common;

use frame_common::{rectangle, steel};
use nalgebra::{Rotation3, Vector3};
use structure_solver::frame::element::{
    add_axial_geometric_stiffness, global_stiffness, local_forces, moments_at, move_integration_point,
    rotation_vector, strain_matrix, strains, S_GAUSS,
};
use structure_solver::frame::newmark;
use structure_solver::frame::section::Section;

/// The log map inverts the exponential map to round-off from 1e-12 rad up to nearly π.
#[test]
fn rotation_vector_inverts_the_exponential_map() {
    let axis = Vector3::new(0.3, -0.5, 0.81).normalize();
    for angle in [1e-12, 1e-6, 1e-3, 0.5, 2.0, 3.1] {
        let v = axis * angle;
        let back = rotation_vector(Rotation3::new(v).matrix());
        let err = (back - v).norm() / angle;
        assert!(err < 1e-9, "angle {angle}: relative error {err:e}");
    }
}

/// Resultants σ are read at r = −s; the end forces l Bᵀ σ carry the moments linearly to the ends,
/// and moving the integration point keeps the end forces.
#[test]
fn moments_are_carried_to_the_ends_and_survive_a_moved_integration_point() {
    let (l, s) = (0.4, S_GAUSS);
    let sigma = [1.5e3, -2.0e3, 3.0e3, 40.0, 7.0e2, -9.0e2];
    let (my, mz) = moments_at(l, s, &sigma, -s);
    assert_eq!((my, mz), (sigma[4], sigma[5]));
    let f = local_forces(l, s, &sigma);
    let (my1, mz1) = moments_at(l, s, &sigma, 1.0);
    let (my0, mz0) = moments_at(l, s, &sigma, -1.0);
    for (got, want) in [(f[10], my1), (f[11], mz1), (-f[4], my0), (-f[5], mz0)] {
        assert!((got - want).abs() < 1e-9 * want.abs().max(1.0), "{got} vs {want}");
    }
    // equilibrium of the free element: forces and moments about node 1 sum to zero
    for k in 0..3 {
        assert!((f[k] + f[6 + k]).abs() < 1e-9);
    }
    assert!((f[5] + f[11] + l * f[7]).abs() < 1e-9, "moment about z");
    assert!((f[4] + f[10] - l * f[8]).abs() < 1e-9, "moment about y");
    for s_new in [1.0, -1.0, 0.0] {
        let mut moved = sigma;
        move_integration_point(l, s, s_new, &mut moved);
        let g = local_forces(l, s_new, &moved);
        for (a, b) in f.iter().zip(&g) {
            assert!((a - b).abs() < 1e-9 * a.abs().max(1.0), "s = {s_new}: {a} vs {b}");
        }
    }
}

/// The element stiffness in global axes equals `T (l Bᵀ D B) Tᵀ` written with the strain matrix (to
/// round-off, 1e-12 of its largest entry), for a hinge-like D with coupled N, My, Mz; it is symmetric
/// and leaves rigid translations unstressed. The geometric stiffness of an axial force N resists a
/// relative transverse translation δ of the ends with N δ / l and leaves an axial one free.
#[test]
fn element_stiffness_is_t_k_tt_symmetric_with_rigid_translations_free() {
    let section = Section::new(&rectangle("r", 0.1, 0.2), &steel());
    let mut d = [[0.0; 6]; 6];
    for (i, row) in d.iter_mut().enumerate() {
        row[i] = section.stiffness[i];
    }
    // D − D a aᵀ D / (aᵀ D a) with a = (1, 0, 0, 0, 0.5, −0.3) on N, My, Mz
    let a = [1e-6, 0.0, 0.0, 0.0, 0.5e-5, -0.3e-5];
    let ada: f64 = (0..6).map(|i| a[i] * d[i][i] * a[i]).sum();
    let da: Vec<f64> = (0..6).map(|i| d[i][i] * a[i]).collect();
    for i in 0..6 {
        for j in 0..6 {
            d[i][j] -= da[i] * da[j] / ada;
        }
    }
    let frame = *Rotation3::from_scaled_axis(Vector3::new(0.3, -0.7, 1.1)).matrix();
    let (length, s) = (0.3, -S_GAUSS);
    let k = global_stiffness(&frame, length, s, &d);

    let b = nalgebra::SMatrix::<f64, 6, 12>::from_fn(|i, j| strain_matrix(length, s)[i][j]);
    let dm = nalgebra::Matrix6::from_fn(|i, j| d[i][j]);
    let mut t = nalgebra::SMatrix::<f64, 12, 12>::zeros();
    for block in 0..4 {
        t.fixed_view_mut::<3, 3>(3 * block, 3 * block).copy_from(&frame);
    }
    let expected = t * (b.transpose() * dm * b * length) * t.transpose();
    let scale = k.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
    for (i, row) in k.iter().enumerate() {
        for (j, kij) in row.iter().enumerate() {
            assert!((kij - expected[(i, j)]).abs() < 1e-12 * scale, "entry ({i}, {j})");
            assert!((kij - k[j][i]).abs() < 1e-12 * scale);
        }
        for dir in 0..3 {
            let rigid: f64 = row[dir] + row[6 + dir];
            assert!(rigid.abs() < 1e-12 * scale, "row {i}, translation {dir}");
        }
    }

    let (axial_force, current_length) = (2e5, 0.31);
    let mut g = [[0.0; 12]; 12];
    add_axial_geometric_stiffness(&mut g, &frame, axial_force, current_length);
    let force_of = |delta: Vector3<f64>| {
        // the second end moved by δ: the force on it
        Vector3::from_fn(|i, _| (0..3).map(|j| g[6 + i][6 + j] * delta[j]).sum::<f64>())
    };
    let transverse = force_of(frame.column(1).into_owned() * 1e-3);
    let expected = frame.column(1) * (axial_force * 1e-3 / current_length);
    assert!((transverse - expected).norm() < 1e-12 * expected.norm());
    assert!(force_of(frame.column(0).into_owned()).norm() < 1e-9 * axial_force);
}

/// The closest-point return lands on the yield surface with a plastic flow normal to it
/// (σ_trial − σ = Δλ D ∂f/∂σ, one Δλ for N, My and Mz).
#[test]
fn return_to_surface_is_a_normal_projection_onto_the_yield_surface() {
    let section = Section::new(&rectangle("r", 0.1, 0.2), &steel());
    let [n0, my0, mz0] = section.plastic;
    let trial = [0.6 * n0, 10.0, -20.0, 5.0, 0.9 * my0, -0.7 * mz0];
    let mut sigma = trial;
    section.return_to_surface(&mut sigma);
    let f = section.yield_function(sigma[0], sigma[4], sigma[5]);
    assert!(f.abs() < 1e-10, "f = {f}");
    let a = section.yield_gradient(&sigma);
    let lambdas: Vec<f64> = [0, 4, 5]
        .iter()
        .map(|&i| (trial[i] - sigma[i]) / (section.stiffness[i] * a[i]))
        .collect();
    assert!(lambdas[0] > 0.0);
    for l in &lambdas {
        assert!((l / lambdas[0] - 1.0).abs() < 1e-9, "Δλ {lambdas:?}");
    }
    // shear and torsion do not take part
    assert_eq!([sigma[1], sigma[2], sigma[3]], [trial[1], trial[2], trial[3]]);
}

/// Under a constant acceleration the Newmark update is exact for any (β, δ).
#[test]
fn newmark_update_is_exact_for_constant_acceleration() {
    let (v, a, dt) = (1.5, -9.81, 0.01);
    let du = v * dt + 0.5 * a * dt * dt;
    let (v_new, a_new) = newmark::advance(du, v, a, dt);
    assert!((a_new - a).abs() < 1e-9 && (v_new - (v + a * dt)).abs() < 1e-12);
}

/// The written-out strains `B(s) d` and end forces `l Bᵀ σ` equal the products with the strain
/// matrix, to round-off (1e-12 relative), for several integration points.
#[test]
fn written_out_strains_and_forces_match_the_strain_matrix() {
    let l = 0.75;
    let d: [f64; 12] = std::array::from_fn(|i| 1e-3 * ((i * 7 % 12) as f64 - 5.5));
    let sigma = [3e5, -2e4, 1.5e4, 800.0, -4e3, 2.5e3];
    for s in [-1.0, -S_GAUSS, 0.0, S_GAUSS, 1.0] {
        let b = strain_matrix(l, s);
        let e = strains(l, s, &d);
        let f = local_forces(l, s, &sigma);
        for (i, row) in b.iter().enumerate() {
            let product: f64 = row.iter().zip(&d).map(|(x, y)| x * y).sum();
            assert!(
                (e[i] - product).abs() <= 1e-12 * product.abs().max(1e-3),
                "strain {i} at s = {s}"
            );
        }
        for (j, fj) in f.iter().enumerate() {
            let product: f64 = l * (0..6).map(|m| b[m][j] * sigma[m]).sum::<f64>();
            assert!(
                (fj - product).abs() <= 1e-12 * product.abs().max(1.0),
                "force {j} at s = {s}"
            );
        }
    }
}
