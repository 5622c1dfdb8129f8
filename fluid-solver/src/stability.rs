//! Instability detector: NaN, fluid particles leaving the domain (other than through an open top,
//! see [`crate::boundaries::escape`]) or entering a wall or body, body
//! particles entering a wall, a fluid particle moving more than half a spacing in one step, and
//! mechanical energy growing without a source (checked until a body moves: moving bodies are a
//! source). Each finding names the step, the particle and the quantity.
//!
//! A body, from a box or a mesh, is checked in its own frame at its present pose
//! ([`BodyInterior`]): a fluid particle is inside a box body when `R(q)ᵀ (r − c)` lies within the
//! box shrunk by half a spacing (behind the centres of its outer particle layer), inside a mesh
//! body when, taken to the body's initial placement, it is more than about half a spacing inside
//! the body's lattice sites (the rule of the mesh solids, [`SolidSites::deep_inside`]).

use crate::boundaries::escape::OpenTop;
use crate::particles::body_interior::{body_frame, BodyInterior};
use crate::particles::kind::{Kind, FLUID};
use crate::particles::layout::Domain;
use crate::particles::solid_sites::SolidSites;
use crate::particles::Particles;
use rayon::prelude::*;
use schemas::case::fluid::Aabb;
use std::fmt;
use std::sync::Arc;

/// Largest displacement per step, in spacings, before the step is taken as unstable.
pub const MAX_STEP_DISPLACEMENT: f64 = 0.5;
/// Allowed growth of the fluid's mechanical energy, as a fraction of its initial potential
/// energy above the tank floor (E-MPS dissipates: growth beyond this has no physical source).
pub const ENERGY_GROWTH_FRACTION: f64 = 0.1;

/// Why a run was stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct Instability {
    pub step: u64,
    pub time: f64,
    /// Stable particle id (index in the initial layout), if one particle is to blame.
    pub particle: Option<u32>,
    /// The quantity that went wrong, e.g. "velocity".
    pub quantity: &'static str,
    pub message: String,
}

impl fmt::Display for Instability {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unstable run stopped at step {} (t = {:.6} s): ",
            self.step, self.time
        )?;
        if let Some(id) = self.particle {
            write!(f, "particle {id}: ")?;
        }
        write!(f, "{}: {}", self.quantity, self.message)
    }
}

impl std::error::Error for Instability {}

/// Watches a run for the signs of instability.
#[derive(Debug, Clone)]
pub struct StabilityMonitor {
    domain: Domain,
    /// Particles that left through here are removed and counted, not findings.
    open_top: OpenTop,
    /// Regions fluid must not enter: the tank's outside (beyond the first wall layer's centres)
    /// is checked through `tank`; fixed walls through their boxes shrunk by half a spacing.
    tank: Aabb,
    solids: Vec<Aabb>,
    /// The mesh solids' and terrains' sites ([`SolidSites::deep_inside`]).
    solid_sites: Arc<SolidSites>,
    /// Each body's inside, checked at the pose given to [`StabilityMonitor::check`].
    bodies: Vec<BodyInterior>,
    spacing: f64,
    gravity: [f64; 3],
    /// Mechanical energy per unit particle mass at the start, and the allowed growth.
    initial_energy: Option<f64>,
    allowed_growth: f64,
    /// Moving bodies do work on the fluid: the energy check is off once one has moved.
    driven: bool,
}

/// A particle-level finding of one scan.
type Finding = (u32, &'static str, String);

impl StabilityMonitor {
    /// A monitor for a tank with fixed `walls` and rigid `bodies` (their insides about their
    /// initial centres), particles of `spacing`; fluid leaving through `open_top` is not a
    /// finding.
    pub fn new(
        domain: Domain,
        open_top: OpenTop,
        tank: Aabb,
        walls: &[Aabb],
        bodies: Vec<BodyInterior>,
        spacing: f64,
        gravity: [f64; 3],
    ) -> Self {
        let h = 0.5 * spacing;
        let solids = walls
            .iter()
            .map(|b| Aabb {
                min: b.min.map(|v| v + h),
                max: b.max.map(|v| v - h),
            })
            .filter(|b| (0..3).all(|a| b.max[a] > b.min[a]))
            .collect();
        StabilityMonitor {
            domain,
            open_top,
            tank,
            solids,
            solid_sites: Arc::new(SolidSites::default()),
            bodies,
            spacing,
            gravity,
            initial_energy: None,
            allowed_growth: 0.0,
            driven: false,
        }
    }

    /// Mechanical energy per unit mass summed over fluid particles: Σ ½|u|² − g·r.
    pub fn mechanical_energy(&self, p: &Particles) -> f64 {
        self.mechanical_energy_where(p, |_| true)
    }

    /// [`StabilityMonitor::mechanical_energy`] over the fluid particles `i` with `keep(i)` (a
    /// slab's own, not its halo's: [`crate::ranks`]).
    pub fn mechanical_energy_where(&self, p: &Particles, keep: impl Fn(usize) -> bool + Sync) -> f64 {
        let g = self.gravity;
        (0..p.len())
            .into_par_iter()
            .with_min_len(4096)
            .filter(|&i| p.kind[i] == FLUID && keep(i))
            .map(|i| {
                let v2 = p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i];
                0.5 * v2 - (g[0] * p.x[i] + g[1] * p.y[i] + g[2] * p.z[i])
            })
            .sum()
    }

    /// Marks the fluid as driven by moving bodies (an energy source): no energy check from now on.
    pub fn set_driven(&mut self) {
        self.driven = true;
    }

    /// The energy check's reference (initial energy, allowed growth, driven), which a resumed run
    /// takes over from the checkpoint.
    pub fn energy_reference(&self) -> (Option<f64>, f64, bool) {
        (self.initial_energy, self.allowed_growth, self.driven)
    }

    /// Takes over a reference from [`StabilityMonitor::energy_reference`].
    pub fn set_energy_reference(&mut self, (initial, growth, driven): (Option<f64>, f64, bool)) {
        self.initial_energy = initial;
        self.allowed_growth = growth;
        self.driven = driven;
    }

    /// The mechanical energy ([`StabilityMonitor::mechanical_energy`]) above which a step is
    /// unstable; `None` when the energy is not checked (driven fluid, or before the start).
    pub fn energy_limit(&self) -> Option<f64> {
        self.initial_energy
            .filter(|_| !self.driven)
            .map(|e0| e0 + self.allowed_growth)
    }

    /// Records the initial energy (call once before the first step).
    pub fn start(&mut self, p: &Particles) {
        let g = self.gravity;
        let gmag = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        let height = self.tank.max[2] - self.tank.min[2];
        let kinetic: f64 = (0..p.len())
            .filter(|&i| p.kind[i] == FLUID)
            .map(|i| 0.5 * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]))
            .sum();
        let fluid = p.count(Kind::Fluid) as f64;
        self.initial_energy = Some(self.mechanical_energy(p));
        self.allowed_growth =
            ENERGY_GROWTH_FRACTION * (fluid * gmag * height + kinetic).max(f64::MIN_POSITIVE);
    }

    /// Checks the state after step `step` of length `dt` ending at `time`, with the bodies at
    /// `body_pose` (7 per body: centre, quaternion w x y z relative to the initial placement).
    pub fn check(
        &self,
        p: &Particles,
        step: u64,
        time: f64,
        dt: f64,
        body_pose: &[f64],
    ) -> Result<(), Instability> {
        // The lowest id found, then its finding again: carrying each finding through the
        // reduction (`filter_map(..).min_by_key(..)`) took 7.5 ms a step over S2's 311 000
        // particles, none of them found, and this 2.3 ms.
        let first = (0..p.len())
            .into_par_iter()
            .with_min_len(4096)
            .filter(|&i| self.check_particle(p, i, dt, body_pose).is_some())
            .min_by_key(|&i| p.id[i]);
        if let Some((id, quantity, message)) = first.and_then(|i| self.check_particle(p, i, dt, body_pose)) {
            return Err(Instability {
                step,
                time,
                particle: Some(id),
                quantity,
                message,
            });
        }
        if let Some(e0) = self.initial_energy.filter(|_| !self.driven) {
            let e = self.mechanical_energy(p);
            if !e.is_finite() || e - e0 > self.allowed_growth {
                let fastest = (0..p.len())
                    .filter(|&i| p.kind[i] == FLUID)
                    .max_by(|&a, &b| speed(p, a).total_cmp(&speed(p, b)));
                return Err(Instability {
                    step,
                    time,
                    particle: fastest.map(|i| p.id[i]),
                    quantity: "mechanical energy",
                    message: format!(
                        "the fluid's energy per unit particle mass grew from {e0:.6e} to {e:.6e} (allowed growth {:.3e}) with no source; the named particle is the fastest ({:.3} m/s)",
                        self.allowed_growth,
                        fastest.map(|i| speed(p, i)).unwrap_or(0.0)
                    ),
                });
            }
        }
        Ok(())
    }

    fn check_particle(&self, p: &Particles, i: usize, dt: f64, body_pose: &[f64]) -> Option<Finding> {
        let id = p.id[i];
        let r = p.position(i);
        let u = p.velocity(i);
        if r.iter().chain(&u).any(|v| !v.is_finite()) || !p.pressure[i].is_finite() {
            let q = if r.iter().any(|v| !v.is_finite()) {
                "position"
            } else if u.iter().any(|v| !v.is_finite()) {
                "velocity"
            } else {
                "pressure"
            };
            return Some((
                id,
                q,
                format!("not a number: r = {r:?}, u = {u:?}, P = {}", p.pressure[i]),
            ));
        }
        let is_body = p.kind[i] == Kind::Body.code();
        if p.kind[i] != FLUID && !is_body {
            return None;
        }
        if let Some(wall) = self.inside_wall(r) {
            let who = if is_body { "a body particle went " } else { "" };
            return Some((id, "position", format!("{who}{wall}")));
        }
        if is_body {
            return None;
        }
        if self.open_top.has_left(r) {
            return None; // removed and counted at the next step's start
        }
        if (0..3).any(|a| r[a] < self.domain.lo[a] || r[a] > self.domain.hi[a]) {
            return Some((
                id,
                "position",
                format!(
                    "left the domain {:?} … {:?} through a closed wall, the floor or the lid: r = {r:?}",
                    self.domain.lo, self.domain.hi
                ),
            ));
        }
        if let Some(finding) = self.inside_body(r, body_pose) {
            return Some((id, "position", finding));
        }
        let step = speed(p, i) * dt;
        if step > MAX_STEP_DISPLACEMENT * self.spacing {
            return Some((
                id,
                "velocity",
                format!(
                    "|u| = {:.4} m/s at r = {r:?} moves {:.3} spacings in one step (limit {MAX_STEP_DISPLACEMENT}): the flow is faster than the time step allows; use time_step ≤ {:.3e} s (E-MPS: with sound_speed ≥ 10 |u|; ISPH, which cuts a step short where the fluid at its start outruns it, down to Δt/8: or set max_velocity ≥ {:.2} m/s so that the case check accounts for it)",
                    speed(p, i),
                    step / self.spacing,
                    MAX_STEP_DISPLACEMENT * self.spacing / speed(p, i),
                    speed(p, i)
                ),
            ));
        }
        None
    }
}

impl StabilityMonitor {
    /// Whether `r` lies inside a wall: more than half a spacing beyond the tank's faces, i.e.
    /// behind the centres of the walls' first layer, or inside a wall block; the message says
    /// which and where. Every face of a wall gets that half spacing, the top face of an open
    /// tank's walls too: a splash particle resting on a wall's top sits there, as one resting on
    /// the floor sits half a spacing above the floor's first layer. Beyond the walls' outer faces
    /// an open tank's fluid has passed over the walls ([`OpenTop::has_left`]), not into them.
    /// A lidded tank's walls run from the floor up to the tank's top (its lid is checked by the
    /// domain).
    fn inside_wall(&self, r: [f64; 3]) -> Option<String> {
        let h = 0.5 * self.spacing;
        let in_wall_height = if self.open_top.open {
            let within_outer_faces = (0..2).all(|a| r[a] >= self.domain.lo[a] && r[a] <= self.domain.hi[a]);
            r[2] < self.tank.max[2] - h && within_outer_faces
        } else {
            r[2] <= self.tank.max[2]
        };
        let outside = (0..2).any(|a| r[a] < self.tank.min[a] - h || r[a] > self.tank.max[a] + h)
            || r[2] < self.tank.min[2] - h;
        if outside && in_wall_height {
            return Some(format!(
                "inside a wall: r = {r:?} is more than half a spacing beyond the tank faces {:?} … {:?}",
                self.tank.min, self.tank.max
            ));
        }
        if self.solid_sites.deep_inside(r) {
            return Some(format!(
                "inside a solid from a mesh or a terrain: r = {r:?} is more than half a spacing inside its sites"
            ));
        }
        self.solids
            .iter()
            .find(|b| b.contains_point(r))
            .map(|b| format!("inside a wall block {:?} … {:?}: r = {r:?}", b.min, b.max))
    }

    /// Checks fluid against the mesh solids' and terrains' sites too.
    pub fn with_solid_sites(mut self, sites: Arc<SolidSites>) -> Self {
        self.solid_sites = sites;
        self
    }

    /// The mesh solids' and terrains' sites fluid is checked against.
    pub fn solid_sites(&self) -> &SolidSites {
        &self.solid_sites
    }

    /// The wall blocks fluid is checked against: the case's (on the lattice) less half a spacing.
    pub fn wall_boxes(&self) -> &[Aabb] {
        &self.solids
    }

    /// The bodies' insides fluid is checked against, in the order of the bodies.
    pub fn body_interiors(&self) -> &[BodyInterior] {
        &self.bodies
    }

    /// Whether `r` lies inside a body at its present pose; the message says which and where.
    fn inside_body(&self, r: [f64; 3], body_pose: &[f64]) -> Option<String> {
        self.bodies.iter().enumerate().find_map(|(b, inside)| {
            let pose: [f64; 7] = body_pose.get(7 * b..7 * b + 7)?.try_into().ok()?;
            let local = body_frame(r, pose);
            inside.holds(local).then(|| {
                format!(
                    "inside body {b} (centre {:?}, quaternion {:?}): r = {r:?} is at {local:?} in the body's frame, {}",
                    &pose[..3],
                    &pose[3..],
                    inside.rule()
                )
            })
        })
    }
}

fn speed(p: &Particles, i: usize) -> f64 {
    (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]).sqrt()
}
