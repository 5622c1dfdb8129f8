//! [`RigidBody`]: a 6-DOF body, `M dV/dt = F` (S1-17) and `I dω/dt + ω × Iω = N` (S1-18).
//!
//! Time integration is a kick–drift–kick splitting instead of the paper's explicit Euler (which
//! gains energy on a torque-free top, see docs/physics.md §5):
//! - kick: `V += F Δt/2M`, spatial angular momentum `L += N Δt/2`;
//! - drift: `x += V Δt`; the torque-free rotation by the implicit midpoint rule on the body-frame
//!   momentum `L_b` (it keeps the quadratic invariants `½ L_b·I⁻¹L_b` and `|L_b|²` exactly), and the
//!   orientation by the exponential map of the rotation that rule implies: angle `2 atan(|ω|Δt/2)`
//!   about `ω_mid = I⁻¹(L_b + L_b')/2` (the Cayley transform of `ω_mid Δt`), which keeps the
//!   spatial `L` to round-off too.
//!
//! With a constant force the kicks and drift reproduce the parabola exactly.

use crate::inertia::MassProperties;
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

/// Relative change of `L_b` at which the implicit midpoint iteration has converged.
const MIDPOINT_TOLERANCE: f64 = 4.0 * f64::EPSILON;
/// Fixed-point iterations allowed for one rotation step (it contracts by about |ω|Δt per pass).
const MIDPOINT_ITERATIONS: usize = 200;

/// State and mass properties of one rigid body.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct RigidBody {
    pub name: String,
    mass: f64,
    /// Inertia about the centre, body frame, and its inverse.
    inertia: Matrix3<f64>,
    inertia_inv: Matrix3<f64>,
    /// Centre at t = 0 (displacements of the centre are measured from it).
    initial_centre: Vector3<f64>,
    centre: Vector3<f64>,
    velocity: Vector3<f64>,
    /// Body → world.
    orientation: UnitQuaternion<f64>,
    /// Angular momentum about the centre, world frame.
    angular_momentum: Vector3<f64>,
}

impl RigidBody {
    /// A body with mass properties `m`, orientation `q` (body → world), velocity and world
    /// angular velocity. `None` when the inertia tensor cannot be inverted.
    pub fn new(
        name: &str,
        m: &MassProperties,
        q: UnitQuaternion<f64>,
        velocity: Vector3<f64>,
        angular_velocity: Vector3<f64>,
    ) -> Option<Self> {
        let inertia_inv = m.inertia.try_inverse()?;
        let r = q.to_rotation_matrix();
        let angular_momentum = r * (m.inertia * (r.inverse() * angular_velocity));
        Some(Self {
            name: name.to_string(),
            mass: m.mass,
            inertia: m.inertia,
            inertia_inv,
            initial_centre: m.centre,
            centre: m.centre,
            velocity,
            orientation: q,
            angular_momentum,
        })
    }

    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// Inertia tensor about the centre in the body frame [kg m²].
    pub fn inertia(&self) -> &Matrix3<f64> {
        &self.inertia
    }

    pub fn centre(&self) -> Vector3<f64> {
        self.centre
    }

    /// Displacement of the centre from its position at t = 0.
    pub fn displacement(&self) -> Vector3<f64> {
        self.centre - self.initial_centre
    }

    pub fn velocity(&self) -> Vector3<f64> {
        self.velocity
    }

    pub fn orientation(&self) -> UnitQuaternion<f64> {
        self.orientation
    }

    /// Angular momentum about the centre, world frame.
    pub fn angular_momentum(&self) -> Vector3<f64> {
        self.angular_momentum
    }

    /// Angular velocity, world frame: `ω = R I⁻¹ Rᵀ L`.
    pub fn angular_velocity(&self) -> Vector3<f64> {
        self.orientation * (self.inertia_inv * (self.orientation.inverse() * self.angular_momentum))
    }

    /// Angular velocity in the body frame: `I⁻¹ Rᵀ L`.
    pub fn body_angular_velocity(&self) -> Vector3<f64> {
        self.inertia_inv * (self.orientation.inverse() * self.angular_momentum)
    }

    /// Translational plus rotational kinetic energy [J].
    pub fn kinetic_energy(&self) -> f64 {
        let l_body = self.orientation.inverse() * self.angular_momentum;
        0.5 * self.mass * self.velocity.norm_squared() + 0.5 * l_body.dot(&(self.inertia_inv * l_body))
    }

    /// Holds the body still (a support carries every load).
    pub fn stop(&mut self) {
        self.velocity = Vector3::zeros();
        self.angular_momentum = Vector3::zeros();
    }

    /// Kick: force and torque (world, about the centre) act for `dt` (S1-17, S1-18 right-hand sides).
    pub fn kick(&mut self, dt: f64, force: &Vector3<f64>, torque: &Vector3<f64>) {
        self.velocity += force * (dt / self.mass);
        self.angular_momentum += torque * dt;
    }

    /// Drift: free motion for `dt` (translation, then the torque-free rotation of the module doc).
    /// Fails when the implicit midpoint iteration does not converge (|ω| Δt too large).
    pub fn drift(&mut self, dt: f64) -> Result<(), String> {
        self.centre += self.velocity * dt;
        let l0 = self.orientation.inverse() * self.angular_momentum;
        let scale = l0.norm();
        if scale == 0.0 {
            return Ok(());
        }
        let mut l1 = l0;
        let mut change = f64::INFINITY;
        for _ in 0..MIDPOINT_ITERATIONS {
            let mid = 0.5 * (l0 + l1);
            let next = l0 + dt * mid.cross(&(self.inertia_inv * mid));
            change = (next - l1).norm();
            l1 = next;
            if change <= MIDPOINT_TOLERANCE * scale {
                break;
            }
        }
        let converged = change <= 1e3 * MIDPOINT_TOLERANCE * scale;
        if !converged {
            let omega = (self.inertia_inv * l0).norm();
            return Err(format!(
                "body `{}`: the rotation step did not converge (|ω| Δt = {:.3}); lower max_step",
                self.name,
                omega * dt
            ));
        }
        let omega_mid = self.inertia_inv * (0.5 * (l0 + l1));
        let rate = omega_mid.norm();
        if rate > 0.0 {
            let angle = 2.0 * (0.5 * rate * dt).atan();
            let half = 0.5 * angle;
            let axis = omega_mid / rate * half.sin();
            let step = UnitQuaternion::new_normalize(Quaternion::new(half.cos(), axis.x, axis.y, axis.z));
            self.orientation = UnitQuaternion::new_normalize(*(self.orientation * step).quaternion());
        }
        Ok(())
    }

    /// Whether position, velocity, orientation and momentum are all finite.
    pub fn is_finite(&self) -> bool {
        self.centre
            .iter()
            .chain(self.velocity.iter())
            .chain(self.angular_momentum.iter())
            .all(|v| v.is_finite())
            && self.orientation.coords.iter().all(|v| v.is_finite())
    }
}
