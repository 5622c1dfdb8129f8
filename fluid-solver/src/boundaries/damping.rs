//! Damping zones (`[[fluid.NAME.damping]]`): after each step the fluid's velocity in a zone is
//! relaxed towards rest, `u ← u exp(−rate s² Δt)`, s rising from 0 at the zone's near face to 1
//! at its far one ([`DampingZone::factor`]), so a wave running into it
//! is absorbed over its length instead of reflected at the tank's end. The quadratic ramp keeps
//! the change of impedance at the zone's entrance small (the same idea as the relaxation zones
//! of wave flumes, e.g. Altomare et al. 2017, Coastal Eng. 127).

use crate::particles::kind::FLUID;
use crate::particles::Particles;
use rayon::prelude::*;
use schemas::case::fluid::{Aabb, DampingConfig};

/// One zone as the step reads it: its box, and the axis and direction the damping grows along,
/// parsed once from its `[[damping]]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct DampingZone {
    zone: Aabb,
    axis: usize,
    sign: f64,
    rate: f64,
}

impl DampingZone {
    /// The zone of a validated `[[damping]]` table (`None` for an axis validation refuses).
    pub fn of(cfg: &DampingConfig) -> Option<DampingZone> {
        let (axis, sign) = cfg.direction()?;
        Some(DampingZone {
            zone: cfg.zone(),
            axis,
            sign,
            rate: cfg.rate,
        })
    }

    /// The factor `exp(−rate s² Δt)` at `x` for a step of `dt` (1 outside the zone).
    pub fn factor(&self, x: [f64; 3], dt: f64) -> f64 {
        let (z, a) = (&self.zone, self.axis);
        if !z.contains_point(x) {
            return 1.0;
        }
        let len = z.max[a] - z.min[a];
        let s = if self.sign > 0.0 {
            (x[a] - z.min[a]) / len
        } else {
            (z.max[a] - x[a]) / len
        };
        (-self.rate * s * s * dt).exp()
    }
}

/// Relaxes the velocity of the fluid in `zones` after a step of `dt`.
pub fn relax(zones: &[DampingZone], p: &mut Particles, dt: f64) {
    if zones.is_empty() {
        return;
    }
    (&mut p.vx, &mut p.vy, &mut p.vz, &p.x, &p.y, &p.z, &p.kind)
        .into_par_iter()
        .with_min_len(4096)
        .for_each(|(u, v, w, &x, &y, &z, &k)| {
            if k != FLUID {
                return;
            }
            let f: f64 = zones.iter().map(|d| d.factor([x, y, z], dt)).product();
            *u *= f;
            *v *= f;
            *w *= f;
        });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::kind::Kind;

    /// A zone 1 m long along +x with rate 10/s: after a step of 0.01 s a fluid particle's
    /// velocity is multiplied by exp(−10 s² 0.01) at s = 0, ½, 1 and 1 outside; walls keep theirs.
    #[test]
    fn the_zone_relaxes_fluid_velocity_by_the_quadratic_ramp() {
        let zone = DampingConfig {
            min: [1.0, 0.0, 0.0],
            max: [2.0, 1.0, 1.0],
            axis: "+x".into(),
            rate: 10.0,
        };
        let mut p = Particles::default();
        for x in [0.5, 1.0, 1.5, 2.0] {
            p.push_moving([x, 0.5, 0.5], [1.0, -2.0, 0.5], Kind::Fluid, p.len() as u32);
        }
        p.push_moving([1.5, 0.5, 0.5], [1.0, 0.0, 0.0], Kind::Wall, 4);
        let zone = DampingZone::of(&zone).unwrap_or_else(|| panic!("+x is an axis"));
        relax(&[zone], &mut p, 0.01);
        for (i, s) in [(0, None), (1, Some(0.0)), (2, Some(0.5)), (3, Some(1.0))] {
            let f = s.map_or(1.0, |s: f64| (-10.0 * s * s * 0.01).exp());
            assert!(
                (p.vx[i] - f).abs() < 1e-15
                    && (p.vy[i] + 2.0 * f).abs() < 1e-15
                    && (p.vz[i] - 0.5 * f).abs() < 1e-15
            );
        }
        assert_eq!(p.vx[4], 1.0);
    }
}
