//! `[fluid.NAME.inflow]` and `[fluid.NAME.outflow]`: open boundaries of a channel.

use super::{Aabb, FluidConfig};
use crate::case::error::check;
use crate::case::FieldError;
use schemars::JsonSchema;
use serde::Deserialize;

/// Fewest strip layers of an inflow: the fluid at the plane must see a full r_e = 3.1 Δs of
/// strip behind it while the back layer lags up to 1.5 Δs behind the strip's back (see
/// `fluid_solver::open_boundary`), so 3.1 + 1.5 rounded up.
pub const MIN_INFLOW_STRIP_LAYERS: f64 = 5.0;

/// `[fluid.NAME.inflow]`: an inflow boundary for run-up (Saitoh & Akitomo, Fig. 5): a strip of
/// particles upstream of the plane x = `plane` moves with u_in along +x and feeds water up to the
/// level h(t), which rises linearly from `initial_level` to `level` over `rise_time`.
///
/// ```toml
/// [fluid.river.inflow]
/// plane = 40.0          # x of the inflow plane [m]
/// velocity = 10.0       # u_in [m/s], along +x
/// strip_length = 40.0   # strip depth upstream of the plane [m]
/// level = 20.0          # h_max above the tank floor [m]
/// initial_level = 0.0   # h(0) [m]
/// rise_time = 4.0       # h reaches h_max at this time [s]
/// span = [0.0, 100.0]   # y range fed [m]; default: the tank's width
/// ```
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct InflowConfig {
    /// x of the inflow plane [m]. Range: on a lattice face, from tank.min.x + `strip_length`
    /// to one spacing before the tank's end.
    pub plane: f64,
    /// u_in [m/s] along +x. Range: > 0.
    pub velocity: f64,
    /// Depth of the strip upstream of the plane [m]. Range: a whole number of spacings, at
    /// least 5.
    pub strip_length: f64,
    /// Largest water level h_max above the tank floor [m]. Range: [spacing, tank height].
    pub level: f64,
    /// Water level at t = 0 [m]. Range: [0, level].
    #[serde(default)]
    pub initial_level: f64,
    /// Time over which the level rises linearly to `level` [s]; 0 means at once. Range: ≥ 0.
    #[serde(default)]
    pub rise_time: f64,
    /// `[y_min, y_max]` fed with water [m]; default: the tank's width.
    #[serde(default)]
    pub span: Option<[f64; 2]>,
}

impl InflowConfig {
    /// The water level h(t) above the tank floor [m].
    pub fn level_at(&self, t: f64) -> f64 {
        if self.rise_time > 0.0 && t < self.rise_time {
            self.initial_level + (self.level - self.initial_level) * (t.max(0.0) / self.rise_time)
        } else {
            self.level
        }
    }

    /// The fed y range: `span`, or the tank's width.
    pub fn span_or(&self, tank: &Aabb) -> [f64; 2] {
        self.span.unwrap_or([tank.min[1], tank.max[1]])
    }

    /// Checks every key against the tank and the spacing; returns the strip's box at full level.
    pub fn validate(&self, key: &str, tank: &Aabb, spacing: f64) -> Result<Aabb, FieldError> {
        let k = |s: &str| format!("{key}.{s}");
        check::positive(&k("velocity"), self.velocity)?;
        check::positive(&k("strip_length"), self.strip_length)?;
        check::positive(&k("level"), self.level)?;
        check::non_negative(&k("rise_time"), self.rise_time)?;
        let layers = self.strip_length / spacing;
        if (layers - layers.round()).abs() > 1e-6 * layers || layers.round() < MIN_INFLOW_STRIP_LAYERS {
            return Err(FieldError::new(
                k("strip_length"),
                format!(
                    "must be a whole number of spacings ({spacing} m), at least {MIN_INFLOW_STRIP_LAYERS}; got {} m = {layers:.4} spacings",
                    self.strip_length
                ),
            ));
        }
        let (back, front) = (tank.min[0] + self.strip_length, tank.max[0] - spacing);
        if !(self.plane.is_finite() && self.plane >= back - 1e-9 * spacing && self.plane <= front) {
            return Err(FieldError::new(
                k("plane"),
                format!(
                    "the inflow plane x = {} is outside the domain: with strip_length = {} m the strip must fit inside the tank, so the plane must be in [{back}, {front}] (tank x from {} to {})",
                    self.plane, self.strip_length, tank.min[0], tank.max[0]
                ),
            ));
        }
        let offset = (self.plane - tank.min[0]) / spacing;
        if (offset - offset.round()).abs() > 1e-6 * offset.max(1.0) {
            return Err(FieldError::new(
                k("plane"),
                format!(
                    "the inflow plane x = {} must lie on a lattice face, tank.min.x + a whole number of spacings ({spacing} m); it is {offset:.4} spacings in",
                    self.plane
                ),
            ));
        }
        let height = tank.max[2] - tank.min[2];
        if self.level > height || self.level < spacing {
            return Err(FieldError::new(
                k("level"),
                format!(
                    "the level {} m must be at least one spacing ({spacing} m) and must not be above the domain: at most the tank height {height} m",
                    self.level
                ),
            ));
        }
        if !(self.initial_level.is_finite() && (0.0..=self.level).contains(&self.initial_level)) {
            return Err(FieldError::new(
                k("initial_level"),
                format!(
                    "must be in [0, level = {}], got {}",
                    self.level, self.initial_level
                ),
            ));
        }
        let span = self.span_or(tank);
        let sites = ((span[1] - tank.min[1]) / spacing - 0.5).floor()
            - ((span[0] - tank.min[1]) / spacing - 0.5).ceil();
        if !(span[0].is_finite() && span[1].is_finite())
            || span[0] < tank.min[1]
            || span[1] > tank.max[1]
            || sites < 0.0
        {
            return Err(FieldError::new(
                k("span"),
                format!(
                    "{span:?} must be an increasing y range inside the tank [{}, {}] that holds a lattice site tank.min.y + (j + ½)·{spacing} m",
                    tank.min[1], tank.max[1]
                ),
            ));
        }
        Ok(Aabb {
            min: [self.plane - self.strip_length, span[0], tank.min[2]],
            max: [self.plane, span[1], tank.min[2] + self.level],
        })
    }
}

/// `[fluid.NAME.outflow]`: fluid particles beyond the plane x = `plane` are removed.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OutflowConfig {
    /// x of the outflow plane [m]. Range: after the inflow plane (or the tank's start), at
    /// least one spacing before the tank's end.
    pub plane: f64,
}

impl FluidConfig {
    /// Checks `inflow` and `outflow`: planes inside the tank, u_in > 0, the level inside the
    /// tank, and the inflow strip clear of blocks, gates and bodies.
    pub(super) fn validate_open_boundaries(
        &self,
        key: &str,
        named: &[(String, Aabb)],
    ) -> Result<(), FieldError> {
        let tank = self.tank.inner();
        let ds = self.spacing;
        let mut inflow_plane = None;
        if let Some(inflow) = &self.inflow {
            let strip = inflow.validate(&format!("{key}.inflow"), &tank, ds)?;
            for (kb, b) in named {
                if strip.overlaps(b) {
                    return Err(FieldError::new(
                        format!("{key}.inflow"),
                        format!(
                            "the inflow strip {:?} … {:?} overlaps `{kb}`; the strip must be free of water blocks, gates and bodies",
                            strip.min, strip.max
                        ),
                    ));
                }
            }
            inflow_plane = Some(inflow.plane);
        }
        if let Some(outflow) = &self.outflow {
            let k = format!("{key}.outflow.plane");
            let (lo, hi) = (inflow_plane.unwrap_or(tank.min[0]), tank.max[0] - ds);
            if !(outflow.plane.is_finite() && outflow.plane > lo && outflow.plane <= hi) {
                return Err(FieldError::new(
                    k,
                    format!(
                        "the outflow plane x = {} is outside the domain: it must lie after the {} (x > {lo}) and at least one spacing before the tank's end (x ≤ {hi})",
                        outflow.plane,
                        if inflow_plane.is_some() { "inflow plane" } else { "tank's start" }
                    ),
                ));
            }
        }
        Ok(())
    }
}
