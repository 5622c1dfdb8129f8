//! Fluid particles leaving through an open top: removed and counted, not a reason to stop.
//!
//! A tank without a lid lets splash rise over its walls: a particle that has left the domain
//! (the walls' outer faces, and [`crate::particles::layout::SPLASH_HEADROOM`] tank heights above the top)
//! while above the walls' top, less half a spacing, has left through the open top. The half
//! spacing is the allowance every wall face gets ([`crate::stability`]): a particle centre may
//! come to the centres of a wall's first layer, which on the walls' top face lie half a spacing
//! below it; so a splash particle that landed on a wall's top and slides off its outer edge has
//! passed over the wall, not through it. Such particles are removed at the
//! start of the next step and counted; the run stops only when they pass the case's
//! `max_removed_fraction` of the fluid. A particle leaving any other way (through a closed wall,
//! the floor or a lid) is an instability ([`crate::stability`]).

use crate::particles::kind::FLUID;
use crate::particles::layout::Domain;
use crate::particles::Particles;
use rayon::prelude::*;

/// Where fluid may leave the domain: above the walls' top of an open tank.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OpenTop {
    pub domain: Domain,
    /// z of the walls' top (the tank's inner top face).
    pub wall_top: f64,
    /// Particle spacing Δs (the walls' top face allows half of it, module doc).
    pub spacing: f64,
    /// False for a tank with a lid: nothing may leave.
    pub open: bool,
}

impl OpenTop {
    /// Whether a particle at `r` has left the domain through the open top.
    pub fn has_left(&self, r: [f64; 3]) -> bool {
        let outside = (0..3).any(|a| r[a] < self.domain.lo[a] || r[a] > self.domain.hi[a]);
        self.open && outside && r[2] > self.wall_top - 0.5 * self.spacing
    }

    /// Removes the fluid particles that have left through the open top (the others keep their
    /// order); returns how many.
    pub fn remove_escaped(&self, p: &mut Particles) -> u64 {
        if !self.open {
            return 0;
        }
        let gone = |i: usize| p.kind[i] == FLUID && self.has_left(p.position(i));
        if !(0..p.len()).into_par_iter().with_min_len(4096).any(gone) {
            return 0;
        }
        let keep: Vec<u32> = (0..p.len() as u32)
            .into_par_iter()
            .with_min_len(4096)
            .filter(|&i| !gone(i as usize))
            .collect();
        let removed = p.len() - keep.len();
        let mut scratch = Vec::new();
        p.permute(&keep, &mut scratch);
        removed as u64
    }
}
