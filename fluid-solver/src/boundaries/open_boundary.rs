//! Inflow and outflow boundaries for tsunami run-up (Saitoh & Akitomo, §IV-B and Fig. 5):
//! water is fed in at u(t) with a level h(t), and removed downstream, so the particle count
//! changes during the run.
//!
//! Inflow: a strip of [`Kind::Inflow`] particles on the tank's lattice, `strip_length` deep
//! upstream of the plane x = x_in, moves rigidly along +x by the law of the section
//! ([`InflowLaw`]: a constant u_in and a linear rise of h, or a CSV time series of both). Its
//! particles are not integrated by S1-10 … S1-13; like wall particles they count in the number
//! density (S1-15), get a pressure from S1-14 and enter the gradient (S1-3) of their fluid
//! neighbours, so the strip pushes the water in front of it like a piston.
//!
//! In the step from t to t + Δt the strip moves by u_s Δt with u_s = u(t + Δt/2), and every strip
//! particle's velocity is set to u_s (a rigid piston; new particles are born with it). The
//! midpoint makes the strip's travel the exact integral ∫u dt over every step that no row of a
//! series falls inside (u is linear there); for a constant u it is u_in Δt. Whenever the strip has
//! advanced one spacing a new layer is inserted at its back. The strip's rows follow the level:
//! n(t) = round(h(t)/Δs) rows, at z_k = z_floor + (k + ½) Δs, k < n. When n rises the new rows
//! are added along the whole strip; when it falls the strip particles of rows k ≥ n are withdrawn
//! (deleted), so the strip is always a box of n(t) rows. A strip particle that crosses the plane
//! becomes fluid, keeping its velocity.
//!
//! Outflow: fluid particles beyond the plane x = x_out are removed.
//!
//! [`ParticleBalance`] counts the particles inserted, turned into fluid, removed and withdrawn;
//! with the counts by kind they close exactly: Δ(all particles) = inserted − removed − withdrawn,
//! Δ(fluid) = entered − removed and Δ(strip) = inserted − entered − withdrawn.

use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;
use schemas::case::fluid::{FluidConfig, InflowConfig, InflowLaw};
use std::fs;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// Particles added and removed by the open boundaries since the solver was made.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct ParticleBalance {
    /// Strip particles created during the run (the initial strip is part of the initial layout).
    pub inserted: u64,
    /// Strip particles that crossed the inflow plane and became fluid.
    pub entered: u64,
    /// Fluid particles removed behind the outflow plane.
    pub removed: u64,
    /// Strip particles deleted above a falling level.
    pub withdrawn: u64,
}

/// The counts of several parts of the fluid added up (the slabs of [`crate::ranks`], each of
/// which runs only the boundaries in it).
impl std::iter::Sum for ParticleBalance {
    fn sum<I: Iterator<Item = ParticleBalance>>(parts: I) -> ParticleBalance {
        parts.fold(ParticleBalance::default(), |a, b| ParticleBalance {
            inserted: a.inserted + b.inserted,
            entered: a.entered + b.entered,
            removed: a.removed + b.removed,
            withdrawn: a.withdrawn + b.withdrawn,
        })
    }
}

/// The inflow strip: where its lattice is and how far it is filled.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
struct InflowStrip {
    /// h(t) and u(t).
    law: InflowLaw,
    /// x of the inflow plane.
    plane: f64,
    spacing: f64,
    /// x of the strip's back face: `plane − strip_length`.
    back: f64,
    /// y of the lattice sites fed with water.
    ys: Vec<f64>,
    /// z of the lowest site (half a spacing above the tank floor).
    z0: f64,
    /// Distance the strip has moved since its back layer was inserted, in [0, Δs).
    shift: f64,
    /// Particle rows the whole strip is filled to.
    rows: usize,
}

impl InflowStrip {
    fn new(cfg: &InflowConfig, fluid: &FluidConfig) -> InflowStrip {
        let tank = fluid.tank.inner();
        let ds = fluid.spacing;
        let span = cfg.span_or(&tank);
        let first = ((span[0] - tank.min[1]) / ds - 0.5).ceil().max(0.0) as usize;
        let last = ((span[1] - tank.min[1]) / ds - 0.5).floor().max(0.0) as usize;
        InflowStrip {
            law: cfg.law().expect(
                "a validated inflow has its law (the series is read when the case is loaded: InflowConfig::read_series)",
            ),
            plane: cfg.plane,
            spacing: ds,
            back: cfg.plane - cfg.strip_length,
            ys: (first..=last)
                .map(|j| tank.min[1] + (j as f64 + 0.5) * ds)
                .collect(),
            z0: tank.min[2] + 0.5 * ds,
            shift: 0.0,
            rows: 0,
        }
    }

    /// Rows of particles for the level h(t): h rounded to whole spacings.
    fn rows_at(&self, t: f64) -> usize {
        (self.law.level_at(t) / self.spacing).round() as usize
    }

    /// x of the strip's layers that are still upstream of the plane, back to front.
    fn layers(&self) -> Vec<f64> {
        (0..)
            .map(|m| self.back + self.shift + (m as f64 + 0.5) * self.spacing)
            .take_while(|&x| x < self.plane)
            .collect()
    }

    /// Adds the sites of layer `x`, rows `rows`, moving with `u`; returns how many.
    fn fill(
        &self,
        p: &mut Particles,
        x: f64,
        rows: std::ops::Range<usize>,
        u: f64,
        next_id: &mut u32,
    ) -> u64 {
        let mut added = 0;
        for k in rows {
            let z = self.z0 + k as f64 * self.spacing;
            for &y in &self.ys {
                p.push_moving([x, y, z], [u, 0.0, 0.0], Kind::Inflow, *next_id);
                *next_id += 1;
                added += 1;
            }
        }
        added
    }

    /// Sets the whole strip to the rows of level h(t): adds the missing rows along it, moving
    /// with `u`, or withdraws the strip particles above them; returns (added, withdrawn).
    fn level_to(&mut self, p: &mut Particles, t: f64, u: f64, next_id: &mut u32) -> (u64, u64) {
        let rows = self.rows_at(t);
        let (mut added, mut withdrawn) = (0, 0);
        if rows > self.rows {
            added = self
                .layers()
                .into_iter()
                .map(|x| self.fill(p, x, self.rows..rows, u, next_id))
                .sum();
        } else if rows < self.rows {
            // rows k ≥ n sit at z ≥ z0 + n Δs; the cut lies half a spacing below
            let cut = self.z0 + (rows as f64 - 0.5) * self.spacing;
            let inflow = Kind::Inflow.code();
            withdrawn = remove_where(p, |p, i| p.kind[i] == inflow && p.z[i] > cut);
        }
        self.rows = rows;
        (added, withdrawn)
    }

    /// Turns the strip particles that crossed the plane during the last step into fluid (those
    /// within [`PLANE_SLACK`] spacings short of it too, see there), moves
    /// the rest by u_s·dt with u_s = u(t + dt/2), sets their velocity to u_s and inserts a back
    /// layer for every spacing travelled; returns (inserted, entered, u_s). Converting before
    /// moving moves every particle once per step: a particle moved across the plane here is
    /// integrated from the next step on, not moved twice (by the strip, then by the E-MPS step)
    /// in this one.
    fn advance(&mut self, p: &mut Particles, t: f64, dt: f64, next_id: &mut u32) -> (u64, u64, f64) {
        let (u, plane) = (
            self.law.velocity_at(t + 0.5 * dt),
            self.plane - PLANE_SLACK * self.spacing,
        );
        let inflow = Kind::Inflow.code();
        let entered: u64 = (&mut p.x, &mut p.vx, &mut p.kind)
            .into_par_iter()
            .with_min_len(4096)
            .map(|(x, vx, k)| {
                if *k != inflow {
                    0
                } else if *x >= plane {
                    *k = FLUID;
                    1
                } else {
                    *x += u * dt;
                    *vx = u;
                    0
                }
            })
            .sum();
        self.shift += u * dt;
        let mut inserted = 0;
        while self.shift >= self.spacing {
            self.shift -= self.spacing;
            let x = self.back + self.shift + 0.5 * self.spacing;
            inserted += self.fill(p, x, 0..self.rows, u, next_id);
        }
        (inserted, entered, u)
    }
}

/// A strip particle within this many spacings short of the inflow plane counts as across it. The
/// particles of one layer share its x only up to rounding (a row added along the strip when the
/// level rises starts at the layer's x, the others got there by a step's travel at a time), so
/// a layer arriving exactly on the plane (u t a whole number of spacings at a step's end: the
/// small bridge's at t = 3.0 s) was split, 68 of its 170 particles entering one step and the rest
/// the next; the GPU path, whose f32 positions cannot tell them apart, then entered all 170 and
/// stopped (`gpu/open_boundary.rs`). 1e-9 Δs is 10⁵ times the rounding of x at 10 km.
pub const PLANE_SLACK: f64 = 1e-9;

/// The inflow and outflow boundaries of one fluid participant, with their particle balance.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct OpenBoundaries {
    inflow: Option<InflowStrip>,
    /// x of the outflow plane.
    outflow: Option<f64>,
    balance: ParticleBalance,
    /// The id the next inserted particle gets (ids are never reused).
    next_id: u32,
}

impl OpenBoundaries {
    /// The boundaries of a validated section of a loaded case; adds the initial strip (level
    /// h(0), velocity u(0)) to `p`.
    pub fn new(cfg: &FluidConfig, p: &mut Particles) -> OpenBoundaries {
        let mut next_id = p.id.iter().max().map_or(0, |&m| m + 1);
        let inflow = cfg.inflow.as_ref().map(|c| {
            let mut strip = InflowStrip::new(c, cfg);
            let u = strip.law.velocity_at(0.0);
            strip.level_to(p, 0.0, u, &mut next_id);
            strip
        });
        OpenBoundaries {
            inflow,
            outflow: cfg.outflow.as_ref().map(|o| o.plane),
            balance: ParticleBalance::default(),
            next_id,
        }
    }

    /// True when the case has an inflow or an outflow.
    pub fn is_active(&self) -> bool {
        self.inflow.is_some() || self.outflow.is_some()
    }

    /// True when water is fed in (an energy source for the stability monitor).
    pub fn has_inflow(&self) -> bool {
        self.inflow.is_some()
    }

    /// Counts since the start.
    pub fn balance(&self) -> ParticleBalance {
        self.balance
    }

    /// x of the outflow plane, when there is one.
    pub fn outflow_plane(&self) -> Option<f64> {
        self.outflow
    }

    /// x of the inflow plane, when there is one.
    pub fn inflow_plane(&self) -> Option<f64> {
        self.inflow.as_ref().map(|strip| strip.plane)
    }

    /// Leaves the inflow out unless `inflow`, the outflow unless `outflow`: a slab of the fluid
    /// runs only the boundaries that lie in it ([`crate::ranks::subdomain`]).
    pub fn keep_only(&mut self, inflow: bool, outflow: bool) {
        if !inflow {
            self.inflow = None;
        }
        if !outflow {
            self.outflow = None;
        }
    }

    /// Adds fluid particles removed behind the outflow plane elsewhere (the GPU path removes
    /// them on the device and runs [`OpenBoundaries::apply`] on its host copy of the strip
    /// only: `crate::gpu::open_boundary`).
    pub(crate) fn add_removed(&mut self, removed: u64) {
        self.balance.removed += removed;
    }

    /// The boundaries' part of a step from `t` to `t + dt`, done before the E-MPS stages: strip
    /// particles past the inflow plane become fluid, the rest of the strip moves by
    /// u(t + dt/2)·dt and gets its new back layers and the rows of h(t + dt) (added or
    /// withdrawn); fluid behind the outflow plane is removed. The particle order changes (the
    /// step re-sorts).
    pub fn apply(&mut self, p: &mut Particles, t: f64, dt: f64) {
        if let Some(strip) = &mut self.inflow {
            let (inserted, entered, u) = strip.advance(p, t, dt, &mut self.next_id);
            let (added, withdrawn) = strip.level_to(p, t + dt, u, &mut self.next_id);
            self.balance.inserted += inserted + added;
            self.balance.entered += entered;
            self.balance.withdrawn += withdrawn;
        }
        if let Some(plane) = self.outflow {
            self.balance.removed += remove_where(p, |p, i| p.kind[i] == FLUID && p.x[i] > plane);
        }
    }
}

/// Removes the particles `i` for which `gone(p, i)` holds (the others keep their order);
/// returns how many.
fn remove_where(p: &mut Particles, gone: impl Fn(&Particles, usize) -> bool + Sync) -> u64 {
    let keep: Vec<u32> = (0..p.len() as u32)
        .into_par_iter()
        .with_min_len(4096)
        .filter(|&i| !gone(p, i as usize))
        .collect();
    let removed = p.len() - keep.len();
    if removed > 0 {
        let mut scratch = Vec::new();
        p.permute(&keep, &mut scratch);
    }
    removed as u64
}

/// The balance CSV: `time, inserted, entered, removed, withdrawn, inflow, fluid, total,
/// fluid_mass`.
pub struct BalanceFile {
    out: BufWriter<fs::File>,
}

impl BalanceFile {
    /// Creates the file with its header.
    pub fn create(path: &Path) -> io::Result<BalanceFile> {
        let mut out = BufWriter::new(fs::File::create(path)?);
        writeln!(
            out,
            "time,inserted,entered,removed,withdrawn,inflow,fluid,total,fluid_mass"
        )?;
        out.flush()?;
        Ok(BalanceFile { out })
    }

    /// Appends the row of time `t` with the counts of `p`; `particle_mass` is ρ0 Δs³.
    pub fn row(&mut self, t: f64, b: ParticleBalance, p: &Particles, particle_mass: f64) -> io::Result<()> {
        let counts = [p.count(Kind::Inflow), p.count(Kind::Fluid), p.len()].map(|n| n as u64);
        self.row_of_counts(t, b, counts, particle_mass)
    }

    /// Appends the row of time `t` with the particles counted elsewhere: `[inflow, fluid,
    /// total]` (the slabs of a fluid count their own).
    pub fn row_of_counts(
        &mut self,
        t: f64,
        b: ParticleBalance,
        [inflow, fluid, total]: [u64; 3],
        particle_mass: f64,
    ) -> io::Result<()> {
        writeln!(
            self.out,
            "{t:.6},{},{},{},{},{inflow},{fluid},{total},{:.6e}",
            b.inserted,
            b.entered,
            b.removed,
            b.withdrawn,
            fluid as f64 * particle_mass
        )?;
        self.out.flush()
    }
}
