//! The particles a sensor reads: the host's, or on the GPU path while the device is ahead of the
//! host's copy, what the device gives back without a whole copy. A local probe (a gauge's
//! column, a pressure point's ball) reads the device's particles around it
//! ([`crate::gpu::gather`]); a surge front the water's extent and the run-up gauge the highest
//! water resting on a solid, both reduced on the device ([`crate::gpu::probe_reductions`]); the
//! open boundaries' balance reads all the particles once per row, positions, kinds, number
//! densities and pressures only (24 B a particle against the whole copy's 44 and the host's cell
//! sort after it), as do a surge front and a run-up gauge with wide positions.

use crate::particles::Particles;
use crate::solver::FluidSolver;
use std::borrow::Cow;
use std::cell::OnceCell;

/// One instant's particles for the sensors of a row (see the module doc).
pub struct ParticleView<'a> {
    solver: &'a FluidSolver,
    /// The device's particles, all of them, light (copied at the first global read).
    all: OnceCell<Option<Particles>>,
    /// The water's extent on the device (reduced at the first surge front's read).
    extent: OnceCell<Option<[[f64; 2]; 3]>>,
    /// The highest water resting on a solid, on the device (reduced at the first run-up read).
    run_up_top: OnceCell<Option<Option<f64>>>,
}

impl<'a> ParticleView<'a> {
    /// The view of `solver`'s particles now.
    pub fn of(solver: &'a FluidSolver) -> ParticleView<'a> {
        ParticleView {
            solver,
            all: OnceCell::new(),
            extent: OnceCell::new(),
            run_up_top: OnceCell::new(),
        }
    }

    pub fn solver(&self) -> &'a FluidSolver {
        self.solver
    }

    /// Every particle (kinds, positions, number densities and pressures; on the device's copy
    /// velocities and ids read 0).
    pub fn all(&self) -> &Particles {
        match self.all.get_or_init(|| self.solver.device_particles_all()) {
            Some(p) => p,
            None => self.solver.particles(),
        }
    }

    /// Per axis, the largest and smallest coordinate of the water (fluid not spray), reduced on
    /// the device; `None` when the host's particles are current, with wide positions, or with no
    /// water.
    pub fn water_extent(&self) -> Option<[[f64; 2]; 3]> {
        *self
            .extent
            .get_or_init(|| self.solver.device_ahead().and_then(|dev| dev.water_extent()))
    }

    /// The highest z of the water resting on a solid (`Some(None)`: none rests), reduced on the
    /// device; `None` when the host's particles are current or with wide positions.
    pub fn run_up_top(&self) -> Option<Option<f64>> {
        *self
            .run_up_top
            .get_or_init(|| self.solver.device_ahead().and_then(|dev| dev.run_up_top()))
    }

    /// At least the particles in the box `lo`–`hi` (the device's copy holds some around it).
    pub fn around(&self, lo: [f64; 3], hi: [f64; 3]) -> Cow<'_, Particles> {
        if let Some(Some(p)) = self.all.get() {
            return Cow::Borrowed(p);
        }
        match self.solver.device_particles_in(lo, hi) {
            Some(p) => Cow::Owned(p),
            None => Cow::Borrowed(self.solver.particles()),
        }
    }
}
