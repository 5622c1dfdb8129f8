//! `[fluid.NAME.inflow]` and `[fluid.NAME.outflow]`: open boundaries of a channel.

use super::inflow_law::InflowLaw;
use super::inflow_series::InflowSeries;
use super::{Aabb, FluidConfig};
use crate::case::error::check;
use crate::case::FieldError;
use schemars::JsonSchema;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Fewest strip layers of an inflow: the fluid at the plane must see a full r_e = 3.1 Δs of
/// strip behind it while the back layer lags up to 1.5 Δs behind the strip's back (see
/// `fluid_solver::open_boundary`), so 3.1 + 1.5 rounded up.
pub const MIN_INFLOW_STRIP_LAYERS: f64 = 5.0;

/// `[fluid.NAME.inflow]`: an inflow boundary for run-up (Saitoh & Akitomo, Fig. 5): a strip of
/// particles upstream of the plane x = `plane` moves with u(t) along +x and feeds water up to the
/// level h(t). Either u(t) = `velocity` and h(t) rises linearly from `initial_level` to `level`
/// over `rise_time`, or both come from the CSV file `series` (then those four keys are absent).
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
///
/// ```toml
/// [fluid.river.inflow]  # a measured or computed hydrograph instead
/// plane = 40.0
/// strip_length = 40.0
/// series = "inflow.csv" # rows `t, level, velocity` [s, m, m/s], linear between rows
/// ```
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct InflowConfig {
    /// x of the inflow plane [m]. Range: on a lattice face, from tank.min.x + `strip_length`
    /// to one spacing before the tank's end.
    pub plane: f64,
    /// u_in [m/s] along +x, constant. Range: > 0. Required unless `series` is given; absent with
    /// it.
    #[serde(default)]
    pub velocity: Option<f64>,
    /// Depth of the strip upstream of the plane [m]. Range: a whole number of spacings, at
    /// least 5.
    pub strip_length: f64,
    /// Largest water level h_max above the tank floor [m]. Range: [spacing, tank height].
    /// Required unless `series` is given; absent with it.
    #[serde(default)]
    pub level: Option<f64>,
    /// Water level at t = 0 [m]; default 0. Range: [0, level]. Absent with `series`.
    #[serde(default)]
    pub initial_level: Option<f64>,
    /// Time over which the level rises linearly to `level` [s]; default 0, at once. Range: ≥ 0.
    /// Absent with `series`.
    #[serde(default)]
    pub rise_time: Option<f64>,
    /// A CSV file of the level and velocity over time, relative to the case file's folder,
    /// instead of `velocity`, `level`, `initial_level` and `rise_time`: rows `t, level, velocity`
    /// in s, m and m/s (a header line and `#` comments allowed), linear between rows and held at
    /// the last row after it. Where the level falls, the strip's rows above it are withdrawn.
    /// Range: times increasing, the first ≤ 0, at least 2 rows; levels in [0, tank height];
    /// velocity > 0 where the level is > 0 and ≥ 0 where it is 0 (a strip cannot run backwards).
    #[serde(default)]
    pub series: Option<PathBuf>,
    /// `[y_min, y_max]` fed with water [m]; default: the tank's width.
    #[serde(default)]
    pub span: Option<[f64; 2]>,
    /// The `series`, read when the case is loaded ([`InflowConfig::read_series`]).
    #[serde(skip)]
    #[schemars(skip)]
    pub loaded: Option<Arc<InflowSeries>>,
}

impl InflowConfig {
    /// What drives the strip: the `series` once read, else `velocity` and the rise of `level`;
    /// `None` while a key it needs is missing or the series is not read (a validated section of
    /// a loaded case always has one).
    pub fn law(&self) -> Option<InflowLaw> {
        match (&self.series, &self.loaded) {
            (Some(_), Some(series)) => Some(InflowLaw::Series(series.as_ref().clone())),
            (Some(_), None) => None,
            (None, _) => Some(InflowLaw::Ramp {
                velocity: self.velocity?,
                level: self.level?,
                initial_level: self.initial_level.unwrap_or(0.0),
                rise_time: self.rise_time.unwrap_or(0.0),
            }),
        }
    }

    /// Reads `series` (if given) relative to `dir`, the case file's folder; `key` names the
    /// section. Before [`InflowConfig::validate`], which checks the levels against the tank.
    pub fn read_series(&mut self, dir: &Path, key: &str) -> Result<(), FieldError> {
        if let Some(file) = &self.series {
            // an absolute path replaces `dir` (`Path::join`)
            let series = InflowSeries::read(&dir.join(file), &format!("{key}.series"))?;
            self.loaded = Some(Arc::new(series));
        }
        Ok(())
    }

    /// The fed y range: `span`, or the tank's width.
    pub fn span_or(&self, tank: &Aabb) -> [f64; 2] {
        self.span.unwrap_or([tank.min[1], tank.max[1]])
    }

    /// Checks every key against the tank and the spacing; returns the strip's box at its highest
    /// level.
    pub fn validate(&self, key: &str, tank: &Aabb, spacing: f64) -> Result<Aabb, FieldError> {
        let k = |s: &str| format!("{key}.{s}");
        let height = tank.max[2] - tank.min[2];
        let top = match &self.series {
            Some(file) => self.validate_series(key, file, height)?,
            None => self.validate_ramp(key, spacing, height)?,
        };
        check::positive(&k("strip_length"), self.strip_length)?;
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
            max: [self.plane, span[1], tank.min[2] + top],
        })
    }

    /// Checks `velocity`, `level`, `initial_level` and `rise_time` (no `series`); returns h_max.
    fn validate_ramp(&self, key: &str, spacing: f64, height: f64) -> Result<f64, FieldError> {
        let k = |s: &str| format!("{key}.{s}");
        let required = |name: &str, v: Option<f64>| {
            v.ok_or_else(|| {
                FieldError::new(
                    k(name),
                    "is required: give `velocity` and `level` (a constant velocity, the level rising over `rise_time`), or `series` (a CSV file of the level and velocity over time)",
                )
            })
        };
        let velocity = required("velocity", self.velocity)?;
        let level = required("level", self.level)?;
        let (initial_level, rise_time) = (self.initial_level.unwrap_or(0.0), self.rise_time.unwrap_or(0.0));
        check::positive(&k("velocity"), velocity)?;
        check::positive(&k("level"), level)?;
        check::non_negative(&k("rise_time"), rise_time)?;
        if level > height || level < spacing {
            return Err(FieldError::new(
                k("level"),
                format!(
                    "the level {level} m must be at least one spacing ({spacing} m) and must not be above the domain: at most the tank height {height} m"
                ),
            ));
        }
        if !(initial_level.is_finite() && (0.0..=level).contains(&initial_level)) {
            return Err(FieldError::new(
                k("initial_level"),
                format!("must be in [0, level = {level}], got {initial_level}"),
            ));
        }
        Ok(level)
    }

    /// Checks that `series` comes alone and that its levels fit the tank; returns the largest.
    fn validate_series(&self, key: &str, file: &Path, height: f64) -> Result<f64, FieldError> {
        let k = format!("{key}.series");
        let given: Vec<&str> = [
            ("velocity", self.velocity.is_some()),
            ("level", self.level.is_some()),
            ("initial_level", self.initial_level.is_some()),
            ("rise_time", self.rise_time.is_some()),
        ]
        .into_iter()
        .filter_map(|(name, set)| set.then_some(name))
        .collect();
        if !given.is_empty() {
            return Err(FieldError::new(
                k,
                format!(
                    "`series` gives the level and velocity over time, so `{}` must be absent (velocity, level, initial_level and rise_time are for a constant velocity and a linear rise)",
                    given.join("`, `")
                ),
            ));
        }
        let series = self.loaded.as_ref().ok_or_else(|| {
            FieldError::new(
                &k,
                format!(
                    "the series {} has not been read: a case read by `Case::load` or `Case::parse` reads it (InflowConfig::read_series)",
                    file.display()
                ),
            )
        })?;
        series.check_height(height, &k)?;
        Ok(series.max_level())
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
