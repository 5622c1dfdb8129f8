//! `[fluid.NAME.initial_wave]`: a solitary wave already in the tank at t = 0, as the NTHMP
//! benchmarks pose it (Synolakis 1987: the wave centred half a wavelength off the beach's toe,
//! moving towards it), instead of a paddle that makes it.
//!
//! ```toml
//! [fluid.flume.initial_wave]
//! height = 0.01                 # H [m]
//! depth = 0.1                   # d [m]: the still level is the tank floor + d
//! crest = 0.6                   # x of the crest at t = 0 [m]
//! direction = "+x"              # the way it travels: "+x" (default) or "-x"
//! ```
//!
//! The water of every block whose top is at the still level is raised to z_s + η(x), and every
//! fluid particle under the wave moves with its velocity ([`SolitaryWave::velocity_at`]).

use super::wave_maker::MAX_SOLITARY_HEIGHT;
use super::{Aabb, FluidConfig};
use crate::case::error::check;
use crate::case::FieldError;
use crate::wave_motion::SolitaryWave;
use schemars::JsonSchema;
use serde::Deserialize;

/// `[fluid.NAME.initial_wave]`: a first-order solitary wave η = H sech²(k (x − crest)),
/// k = √(3H / 4d³), in the tank at t = 0 (as NTHMP benchmark 1 starts): the water of every block
/// whose top is at the still level (tank floor + `depth`) is raised to the wave's surface, and
/// the water under it moves with the wave's depth-averaged velocity u = ± c η / (d + η),
/// c = √(g (d + H)), and the vertical velocity continuity gives it (zero at the floor).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct InitialWaveConfig {
    /// Wave height H [m]. Range: > 0, H/d ≤ 0.6.
    pub height: f64,
    /// Still-water depth d over the tank floor [m]: the still level z_s = tank `min` z + d is the
    /// top of the blocks the wave raises. Range: > 0, z_s + H inside the tank.
    pub depth: f64,
    /// x of the crest at t = 0 [m]. Range: inside the tank.
    pub crest: f64,
    /// The direction the wave travels: "+x" (default) or "-x".
    #[serde(default = "default_direction")]
    pub direction: String,
}

fn default_direction() -> String {
    "+x".into()
}

impl InitialWaveConfig {
    /// +1 for "+x", −1 for "-x", None otherwise.
    pub fn sign(&self) -> Option<f64> {
        match self.direction.as_str() {
            "+x" => Some(1.0),
            "-x" => Some(-1.0),
            _ => None,
        }
    }

    /// The wave under gravity of magnitude `g`, crest at `crest` (x measured in the tank's frame).
    pub fn wave(&self, g: f64) -> Result<SolitaryWave, String> {
        Ok(SolitaryWave::new(self.height, self.depth, g)?.with_crest_at(self.crest))
    }
}

impl FluidConfig {
    /// Checks `initial_wave` against the tank and the blocks.
    pub(super) fn validate_initial_wave(&self, key: &str) -> Result<(), FieldError> {
        let Some(w) = &self.initial_wave else {
            return Ok(());
        };
        let wk = format!("{key}.initial_wave");
        check::positive(&format!("{wk}.height"), w.height)?;
        check::positive(&format!("{wk}.depth"), w.depth)?;
        check::finite(&format!("{wk}.crest"), &[w.crest])?;
        if w.sign().is_none() {
            return Err(FieldError::new(
                format!("{wk}.direction"),
                format!("must be \"+x\" or \"-x\", got \"{}\"", w.direction),
            ));
        }
        if w.height / w.depth > MAX_SOLITARY_HEIGHT {
            return Err(FieldError::new(
                format!("{wk}.height"),
                format!(
                    "H/d = {:.3} is above {MAX_SOLITARY_HEIGHT}: the first-order solitary wave is not a wave of permanent form that high",
                    w.height / w.depth
                ),
            ));
        }
        w.wave(self.gravity_magnitude())
            .map_err(|e| FieldError::new(wk.clone(), e))?;
        let tank = self.tank.inner();
        let still = tank.min[2] + w.depth;
        if still + w.height > tank.max[2] {
            return Err(FieldError::new(
                format!("{wk}.depth"),
                format!(
                    "the crest's top, tank floor + depth + height = {} m, is above the tank's top {} m",
                    still + w.height,
                    tank.max[2]
                ),
            ));
        }
        if !(tank.min[0]..=tank.max[0]).contains(&w.crest) {
            return Err(FieldError::new(
                format!("{wk}.crest"),
                format!(
                    "x = {} m is outside the tank's x range [{}, {}]",
                    w.crest, tank.min[0], tank.max[0]
                ),
            ));
        }
        let half = 0.5 * self.spacing;
        if !self.block.iter().any(|b| (b.max[2] - still).abs() <= half) {
            return Err(FieldError::new(
                format!("{wk}.depth"),
                format!(
                    "no block's top is at the still level tank floor + depth = {still} m (within half a spacing): the wave raises the water of such blocks"
                ),
            ));
        }
        Ok(())
    }

    /// True when the initial wave raises the site `p` to water: above the still level, below the
    /// wave's surface, over a block whose top is at the still level.
    pub fn raised_by_initial_wave(&self, p: [f64; 3], wave: &SolitaryWave) -> bool {
        let Some(w) = &self.initial_wave else { return false };
        let still = self.tank.min[2] + w.depth;
        let half = 0.5 * self.spacing;
        p[2] >= still
            && p[2] < still + wave.elevation(p[0], 0.0)
            && self.block.iter().any(|b: &Aabb| {
                (b.max[2] - still).abs() <= half && b.contains_point([p[0], p[1], still - half])
            })
    }
}
