//! `[fluid.NAME.wave_maker]` (a paddle moved by a prescribed stroke: a piston along +x, or a
//! flap turning about a hinge) and `[[fluid.NAME.damping]]` (zones that absorb waves at the far
//! end of a flume).
//!
//! ```toml
//! [fluid.flume.wave_maker]      # a solitary wave by Goring's method
//! min = [0.0, 0.0, 0.0]         # the paddle at rest: a box of wall particles across the flume
//! max = [0.04, 0.1, 0.3]
//! motion = "solitary"           # or "regular", "table"
//! wave_height = 0.02            # H [m]
//! depth = 0.1                   # still-water depth d in front of the paddle [m]
//! # kind = "flap"               # a flap instead of the piston: it turns about an axis along y
//! # hinge_z = 0.0               # at the paddle's front face, at or below its bottom [m]
//!
//! [[fluid.flume.damping]]       # the last 2 m absorb the wave
//! min = [8.0, 0.0, 0.0]
//! max = [10.0, 0.1, 0.3]
//! rate = 10.0                   # [1/s] at the zone's far end
//! ```

use super::{signed_axis, Aabb, FluidConfig};
use crate::case::error::check;
use crate::case::FieldError;
use crate::wave_motion::flap::{swept_extent, MAX_FLAP_ANGLE_DEG};
use crate::wave_motion::{
    FlapHinge, FlapMotion, GoringSolitary, PistonMotion, Ramp, RegularWaves, StrokeTable, WaveMakerMotion,
};
use schemars::JsonSchema;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Highest solitary wave height over depth a wave maker generates: Goring's first-order wave
/// departs from the exact solitary wave as H/d grows, and the highest one is H/d ≈ 0.83.
pub const MAX_SOLITARY_HEIGHT: f64 = 0.6;

/// What kind of paddle the wave maker is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum PaddleKind {
    /// A vertical paddle that moves rigidly along +x by the stroke X(t).
    #[default]
    Piston,
    /// A paddle that turns rigidly about a horizontal axis along y at its front face (x = `max`
    /// x, z = `hinge_z`) by θ = atan(X / (z_s − `hinge_z`)), so that its face moves by the stroke
    /// X(t) at the still-water level z_s = `min` z + `depth`.
    Flap,
}

/// How the paddle moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum PaddleMotion {
    /// A solitary wave of height `wave_height` on `depth` by Goring's (1978) piston motion: the
    /// paddle moves with the wave's depth-averaged velocity at its own position, from rest to
    /// rest, by a stroke √(16 H d / 3). A flap's depth-averaged stroke follows it (its stroke at
    /// the still-water level is (d + l)/(d/2 + l) times the piston's, l = `min` z − `hinge_z`;
    /// our reading, Goring's method is a piston's).
    Solitary,
    /// Regular waves of height `wave_height` and `period` on `depth` by linear wave-maker theory
    /// (Biesel's transfer function; a flap's for a flap), started over `ramp` seconds.
    Regular,
    /// The stroke over time from the CSV file `table` (columns t [s], X [m]; linear between
    /// rows; a flap's at the still-water level), started over `ramp` seconds.
    Table,
}

/// `[fluid.NAME.wave_maker]`: a piston or flap wave maker. Its paddle is a box of wall particles
/// that moves rigidly by the stroke X(t) (negative X: backwards): a piston along +x, a flap by
/// turning about its hinge; the water sees the paddle's position and velocity as it sees a moving
/// wall.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WaveMakerConfig {
    /// Lower corner of the paddle at rest `[x, y, z]` [m]; inside the tank.
    pub min: [f64; 3],
    /// Upper corner of the paddle at rest `[x, y, z]` [m]: at least `wall_layers` spacings
    /// thick along x (so the water in front sees a full wall), as wide as the water it pushes.
    pub max: [f64; 3],
    /// "piston" (default) or "flap".
    #[serde(default)]
    pub kind: PaddleKind,
    /// Flap only, required: height of the hinge axis [m] (along y, at the paddle's front face
    /// x = `max` x). Range: at or below the paddle's bottom `min` z (the floor under it; lower:
    /// the flap is hinged in a pit under the floor). The flap may turn by at most ±30° over the
    /// run, and its turned box must stay inside the tank.
    #[serde(default)]
    pub hinge_z: Option<f64>,
    /// The stroke's law.
    pub motion: PaddleMotion,
    /// Solitary and regular: wave height H [m]. Range: > 0; solitary H/d ≤ 0.6.
    #[serde(default)]
    pub wave_height: Option<f64>,
    /// Solitary, regular and every flap: still-water depth d in front of the paddle [m], over
    /// its bottom `min` z. Range: > 0.
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
    pub built: Option<Arc<WaveMakerMotion>>,
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
    pub fn motion(&self, gravity: f64, dir: &Path, key: &str) -> Result<WaveMakerMotion, FieldError> {
        let hinge = match self.kind {
            PaddleKind::Piston => None,
            PaddleKind::Flap => Some(self.flap_hinge(key)?),
        };
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
                match hinge {
                    None => GoringSolitary::new(h, d, gravity)
                        .map(|m| WaveMakerMotion::Piston(PistonMotion::Solitary(m))),
                    Some(hinge) => FlapMotion::solitary(h, gravity, hinge).map(WaveMakerMotion::Flap),
                }
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
                match hinge {
                    None => RegularWaves::new(h, t, d, gravity, ramp)
                        .map(|m| WaveMakerMotion::Piston(PistonMotion::Regular(m))),
                    Some(hinge) => FlapMotion::regular(h, t, gravity, ramp, hinge).map(WaveMakerMotion::Flap),
                }
                .map_err(at_motion)
            }
            PaddleMotion::Table => {
                let file = self.table.as_ref().ok_or_else(|| {
                    FieldError::new(format!("{key}.table"), "is required with motion = \"table\"")
                })?;
                // an absolute path replaces `dir` (`Path::join`)
                let table = StrokeTable::read(&dir.join(file), ramp, &format!("{key}.table"))?;
                Ok(match hinge {
                    None => WaveMakerMotion::Piston(PistonMotion::Table(table)),
                    Some(hinge) => WaveMakerMotion::Flap(FlapMotion::table(table, hinge)),
                })
            }
        }
    }

    /// A flap's hinge: `hinge_z` under the paddle's bottom, with the still water `depth` deep
    /// over it (required for every flap motion: the stroke is measured at its level).
    fn flap_hinge(&self, key: &str) -> Result<FlapHinge, FieldError> {
        let depth = self.depth.ok_or_else(|| {
            FieldError::new(
                format!("{key}.depth"),
                "is required with kind = \"flap\": a flap's stroke is its displacement at the still-water level, `depth` above the paddle's bottom",
            )
        })?;
        check::positive(&format!("{key}.depth"), depth)?;
        let hinge_z = self
            .hinge_z
            .ok_or_else(|| FieldError::new(format!("{key}.hinge_z"), "is required with kind = \"flap\""))?;
        FlapHinge::new(hinge_z, self.min[2], depth).map_err(|e| FieldError::new(format!("{key}.hinge_z"), e))
    }

    fn motion_name(&self) -> &'static str {
        match self.motion {
            PaddleMotion::Solitary => "solitary",
            PaddleMotion::Regular => "regular",
            PaddleMotion::Table => "table",
        }
    }
}

/// Refuses a flap that turns by more than [`MAX_FLAP_ANGLE_DEG`] over [0, `end_time`], or whose
/// `paddle` box, turned through every angle it reaches about its hinge (x = `max` x, z =
/// `hinge_z`), leaves the `tank` along x or rises into its lid. (It may dip into the floor: the
/// floor's wall particles lie there, and a flap hinged under the floor turns through it.)
fn flap_stays_in(
    flap: &FlapMotion,
    paddle: &Aabb,
    tank: &Aabb,
    lid: bool,
    end_time: f64,
    wk: &str,
) -> Result<(), FieldError> {
    let (lo, hi) = flap.angle_range(end_time);
    let limit = MAX_FLAP_ANGLE_DEG.to_radians();
    let (x_lo, x_hi) = flap.range(end_time);
    if lo < -limit || hi > limit {
        return Err(FieldError::new(
            format!("{wk}.motion"),
            format!(
                "the flap turns from {:.1}° to {:.1}° over the run (its stroke {x_lo:.4} … {x_hi:.4} m at the still-water level, {:.4} m above the hinge); at most ±{MAX_FLAP_ANGLE_DEG}° is allowed, where linear wave-maker theory, on which the motions rest, still holds: lower the waves, or lower the hinge (hinge_z)",
                lo.to_degrees(),
                hi.to_degrees(),
                flap.hinge().lever()
            ),
        ));
    }
    let hinge = [paddle.max[0], flap.hinge().z()];
    let (min, max) = swept_extent(
        [paddle.min[0], paddle.min[2]],
        [paddle.max[0], paddle.max[2]],
        hinge,
        (lo, hi),
    );
    let into_lid = lid && max[1] > tank.max[2] + 1e-9;
    if min[0] < tank.min[0] - 1e-9 || max[0] > tank.max[0] + 1e-9 || into_lid {
        return Err(FieldError::new(
            format!("{wk}.motion"),
            format!(
                "the flap {:?} … {:?}, turning from {:.1}° to {:.1}° about its hinge at x = {}, z = {} over the run, sweeps x from {:.4} to {:.4} m and z up to {:.4} m and would leave the tank (x from {} to {}{}): move it, leave room behind it or under the lid, or lower the waves",
                paddle.min,
                paddle.max,
                lo.to_degrees(),
                hi.to_degrees(),
                hinge[0],
                hinge[1],
                min[0],
                max[0],
                max[1],
                tank.min[0],
                tank.max[0],
                if lid {
                    format!(", z up to the lid at {}", tank.max[2])
                } else {
                    String::new()
                }
            ),
        ));
    }
    Ok(())
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
        let hk = format!("{wk}.hinge_z");
        match (w.kind, w.hinge_z) {
            (PaddleKind::Piston, Some(_)) => Err(FieldError::new(
                hk,
                "applies to kind = \"flap\" only: a piston has no hinge",
            )),
            (PaddleKind::Flap, None) => Err(FieldError::new(
                hk,
                "is required with kind = \"flap\": the height of the hinge axis (along y, at the paddle's front face x = max.x), at or below the paddle's bottom min.z",
            )),
            (PaddleKind::Flap, Some(z)) if !z.is_finite() || z > paddle.min[2] => Err(FieldError::new(
                hk,
                format!(
                    "must lie at or below the paddle's bottom min.z = {} (the floor under it; lower: a flap hinged in a pit under the floor), got {z}",
                    paddle.min[2]
                ),
            )),
            _ => Ok(()),
        }
    }

    /// Builds the wave maker's motion and checks that the paddle stays inside the tank over the
    /// whole run (`end_time`; a flap also within ±[`MAX_FLAP_ANGLE_DEG`], [`flap_stays_in`]);
    /// `dir` is the case file's folder. (Boxes in its path are not checked: the paddle pushes
    /// what is in front of it.)
    pub fn build_wave_maker(&mut self, dir: &Path, key: &str, end_time: f64) -> Result<(), FieldError> {
        let g = self.gravity_magnitude();
        let tank = self.tank.inner();
        let lid = self.tank.lid;
        let Some(w) = self.wave_maker.as_mut() else {
            return Ok(());
        };
        let wk = format!("{key}.wave_maker");
        let motion = w.motion(g, dir, &wk)?;
        let paddle = w.paddle();
        if let WaveMakerMotion::Flap(flap) = &motion {
            flap_stays_in(flap, &paddle, &tank, lid, end_time, &wk)?;
            w.built = Some(Arc::new(motion));
            return Ok(());
        }
        let (lo, hi) = motion.range(end_time);
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
