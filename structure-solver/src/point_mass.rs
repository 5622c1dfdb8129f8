//! [`PointMass`]: a translating mass, the unit the coupler's spring oscillators are built from.

use nalgebra::Vector3;
use schemas::case::structure::PointMassConfig;

/// A point with mass, its reference position, displacement from it and velocity.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct PointMass {
    pub name: String,
    /// Mass [kg].
    pub mass: f64,
    /// Reference position [m].
    pub position: Vector3<f64>,
    /// Displacement from the reference position [m].
    pub displacement: Vector3<f64>,
    /// Velocity [m/s].
    pub velocity: Vector3<f64>,
}

impl PointMass {
    /// From a validated `[[structure.NAME.point_mass]]`.
    pub fn from_config(c: &PointMassConfig) -> Self {
        Self {
            name: c.name.clone(),
            mass: c.mass,
            position: Vector3::from(c.position),
            displacement: Vector3::from(c.displacement),
            velocity: Vector3::from(c.velocity),
        }
    }
}
