//! Mass properties of a rigid body from its `inertia = { … }` table: a homogeneous box, a given
//! tensor, a set of equal-mass particles (the paper's bodies are particle sets, S1 §2.2), or the
//! homogeneous solid a closed mesh bounds (its mass, centre and world tensor are computed when
//! the case is loaded, `TriangleMesh::mass_properties`).

use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use schemas::case::structure::{check_inertia_tensor, BodyConfig};
use schemas::case::FieldError;

/// Mass, centre of mass (world, t = 0) and inertia tensor about the centre in the body frame.
#[derive(Debug, Clone, PartialEq)]
pub struct MassProperties {
    pub mass: f64,
    pub centre: Vector3<f64>,
    pub inertia: Matrix3<f64>,
}

impl MassProperties {
    /// From a validated body section; `key` is its dotted path. Particle positions and meshes are
    /// world positions at t = 0; their tensor `I_w` is turned into the body frame with the body's
    /// initial orientation R: `I_b = Rᵀ I_w R`.
    pub fn from_config(c: &BodyConfig, key: &str) -> Result<Self, FieldError> {
        let q = c.orientation;
        let rotation = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]))
            .to_rotation_matrix();
        let i = &c.inertia;
        let missing = |name: &str| FieldError::new(format!("{key}.{name}"), "is required");
        if let (Some(particles), Some(particle_mass)) = (&i.particles, i.particle_mass) {
            let points: Vec<Vector3<f64>> = particles.iter().map(|p| Vector3::from(*p)).collect();
            let mass = particle_mass * points.len() as f64;
            let centre = points.iter().sum::<Vector3<f64>>() / points.len() as f64;
            let world = points.iter().fold(Matrix3::zeros(), |acc, p| {
                let r = p - centre;
                acc + particle_mass * (Matrix3::identity() * r.norm_squared() - r * r.transpose())
            });
            let inertia = rotation.matrix().transpose() * world * rotation.matrix();
            check_inertia_tensor(&format!("{key}.inertia.particles"), &rows(&inertia)).map_err(|e| {
                FieldError::new(
                    e.key,
                    format!(
                        "give an inertia tensor from particles not all on one line: {}",
                        e.message
                    ),
                )
            })?;
            return Ok(Self {
                mass,
                centre,
                inertia,
            });
        }
        if i.mesh.is_some() {
            let m = i.mesh_properties.ok_or_else(|| {
                FieldError::new(
                    format!("{key}.inertia.mesh"),
                    "was not read: load the case with `Case::load`, which reads the mesh",
                )
            })?;
            let world = Matrix3::from_fn(|r, col| m.inertia[r][col]);
            return Ok(Self {
                mass: m.mass,
                centre: Vector3::from(m.centre),
                inertia: rotation.matrix().transpose() * world * rotation.matrix(),
            });
        }
        let mass = c.mass.ok_or_else(|| missing("mass"))?;
        let centre = Vector3::from(c.centre.ok_or_else(|| missing("centre"))?);
        let inertia = if let Some([lx, ly, lz]) = i.box_size {
            let k = mass / 12.0;
            Matrix3::from_diagonal(&Vector3::new(
                k * (ly * ly + lz * lz),
                k * (lx * lx + lz * lz),
                k * (lx * lx + ly * ly),
            ))
        } else if let Some(t) = &i.tensor {
            check_inertia_tensor(&format!("{key}.inertia.tensor"), t)?;
            Matrix3::from_fn(|r, col| t[r][col])
        } else {
            return Err(FieldError::new(
                format!("{key}.inertia"),
                "needs `box`, `tensor`, `particles` or `mesh`",
            ));
        };
        Ok(Self {
            mass,
            centre,
            inertia,
        })
    }
}

fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    [
        [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
        [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
        [m[(2, 0)], m[(2, 1)], m[(2, 2)]],
    ]
}
