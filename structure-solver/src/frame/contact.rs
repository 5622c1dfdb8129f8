//! Contact between members and with walls (S2 §3(2)): each element is represented by particles along
//! its axis (radius: half the section's larger side, spacing about one diameter); overlapping
//! particles of elements that share no node, and particles that cross a wall, are pushed apart by a
//! penalty spring and dashpot. Towards a wall a particle is the short cylinder of the element it
//! stands for (its share of the element's length, radius the particle's): it reaches
//! `ℓ/2 |t·n| + r √(1 − (t·n)²)` past its centre (t the element's axis, n the wall's normal), the
//! radius for a member lying on the wall, half its share of the length for one standing on it end
//! first, so that a short piece standing on a wall rests on its end node instead of one radius
//! above it. The forces are taken at the start of each step (explicit), so the
//! penalty stiffness must stay below the mass of the lightest particle over Δt².
//!
//! # A member standing on a wall
//!
//! A wall does not push on the particles of an element that is *held on it*: one of the element's
//! nodes is a support fixed along the wall's normal and lies on the wall or behind it (at most one
//! particle radius in front of it). A column standing on the channel floor, a pier founded on the
//! seabed, a member pinned to a bearing on a wall: their first element touches the wall at t = 0,
//! and any shortening under their own weight would let the wall push that element off the wall
//! against its own support — an axial load the support takes back and the model does not mean.
//! Before this rule (and with spherical particles of radius half the section's larger side, which
//! put the prism of `cases/prism-washout` half a radius inside the floor) that load yielded a weak
//! foot and made it ratchet to 50 % axial strain. The support already keeps that element on the
//! wall. As soon as the element lets go of the support — a fracture gives it a new node — the wall
//! acts on it again, so a piece broken off the foot, or a deck resting on bearings without being
//! tied to them, lands and stays on the wall; the piece broken off standing starts touching the wall
//! with its end (the cylinder's reach above), not half a radius inside it, which would throw it off.
//! The rule reads the present topology, not the state at t = 0: a rule "a particle that starts
//! inside a wall never touches it" would let the broken foot fall through the floor. A member
//! modelled below the wall beyond its supported element (a pile driven through the seabed) is still
//! pushed: model it from the wall up.
//!
//! Member contact likewise skips elements that are joined or were joined before a fracture split
//! their node ([`adjacent`]): neighbours overlap near their common node.

use super::section::Section;
use super::topology::{Element, Node};
use nalgebra::Vector3;
use schemas::case::frame::{ContactConfig, WallConfig};
use std::collections::HashMap;

/// Contact parameters and walls of a frame.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Contact {
    stiffness: f64,
    damping_ratio: f64,
    members: bool,
    /// Point and unit normal of each wall.
    walls: Vec<(Vector3<f64>, Vector3<f64>)>,
}

/// A contact particle: where it is on which element.
struct Particle {
    element: usize,
    /// Position along the element, 0 at its first node, 1 at its second.
    t: f64,
    position: Vector3<f64>,
    velocity: Vector3<f64>,
    radius: f64,
    /// The element's unit axis (its chord now).
    axis: Vector3<f64>,
    /// Half the particle's share of the element's length (now).
    half_length: f64,
    mass: f64,
}

impl Particle {
    /// How far the particle's cylinder reaches past its centre along a wall's normal.
    fn reach(&self, normal: &Vector3<f64>) -> f64 {
        let c = self.axis.dot(normal).abs().min(1.0);
        self.half_length * c + self.radius * (1.0 - c * c).sqrt()
    }
}

impl Contact {
    pub fn new(cfg: &ContactConfig, walls: &[WallConfig]) -> Contact {
        Contact {
            stiffness: cfg.stiffness,
            damping_ratio: cfg.damping_ratio,
            members: cfg.members,
            walls: walls
                .iter()
                .map(|w| (Vector3::from(w.point), Vector3::from(w.normal).normalize()))
                .collect(),
        }
    }

    /// Largest stable penalty stiffness for a time step: the lightest particle's mass over Δt².
    pub fn stiffness_limit(elements: &[Element], sections: &[Section], density: f64, dt: f64) -> f64 {
        elements
            .iter()
            .map(|e| {
                let section = &sections[e.section];
                let count = particle_count(e.length0, section.contact_radius);
                density * section.area * e.length0 / count as f64 / (dt * dt)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Contact forces, 6 per node (moments zero), at the given state.
    pub fn forces(
        &self,
        nodes: &[Node],
        elements: &[Element],
        sections: &[Section],
        density: f64,
    ) -> Vec<f64> {
        let particles = particles(nodes, elements, sections, density);
        let mut forces = vec![0.0; nodes.len() * 6];
        let mut push = |p: &Particle, f: Vector3<f64>| {
            let [a, b] = elements[p.element].nodes;
            for k in 0..3 {
                forces[6 * a + k] += (1.0 - p.t) * f[k];
                forces[6 * b + k] += p.t * f[k];
            }
        };
        for p in &particles {
            for (point, normal) in &self.walls {
                if held_on_wall(&elements[p.element], nodes, point, normal, p.radius) {
                    continue;
                }
                let gap = (p.position - point).dot(normal) - p.reach(normal);
                if gap < 0.0 {
                    let magnitude = self.normal_force(-gap, p.velocity.dot(normal), p.mass);
                    push(p, normal * magnitude);
                }
            }
        }
        if self.members {
            for (i, j) in touching_pairs(&particles, elements, nodes) {
                let (pi, pj) = (&particles[i], &particles[j]);
                let d = pj.position - pi.position;
                let distance = d.norm();
                let overlap = pi.radius + pj.radius - distance;
                if overlap > 0.0 && distance > 0.0 {
                    let n = d / distance;
                    let reduced = pi.mass * pj.mass / (pi.mass + pj.mass);
                    let magnitude = self.normal_force(overlap, (pj.velocity - pi.velocity).dot(&n), reduced);
                    push(pi, -n * magnitude);
                    push(pj, n * magnitude);
                }
            }
        }
        forces
    }

    /// Stops a run in which a member went through a wall (a particle's centre more than its reach
    /// behind it).
    pub fn check_walls(
        &self,
        nodes: &[Node],
        elements: &[Element],
        sections: &[Section],
    ) -> Result<(), String> {
        for p in particles(nodes, elements, sections, 0.0) {
            for (w, (point, normal)) in self.walls.iter().enumerate() {
                if held_on_wall(&elements[p.element], nodes, point, normal, p.radius) {
                    continue;
                }
                let depth = -(p.position - point).dot(normal);
                if depth > p.reach(normal) {
                    return Err(format!(
                        "frame: element {} went through wall {w} ({depth:.3e} m behind it): the run is unstable; \
                         raise the contact stiffness or reduce the time step",
                        p.element
                    ));
                }
            }
        }
        Ok(())
    }

    /// Repulsive normal force `k δ − c v_n` (never pulling), `c = 2 ζ √(k m)`.
    fn normal_force(&self, overlap: f64, approach_velocity: f64, mass: f64) -> f64 {
        let c = 2.0 * self.damping_ratio * (self.stiffness * mass).sqrt();
        (self.stiffness * overlap - c * approach_velocity).max(0.0)
    }
}

/// Whether `element` is held on a wall by a support: one of its nodes fixed along the wall's normal
/// (every translation the normal has a component along is fixed) and at most `radius` in front of
/// the wall (on it, or behind it).
fn held_on_wall(
    element: &Element,
    nodes: &[Node],
    point: &Vector3<f64>,
    normal: &Vector3<f64>,
    radius: f64,
) -> bool {
    element.nodes.iter().any(|&n| {
        let node = &nodes[n];
        let held = (0..3).all(|k| node.fixed[k] || normal[k].abs() < 1e-12);
        held && (node.position - point).dot(normal) <= radius
    })
}

/// Particles per element: about one per diameter, at least one.
fn particle_count(length: f64, radius: f64) -> usize {
    ((length / (2.0 * radius)).ceil() as usize).max(1)
}

fn particles(nodes: &[Node], elements: &[Element], sections: &[Section], density: f64) -> Vec<Particle> {
    let mut out = Vec::new();
    for (i, e) in elements.iter().enumerate() {
        let section = &sections[e.section];
        let radius = section.contact_radius;
        let count = particle_count(e.length0, radius);
        let [a, b] = e.nodes.map(|n| &nodes[n]);
        let (va, vb) = (
            Vector3::from_column_slice(&a.velocity[..3]),
            Vector3::from_column_slice(&b.velocity[..3]),
        );
        let mass = density * section.area * e.length0 / count as f64;
        let chord = b.position - a.position;
        let length = chord.norm();
        let axis = if length > 0.0 {
            chord / length
        } else {
            Vector3::zeros()
        };
        let half_length = 0.5 * length / count as f64;
        for k in 0..count {
            let t = (k as f64 + 0.5) / count as f64;
            out.push(Particle {
                element: i,
                t,
                position: a.position * (1.0 - t) + b.position * t,
                velocity: va * (1.0 - t) + vb * t,
                radius,
                axis,
                half_length,
                mass,
            });
        }
    }
    out
}

/// Whether two elements are joined, or were joined before a fracture split their common node: a
/// node made by fracture keeps the initial position of the node it was split from. Neighbours
/// always overlap near their common node (their particles are closer than two radii), so they do
/// not touch each other, nor do they once a fracture separated them: the pieces would otherwise be
/// thrown apart by the overlap they had while joined (250 N for the prism of `prism-washout`).
fn adjacent(a: &Element, b: &Element, nodes: &[Node]) -> bool {
    a.nodes.iter().any(|&n| {
        b.nodes
            .iter()
            .any(|&m| n == m || nodes[n].initial == nodes[m].initial)
    })
}

/// Pairs of particles closer than the sum of the largest radii, on elements that are not
/// [`adjacent`], found with a cell list.
fn touching_pairs(particles: &[Particle], elements: &[Element], nodes: &[Node]) -> Vec<(usize, usize)> {
    let reach = 2.0 * particles.iter().map(|p| p.radius).fold(0.0, f64::max);
    if reach <= 0.0 {
        return Vec::new();
    }
    let cell = |x: &Vector3<f64>| [0, 1, 2].map(|k| (x[k] / reach).floor() as i64);
    let mut cells: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, p) in particles.iter().enumerate() {
        cells.entry(cell(&p.position)).or_default().push(i);
    }
    let mut pairs = Vec::new();
    for (i, p) in particles.iter().enumerate() {
        let c = cell(&p.position);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(list) = cells.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else {
                        continue;
                    };
                    for &j in list {
                        if j <= i {
                            continue;
                        }
                        let (ei, ej) = (&elements[p.element], &elements[particles[j].element]);
                        if (particles[j].position - p.position).norm() < reach && !adjacent(ei, ej, nodes) {
                            pairs.push((i, j));
                        }
                    }
                }
            }
        }
    }
    pairs
}
