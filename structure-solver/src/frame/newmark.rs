//! Newmark-β time integration with β = 4/9, δ = 5/6 (S2-14; the standard velocity update replaces
//! the misprinted S2-16): unconditionally stable, spectral radius 0.5 at infinite frequency.

/// Newmark β.
pub const BETA: f64 = 4.0 / 9.0;
/// Newmark δ (often written γ).
pub const DELTA: f64 = 5.0 / 6.0;

/// Factor of the mass matrix in the effective stiffness `K + M / (β Δt²)`.
pub fn mass_factor(dt: f64) -> f64 {
    1.0 / (BETA * dt * dt)
}

/// What the old motion contributes to the right-hand side, per unit mass:
/// `v / (β Δt) + (1/(2β) − 1) a`.
pub fn inertia_term(v: f64, a: f64, dt: f64) -> f64 {
    v / (BETA * dt) + (0.5 / BETA - 1.0) * a
}

/// New velocity and acceleration from the step's displacement increment `du`:
/// `a' = (du − Δt v − Δt² (1/2 − β) a) / (β Δt²)`, `v' = v + Δt ((1 − δ) a + δ a')`.
pub fn advance(du: f64, v: f64, a: f64, dt: f64) -> (f64, f64) {
    let a_new = (du - dt * v - dt * dt * (0.5 - BETA) * a) / (BETA * dt * dt);
    let v_new = v + dt * ((1.0 - DELTA) * a + DELTA * a_new);
    (v_new, a_new)
}
