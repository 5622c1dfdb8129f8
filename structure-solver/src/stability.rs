//! The substep limit of the spring–mass system: `max_step · ω_max` must stay inside the stability
//! interval of the integrator — `2√2` on the imaginary axis for classical RK4 (point masses) and
//! `2` for the kick–drift–kick of bodies. `ω_max` is bounded from above by Gershgorin's theorem
//! on `M^{-1/2} K M^{-1/2}`: row i gives `Σ k/m_i + Σ_{j≠ground} k/√(m_i m_j)`.

use crate::anchor::Anchor;
use crate::spring::Spring;
use schemas::case::FieldError;

/// RK4's stability limit of `ω Δt` for an undamped oscillator is 2√2 = 2.83; a little margin.
const RK4_LIMIT: f64 = 2.8;
/// Störmer–Verlet (kick–drift–kick) is stable for `ω Δt < 2`; a little margin.
const VERLET_LIMIT: f64 = 1.95;

/// Fails with an error at `key` (the `max_step` key) naming the stiffest point or body when
/// `max_step` is beyond the limit. `point_mass` and `body_mass` give the masses by index,
/// `names(anchor)` the name to report.
pub fn check_max_step(
    key: &str,
    max_step: f64,
    springs: &[Spring],
    point_mass: &[f64],
    body_mass: &[f64],
    name: impl Fn(Anchor) -> String,
) -> Result<(), FieldError> {
    let mass = |a: Anchor| match a {
        Anchor::Ground => f64::INFINITY,
        Anchor::Point(i) => point_mass[i],
        Anchor::Body(i) => body_mass[i],
    };
    let anchors = (0..point_mass.len())
        .map(Anchor::Point)
        .chain((0..body_mass.len()).map(Anchor::Body));
    for row in anchors {
        let mut omega2 = 0.0;
        let mut touches_body = matches!(row, Anchor::Body(_));
        for s in springs {
            let other = if s.a == row {
                s.b
            } else if s.b == row {
                s.a
            } else {
                continue;
            };
            touches_body |= matches!(other, Anchor::Body(_));
            omega2 += s.stiffness / mass(row);
            if other != Anchor::Ground {
                omega2 += s.stiffness / (mass(row) * mass(other)).sqrt();
            }
        }
        let limit = if touches_body { VERLET_LIMIT } else { RK4_LIMIT };
        let omega = omega2.sqrt();
        if max_step * omega > limit {
            return Err(FieldError::new(
                key,
                format!(
                    "{max_step} s is too long for the springs at `{}` (ω up to {omega:.4} rad/s): \
                     the integrator is stable for ω·max_step < {limit}; use max_step ≤ {:.3e}",
                    name(row),
                    limit / omega
                ),
            ));
        }
    }
    Ok(())
}
