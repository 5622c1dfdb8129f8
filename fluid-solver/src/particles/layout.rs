//! The initial particle layout of a case: tank walls, water blocks, gates and bodies on one
//! simple cubic lattice of spacing Δs.
//!
//! Lattice sites are `tank.min + (i + ½) Δs`; the tank's inner faces lie half a spacing from the
//! nearest sites. Sites outside the tank within `wall_layers` layers are walls: the two layers
//! next to the tank are [`Kind::Wall`] (they carry pressure), the outer ones [`Kind::Dummy`].
//! Sites inside the tank whose centre is inside a gate, a body (its box or its mesh,
//! [`BodySites`]), a solid wall box or a water block (raised by an initial wave, whose water moves
//! with it) get that kind; so do the skins of mesh solids and terrains ([`SolidSites`]), and the wave
//! maker's paddle, whose particles come last. Boxes and the tank are first moved onto the lattice ([`crate::particles::lattice`]); the
//! layout keeps that config and the messages saying what moved.

use crate::particles::body_sites::BodySites;
use crate::particles::kind::Kind;
use crate::particles::solid_sites::SolidSites;
use crate::particles::Particles;
use schemas::case::fluid::{Aabb, FluidConfig};

/// Wall layers that carry pressure: a fluid particle half a spacing off the wall reaches
/// r_e,grad = 2.1 Δs, i.e. wall centres 0.5 Δs and 1.5 Δs deep.
pub const PRESSURE_LAYERS: i64 = 2;

/// Headroom above an open tank, in tank heights, before a particle counts as gone.
pub const SPLASH_HEADROOM: f64 = 4.0;

/// The cell grid covers one tank height above an open tank; particles higher up are spray and
/// are kept in the top cell layer (their distances stay exact, only the search does more work).
pub const GRID_HEADROOM: f64 = 1.0;

/// The box particles must stay in: the walls' outer faces, and above an open tank a headroom
/// of [`SPLASH_HEADROOM`] tank heights (jets in the corners of the seed's tank rise at 4 m/s,
/// i.e. 0.8 m, above a 0.3 m tank).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Domain {
    pub lo: [f64; 3],
    pub hi: [f64; 3],
}

/// The particles of one rigid body, by particle id.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyParticles {
    pub name: String,
    pub ids: Vec<u32>,
}

/// The wave maker's paddle in the layout: its particles are pushed last.
#[derive(Debug, Clone, PartialEq)]
pub struct PaddleParticles {
    /// Id of the first paddle particle; the paddle's ids follow it without gaps.
    pub first: u32,
    /// Each paddle particle's x at rest, in id order.
    pub rest_x: Vec<f64>,
    /// Each paddle particle's z at rest, in id order (a flap turns them in the x–z plane).
    pub rest_z: Vec<f64>,
}

/// The initial state built from a case section.
#[derive(Debug, Clone)]
pub struct Layout {
    pub particles: Particles,
    pub domain: Domain,
    /// The box the cell grid covers.
    pub grid_box: Domain,
    pub tank: Aabb,
    pub bodies: Vec<BodyParticles>,
    /// The wave maker's paddle, when the case has one.
    pub paddle: Option<PaddleParticles>,
    /// The sites of the mesh solids and terrains.
    pub solid_sites: SolidSites,
    /// Which sites each body took (a box's or a mesh's).
    pub body_sites: BodySites,
    /// The case's section with the tank and every box on the lattice (what was built).
    pub config: FluidConfig,
    /// One message per box that was moved onto the lattice.
    pub notes: Vec<String>,
}

/// Builds the lattice layout of `cfg` (already validated).
pub fn build(cfg: &FluidConfig) -> Layout {
    let (config, notes) = crate::particles::lattice::snap(cfg);
    let cfg = &config;
    let ds = cfg.spacing;
    let tank = cfg.tank.inner();
    let layers = i64::from(cfg.wall_layers);
    let n: [i64; 3] = std::array::from_fn(|a| ((tank.max[a] - tank.min[a]) / ds).round() as i64);
    let top = if cfg.tank.lid { n[2] + layers } else { n[2] };
    let mut particles = Particles::default();
    let mut bodies: Vec<BodyParticles> = cfg
        .body
        .iter()
        .map(|b| BodyParticles {
            name: b.name.clone(),
            ids: Vec::new(),
        })
        .collect();
    let paddle_box = cfg.wave_maker.as_ref().map(|w| w.paddle());
    let in_paddle = |p: [f64; 3]| paddle_box.is_some_and(|b| b.contains_point(p));
    let mut paddle_sites = Vec::new();
    let wave = cfg.initial_wave.as_ref().map(|w| {
        let sign = w.sign().expect("the initial wave's direction was validated");
        let wave = w
            .wave(cfg.gravity_magnitude())
            .expect("the initial wave was validated");
        (wave, sign)
    });
    let solids = SolidSites::build(cfg, n);
    let body_sites = BodySites::build(cfg, n);
    for k in -layers..top {
        for j in -layers..n[1] + layers {
            for i in -layers..n[0] + layers {
                let idx = [i, j, k];
                let p: [f64; 3] = std::array::from_fn(|a| tank.min[a] + (idx[a] as f64 + 0.5) * ds);
                let depth = (0..3)
                    .map(|a| (-idx[a]).max(idx[a] - n[a] + 1))
                    .max()
                    .unwrap_or(0);
                if depth > 0 {
                    let kind = if depth <= PRESSURE_LAYERS {
                        Kind::Wall
                    } else {
                        Kind::Dummy
                    };
                    particles.push(p, kind);
                } else if in_paddle(p) {
                    paddle_sites.push(p);
                } else if cfg.gate.iter().any(|g| g.contains_point(p)) {
                    particles.push(p, Kind::Gate);
                } else if let Some(b) = body_sites.body_at(idx, p) {
                    bodies[b].ids.push(particles.len() as u32);
                    particles.push(p, Kind::Body);
                } else if cfg.wall.iter().any(|w| w.contains_point(p)) {
                    // Only sites within r_e,grad of water get a pressure (see `operators`), so
                    // the inside of a solid box costs no more than dummies.
                    particles.push(p, Kind::Wall);
                } else if solids.holds(idx) {
                    particles.push(p, Kind::Wall);
                } else if solids.buries(idx) {
                    // deeper inside a mesh solid or a terrain than its skin: no particle
                } else if cfg.block.iter().any(|b| b.contains_point(p))
                    || wave.is_some_and(|(w, _)| cfg.raised_by_initial_wave(p, &w))
                {
                    let v = wave.map_or([0.0; 3], |(w, sign)| {
                        let [u, w] = w.velocity_at(p[0], p[2] - tank.min[2], 0.0);
                        [sign * u, 0.0, sign * w]
                    });
                    let id = particles.len() as u32;
                    particles.push_moving(p, v, Kind::Fluid, id);
                }
            }
        }
    }
    let paddle = paddle_box.map(|_| PaddleParticles {
        first: particles.len() as u32,
        rest_x: paddle_sites.iter().map(|p| p[0]).collect(),
        rest_z: paddle_sites.iter().map(|p| p[2]).collect(),
    });
    for p in paddle_sites {
        particles.push(p, Kind::Wall);
    }
    particles.shrink_to_fit();
    let l = layers as f64 * ds;
    let height = tank.max[2] - tank.min[2];
    let above = |headroom: f64| Domain {
        lo: std::array::from_fn(|a| tank.min[a] - l),
        hi: [
            tank.max[0] + l,
            tank.max[1] + l,
            tank.max[2] + if cfg.tank.lid { l } else { headroom * height },
        ],
    };
    Layout {
        particles,
        domain: above(SPLASH_HEADROOM),
        grid_box: above(GRID_HEADROOM),
        tank,
        bodies,
        paddle,
        solid_sites: solids,
        body_sites,
        notes,
        config,
    }
}
