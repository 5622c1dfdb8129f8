//! `[fluid.NAME.wave_maker]` (a piston paddle moving along +x by a prescribed stroke) and
//! `[[fluid.NAME.damping]]` (zones that absorb waves at the far end of a flume).
//!
//! ```toml
//! [fluid.flume.wave_maker]      # a solitary wave by Goring's method
//! min = [0.0, 0.0, 0.0]         # the paddle at rest: a box of wall particles across the flume
//! max = [0.04, 0.1, 0.3]
//! motion = "solitary"           # or "regular", "table"
//! wave_height = 0.02            # H [m]
//! depth = 0.1                   # still-water depth d in front of the paddle [m]
//!
//! [[fluid.flume.damping]]       # the last 2 m absorb the wave
//! min = [8.0, 0.0, 0.0]
//! max = [10.0, 0.1, 0.3]
//! rate = 10.0                   # [1/s] at the zone's far end
//! ```

use super::{signed_axis, Aabb, FluidConfig};
use crate::case::error::check;
use crate::case::FieldError;
use crate::wave_motion::{GoringSolitary, PistonMotion, Ramp, RegularWaves, StrokeTable};
use schemars::JsonSchema;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Highest solitary wave height over depth a wave maker generates: Goring's first-order wave
/// departs from the exact solitary wave as H/d grows, and the highest one is H/d ≈ 0.83.
pub const MAX_SOLITARY_HEIGHT: f64 = 0.6;

/// How the paddle moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum PaddleMotion {
    /// A solitary wave of height `wave_height` on `depth` by Goring's (1978) piston motion: the
    /// paddle moves with the wave's depth-averaged velocity at its own position, from rest to
    /// rest, by a stroke √(16 H d / 3).
    Solitary,
    /// Regular waves of height `wave_height` and `period` on `depth` by linear wave-maker theory
    /// (Biesel's transfer function), started over `ramp` seconds.
    Regular,
    /// The stroke over time from the CSV file `table` (columns t [s], X [m]; linear between
    /// rows), started over `ramp` seconds.
    Table,
}

/// `[fluid.NAME.wave_maker]`: a piston wave maker. Its paddle is a box of wall particles that
/// moves rigidly along +x by the stroke X(t) (negative X: backwards); the water sees the paddle's
/// position and velocity as it sees a moving wall.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WaveMakerConfig {
    /// Lower corner of the paddle at rest `[x, y, z]` [m]; inside the tank.
    pub min: [f64; 3],
    /// Upper corner of the paddle at rest `[x, y, z]` [m]: at least `wall_layers` spacings
    /// thick along x (so the water in front sees a full wall), as wide as the water it pushes.
    pub max: [f64; 3],
    /// The stroke's law.
    pub motion: PaddleMotion,
    /// Solitary and regular: wave height H [m]. Range: > 0; solitary H/d ≤ 0.6.
    #[serde(default)]
    pub wave_height: Option<f64>,
    /// Solitary and regular: still-water depth d in front of the paddle [m]. Range: > 0.
    #[serde(default)]
    pub depth: Option<f64>,
    /// Regular: wave period T [s]. Range: > 0.
    #[serde(default)]
    pub period: Option<f64>,
    /// Table: the CSV file of the stroke (t [s], X [m]), relative to the case file's folder.
    #[serde(default)]
    pub table: Option<PathBuf>,
    /// Regular and table: the stroke rises from 0 over this time [s] (½(1 − cos π t/ramp)); 0 is
    /// none. Range: ≥ 0.
    #[serde(default)]
    pub ramp: f64,
    /// The motion, built when the case is loaded ([`FluidConfig::load_files`]).
    #[serde(skip)]
    #[schemars(skip)]
    pub built: Option<Arc<PistonMotion>>,
}

impl WaveMakerConfig {
    /// The paddle's box at rest.
    pub fn paddle(&self) -> Aabb {
        Aabb {
            min: self.min,
            max: self.max,
        }
    }

    /// Builds the motion (reading the table, relative to `dir`); `key` names the section.
    pub fn motion(&self, gravity: f64, dir: &Path, key: &str) -> Result<PistonMotion, FieldError> {
        let need = |name: &str, v: Option<f64>| {
            v.ok_or_else(|| {
                FieldError::new(
                    format!("{key}.{name}"),
                    format!("is required with motion = \"{}\"", self.motion_name()),
                )
            })
        };
        let ramp = Ramp::new(self.ramp).map_err(|e| FieldError::new(format!("{key}.ramp"), e))?;
        let at_motion = |e: String| FieldError::new(format!("{key}.motion"), e);
        match self.motion {
            PaddleMotion::Solitary => {
                let (h, d) = (need("wave_height", self.wave_height)?, need("depth", self.depth)?);
                check::positive(&format!("{key}.wave_height"), h)?;
                check::positive(&format!("{key}.depth"), d)?;
                if h / d > MAX_SOLITARY_HEIGHT {
                    return Err(FieldError::new(
                        format!("{key}.wave_height"),
                        format!(
                            "H/d = {:.3} is above {MAX_SOLITARY_HEIGHT}: Goring's first-order solitary wave is not valid there (the highest solitary wave is H/d ≈ 0.83, and it breaks before)",
                            h / d
                        ),
                    ));
                }
                if self.ramp != 0.0 {
                    return Err(FieldError::new(
                        format!("{key}.ramp"),
                        "a solitary wave's paddle starts from rest by itself; `ramp` applies to regular and table motions",
                    ));
                }
                GoringSolitary::new(h, d, gravity)
                    .map(PistonMotion::Solitary)
                    .map_err(at_motion)
            }
            PaddleMotion::Regular => {
                let (h, d, t) = (
                    need("wave_height", self.wave_height)?,
                    need("depth", self.depth)?,
                    need("period", self.period)?,
                );
                check::positive(&format!("{key}.wave_height"), h)?;
                check::positive(&format!("{key}.depth"), d)?;
                check::positive(&format!("{key}.period"), t)?;
                RegularWaves::new(h, t, d, gravity, ramp)
                    .map(PistonMotion::Regular)
                    .map_err(at_motion)
            }
            PaddleMotion::Table => {
                let file = self.table.as_ref().ok_or_else(|| {
                    FieldError::new(format!("{key}.table"), "is required with motion = \"table\"")
                })?;
                // an absolute path replaces `dir` (`Path::join`)
                StrokeTable::read(&dir.join(file), ramp, &format!("{key}.table")).map(PistonMotion::Table)
            }
        }
    }

    fn motion_name(&self) -> &'static str {
        match self.motion {
            PaddleMotion::Solitary => "solitary",
            PaddleMotion::Regular => "regular",
            PaddleMotion::Table => "table",
        }
    }
}

/// `[[fluid.NAME.damping]]`: a box in which the fluid's velocity is relaxed towards rest, more
/// strongly towards its far end along `axis`: `u ← u exp(−rate s² Δt)` each step, with s the
/// distance into the box along `axis` over its length (0 at the near face, 1 at the far one). A
/// zone a wavelength or two long absorbs a wave with little reflection.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DampingConfig {
    /// Lower corner `[x, y, z]` [m]; inside the tank.
    pub min: [f64; 3],
    /// Upper corner `[x, y, z]` [m].
    pub max: [f64; 3],
    /// The direction the damping grows along: "+x" (default), "-x", "+y", "-y".
    #[serde(default = "default_damping_axis")]
    pub axis: String,
    /// Relaxation rate at the far face [1/s]; about 2π over the wave's period is a start.
    /// Range: > 0.
    pub rate: f64,
}

fn default_damping_axis() -> String {
    "+x".into()
}

impl DampingConfig {
    /// The zone's box.
    pub fn zone(&self) -> Aabb {
        Aabb {
            min: self.min,
            max: self.max,
        }
    }

    /// The axis (0 for x, 1 for y) and the sign of the direction the damping grows along
    /// ([`signed_axis`]; z is not an axis a wave runs along).
    pub fn direction(&self) -> Option<(usize, f64)> {
        signed_axis(&self.axis).filter(|&(a, _)| a < 2)
    }
}

impl FluidConfig {
    /// Checks the wave maker's paddle at rest and the damping zones; `named` are the section's
    /// boxes, which the paddle must not overlap (its motion is checked by
    /// [`FluidConfig::build_wave_maker`]).
    pub(super) fn validate_waves(&self, key: &str, named: &[(String, Aabb)]) -> Result<(), FieldError> {
        let tank = self.tank.inner();
        for (i, d) in self.damping.iter().enumerate() {
            let dk = format!("{key}.damping[{i}]");
            d.zone().validate(&dk)?;
            check::positive(&format!("{dk}.rate"), d.rate)?;
            if d.direction().is_none() {
                return Err(FieldError::new(
                    format!("{dk}.axis"),
                    format!(
                        "must be one of \"+x\", \"-x\", \"+y\", \"-y\", got \"{}\"",
                        d.axis
                    ),
                ));
            }
            if !tank.contains(&d.zone()) {
                return Err(FieldError::new(dk, "must lie inside the tank"));
            }
        }
        let Some(w) = &self.wave_maker else { return Ok(()) };
        let wk = format!("{key}.wave_maker");
        let paddle = w.paddle();
        paddle.validate(&wk)?;
        check::non_negative(&format!("{wk}.ramp"), w.ramp)?;
        let thick = paddle.max[0] - paddle.min[0];
        let need = f64::from(self.wall_layers) * self.spacing;
        if thick < need - 1e-9 * need {
            return Err(FieldError::new(
                format!("{wk}.max"),
                format!(
                    "the paddle is {thick} m thick along x; it needs at least wall_layers × spacing = {need} m so the water in front of it sees a full wall"
                ),
            ));
        }
        if !tank.contains(&paddle) {
            return Err(FieldError::new(
                wk,
                format!(
                    "the paddle {:?} … {:?} must lie inside the tank {:?} … {:?}",
                    paddle.min, paddle.max, tank.min, tank.max
                ),
            ));
        }
        for (k, b) in named {
            if paddle.overlaps(b) {
                return Err(FieldError::new(wk, format!("the paddle overlaps `{k}` at rest")));
            }
        }
        Ok(())
    }

    /// Builds the wave maker's motion and checks that the paddle stays inside the tank over the
    /// whole run (`end_time`); `dir` is the case file's folder. (Boxes in its path are not
    /// checked: the paddle pushes what is in front of it.)
    pub fn build_wave_maker(&mut self, dir: &Path, key: &str, end_time: f64) -> Result<(), FieldError> {
        let g = self.gravity_magnitude();
        let tank = self.tank.inner();
        let Some(w) = self.wave_maker.as_mut() else {
            return Ok(());
        };
        let wk = format!("{key}.wave_maker");
        let motion = w.motion(g, dir, &wk)?;
        let (lo, hi) = motion.range(end_time);
        let paddle = w.paddle();
        if paddle.min[0] + lo < tank.min[0] - 1e-9 || paddle.max[0] + hi > tank.max[0] + 1e-9 {
            return Err(FieldError::new(
                format!("{wk}.motion"),
                format!(
                    "the paddle {:?} … {:?} moves by {lo:.4} … {hi:.4} m along x over the run and would leave the tank (x from {} to {}): move it, or lengthen the tank behind it",
                    paddle.min[0], paddle.max[0], tank.min[0], tank.max[0]
                ),
            ));
        }
        w.built = Some(Arc::new(motion));
        Ok(())
    }
}
