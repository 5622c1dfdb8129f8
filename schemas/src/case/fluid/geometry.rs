//! Boxes of a fluid section: `tank` ([`TankConfig`]), `[[fluid.NAME.block]]`,
//! `[[fluid.NAME.gate]]`, `[[fluid.NAME.wall]]` (an [`Aabb`] each) and `[[fluid.NAME.body]]`
//! ([`BodyConfig`]).

use crate::case::error::check;
use crate::case::FieldError;
use schemars::JsonSchema;
use serde::Deserialize;

/// An axis-aligned box `[min, max]` [m].
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Aabb {
    /// Lower corner `[x, y, z]` [m].
    pub min: [f64; 3],
    /// Upper corner `[x, y, z]` [m]; above `min` on every axis, inside the tank.
    pub max: [f64; 3],
}

impl Aabb {
    /// Checks that the box is finite and has positive extent along every axis.
    pub fn validate(&self, key: &str) -> Result<(), FieldError> {
        check::finite(&format!("{key}.min"), &self.min)?;
        check::finite(&format!("{key}.max"), &self.max)?;
        for a in 0..3 {
            if self.max[a] <= self.min[a] {
                return Err(FieldError::new(
                    format!("{key}.max"),
                    format!(
                        "must be greater than `min` along every axis; axis {} has min {} and max {}",
                        ["x", "y", "z"][a],
                        self.min[a],
                        self.max[a]
                    ),
                ));
            }
        }
        Ok(())
    }

    /// True when `other` lies inside `self` (faces may touch).
    pub fn contains(&self, other: &Aabb) -> bool {
        (0..3).all(|a| other.min[a] >= self.min[a] - 1e-12 && other.max[a] <= self.max[a] + 1e-12)
    }

    /// True when the two boxes share a volume (touching faces do not overlap).
    pub fn overlaps(&self, other: &Aabb) -> bool {
        (0..3).all(|a| self.min[a] < other.max[a] - 1e-12 && other.min[a] < self.max[a] - 1e-12)
    }

    /// True when `p` lies inside the box (faces included).
    pub fn contains_point(&self, p: [f64; 3]) -> bool {
        (0..3).all(|a| p[a] >= self.min[a] && p[a] <= self.max[a])
    }
}

/// `tank = { min, max }`: the inner faces of the walls; walls are `wall_layers` particle layers
/// outside it. Extents that are not whole spacings are rounded to the nearest lattice face.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TankConfig {
    /// Lower corner `[x, y, z]` [m].
    pub min: [f64; 3],
    /// Upper corner `[x, y, z]` [m]: at least one spacing above `min` on every axis.
    pub max: [f64; 3],
    /// Close the top with a wall too (default: open top).
    #[serde(default)]
    pub lid: bool,
}

impl TankConfig {
    /// The tank's inner box.
    pub fn inner(&self) -> Aabb {
        Aabb {
            min: self.min,
            max: self.max,
        }
    }
}

/// `[[fluid.NAME.body]]`: a rigid box made of `Body` particles. In a fluid-only run it is held
/// fixed (an obstacle); coupled scenes move it with the structure's kinematics.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BodyConfig {
    /// The body's name, unique in the participant (`[[coupling.body]]` names it
    /// `fluid-participant/name`).
    pub name: String,
    /// Lower corner `[x, y, z]` [m].
    pub min: [f64; 3],
    /// Upper corner `[x, y, z]` [m].
    pub max: [f64; 3],
}
