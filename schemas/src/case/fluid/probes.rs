//! `[[fluid.NAME.probe]]`: what a fluid participant measures, one CSV column per probe.

use super::FluidConfig;
use crate::case::error::check;
use crate::case::FieldError;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// What a probe measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ProbeKind {
    /// Height of the water surface above the tank floor at `position = [x, y]`: the top of the
    /// water column within Δs horizontally that stands on the floor (or on a wall block), plus
    /// Δs/2; spray and drops not connected to that column are left out.
    #[default]
    WaterHeight,
    /// Pressure at `position = [x, y, z]`: the mean over fluid, wall and body particles within
    /// r_e,grad = 2.1 Δs, weighted by w(r) of S1-6.
    Pressure,
    /// Surge front: how far the water reaches along `axis` ("x", "+x", "-x", …), plus Δs/2,
    /// measured from the tank face it starts at (`tank.min` for +, `tank.max` for −; spray
    /// excluded).
    SurgeFront,
    /// A pressure sensor mounted on a wall or obstacle face: a disc of `diameter` centred at
    /// `position` on the face whose outward normal (into the water) is `normal`; reads the
    /// normal force of the fluid on the wall particles behind the disc per unit area, optionally
    /// box-filtered over the last `window` seconds.
    WallPressure,
    /// Run-up: the elevation above the tank floor of the highest water particle resting on a
    /// solid (a wall, terrain, solid or body particle below it within r_e,grad = 2.1 Δs and
    /// within 27° of the vertical: a beach or a floor holds it, the side walls of a narrow flume
    /// and vertical faces do not), plus Δs/2 as the water-height gauge adds; spray (number
    /// density below half of n0) is left out. No position. The column's maximum minus the
    /// still-water level is the run-up R.
    RunUp,
}

/// `[[fluid.NAME.probe]]`: one column of the probe CSV.
#[derive(Debug, Clone, PartialEq, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ProbeConfig {
    /// The probe's column in the probe CSV: unique, without commas.
    pub name: String,
    /// What the probe measures.
    pub kind: ProbeKind,
    /// `[x, y]` for water-height, `[x, y, z]` for pressure and wall-pressure, none for
    /// surge-front and run-up [m]; inside the tank.
    #[serde(default)]
    pub position: Vec<f64>,
    /// Surge-front only: axis and direction of the front, "x" or "+x" (default), "-x", "y",
    /// "+y", "-y", "z", "+z", "-z".
    #[serde(default)]
    pub axis: Option<String>,
    // Wall-pressure sensors (issue 15): face normal, disc diameter, filter window.
    /// Wall-pressure only: outward normal of the face the sensor is mounted on, pointing into
    /// the water: one of "+x", "-x", "+y", "-y", "+z", "-z" (walls and obstacles are
    /// axis-aligned boxes). Required there.
    #[serde(default)]
    pub normal: Option<String>,
    /// Wall-pressure only: diameter of the sensor's disc [m]. Required there. Range: ≥ spacing.
    #[serde(default)]
    pub diameter: Option<f64>,
    /// Wall-pressure only: box filter [s]: the reading is the mean over every step
    /// of the last `window` seconds (an experiment's sensor rate / anti-alias filter); default:
    /// the instantaneous reading. Range: > 0.
    #[serde(default)]
    pub window: Option<f64>,
}

/// An axis and a sign, parsed from "x", "+x", "-x", … (`None` for anything else).
pub fn signed_axis(s: &str) -> Option<(usize, f64)> {
    let (sign, axis) = match s.as_bytes().first() {
        Some(b'+') => (1.0, &s[1..]),
        Some(b'-') => (-1.0, &s[1..]),
        _ => (1.0, s),
    };
    let a = ["x", "y", "z"].iter().position(|&n| n == axis)?;
    Some((a, sign))
}

impl ProbeConfig {
    /// A water-height gauge named `name` at (x, y) = `at`.
    pub fn water_height(name: &str, at: [f64; 2]) -> ProbeConfig {
        ProbeConfig {
            name: name.into(),
            kind: ProbeKind::WaterHeight,
            position: at.to_vec(),
            ..Default::default()
        }
    }

    /// The surge-front axis as an index (0 = x).
    pub fn axis_index(&self) -> usize {
        self.axis_direction().0
    }

    /// The surge-front axis and its direction (+1 towards `tank.max`, −1 towards `tank.min`).
    pub fn axis_direction(&self) -> (usize, f64) {
        self.axis.as_deref().and_then(signed_axis).unwrap_or((0, 1.0))
    }

    /// A wall-pressure sensor's normal as axis and sign (validated: always present there).
    pub fn normal_direction(&self) -> (usize, f64) {
        self.normal.as_deref().and_then(signed_axis).unwrap_or((2, 1.0))
    }
}

impl FluidConfig {
    pub(super) fn validate_probes(&self, key: &str) -> Result<(), FieldError> {
        for (i, p) in self.probe.iter().enumerate() {
            let pk = format!("{key}.probe[{i}]");
            if p.name.trim().is_empty() || p.name.contains(',') {
                return Err(FieldError::new(
                    format!("{pk}.name"),
                    "must be a non-empty name without commas",
                ));
            }
            if self.probe[..i].iter().any(|o| o.name == p.name) {
                return Err(FieldError::new(
                    format!("{pk}.name"),
                    format!("probe name `{}` is used twice", p.name),
                ));
            }
            let (want, kind) = match p.kind {
                ProbeKind::WaterHeight => (2, "water-height"),
                ProbeKind::Pressure => (3, "pressure"),
                ProbeKind::SurgeFront => (0, "surge-front"),
                ProbeKind::WallPressure => (3, "wall-pressure"),
                ProbeKind::RunUp => (0, "run-up"),
            };
            Self::validate_sensor_keys(p, &pk, self.spacing)?;
            if p.position.len() != want {
                return Err(FieldError::new(
                    format!("{pk}.position"),
                    format!(
                        "a {kind} probe needs {want} coordinates, got {}",
                        p.position.len()
                    ),
                ));
            }
            check::finite(&format!("{pk}.position"), &p.position)?;
            let t = self.tank;
            if (0..want).any(|a| p.position[a] < t.min[a] || p.position[a] > t.max[a]) {
                return Err(FieldError::new(
                    format!("{pk}.position"),
                    format!("{:?} is outside the tank {:?} … {:?}", p.position, t.min, t.max),
                ));
            }
            if let Some(axis) = &p.axis {
                if signed_axis(axis).is_none() || p.kind != ProbeKind::SurgeFront {
                    return Err(FieldError::new(
                        format!("{pk}.axis"),
                        format!(
                            "only a surge-front probe has an axis, one of \"x\", \"+x\", \"-x\", \"y\", \"+y\", \"-y\", \"z\", \"+z\", \"-z\"; got `{axis}`"
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// `normal`, `diameter` and `window`: required (the first two) on a wall-pressure sensor,
    /// refused on the other probes.
    fn validate_sensor_keys(p: &ProbeConfig, pk: &str, spacing: f64) -> Result<(), FieldError> {
        let sensor = p.kind == ProbeKind::WallPressure;
        let keys = [
            ("normal", p.normal.is_some()),
            ("diameter", p.diameter.is_some()),
            ("window", p.window.is_some()),
        ];
        if let Some((key, _)) = keys.iter().find(|(_, set)| *set && !sensor) {
            return Err(FieldError::new(
                format!("{pk}.{key}"),
                "only a wall-pressure probe has `normal`, `diameter` and `window`",
            ));
        }
        if !sensor {
            return Ok(());
        }
        match p.normal.as_deref() {
            Some(n) if n.starts_with(['+', '-']) && signed_axis(n).is_some() => {}
            other => {
                return Err(FieldError::new(
                    format!("{pk}.normal"),
                    format!(
                        "a wall-pressure sensor needs the face's outward normal (into the water), one of \"+x\", \"-x\", \"+y\", \"-y\", \"+z\", \"-z\"; got {other:?}"
                    ),
                ))
            }
        }
        match p.diameter {
            Some(d) if d.is_finite() && d >= spacing => {}
            other => {
                return Err(FieldError::new(
                    format!("{pk}.diameter"),
                    format!(
                        "a wall-pressure sensor needs a disc diameter of at least one spacing ({spacing} m); got {other:?}"
                    ),
                ))
            }
        }
        if let Some(w) = p.window {
            check::positive(&format!("{pk}.window"), w)?;
        }
        Ok(())
    }
}
