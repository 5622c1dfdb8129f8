//! `[[coupling.drag]]`: unresolved drag and buoyancy on beam members thinner than a fluid
//! particle (S2 §4, docs/physics.md §6).
//!
//! At each instant: every member of the structure's geometry is cut into sub-members
//! ([`sub_members`]); each sub-member's sample point sits one member width upstream of its
//! centroid, upstream being against the flow direction its last accepted window sampled (or the
//! case's `initial_flow`). The fluid answers the velocity and λ_min there; the law turns them
//! into drag (S2-19, with the fluid velocity relative to the member), submerged length (S2-20),
//! buoyancy (S2-21) and optional axial drag (S2 §6, same C_D), shares each sub-member's force
//! between its member's nodes (S2-22, S2-23) and hands the exact opposite force to the fluid as
//! a reaction at the centroid with the member's width, which the fluid spreads by S2-24 (over
//! the member's footprint when it is wider than a particle). Buoyancy's reaction goes
//! to the fluid too (the member pushes the water it displaces down), so the pair balances.
//!
//! Lag: the forces at an instant use the samples the fluid returned for that instant in the
//! outputs the sweep started from — in explicit coupling those of the last window's end, in
//! implicit coupling the iterate, which converges to the same instant's samples. Before the
//! fluid has answered any sample point (the first window of an explicit run) the force is zero.

pub mod coefficient;
pub mod force;
pub mod sub_members;

use super::reference::participant_index;
use super::{sum_vectors, trapezoid_work, work_rounding, Instant, Law, LawEnergy};
use crate::error::CouplerError;
use coefficient::{attack_angle, projected_width, DragTable};
use nalgebra::Vector3;
use schemas::case::drag::{DragLink, KERNEL_SUPPORT_IN_SPACINGS};
use schemas::case::Case;
use schemas::message::{Fields, Geometry, InterfaceDecl};
use schemas::F64s;
use sub_members::SubMember;

/// A flow direction is taken from a wet sample (λ_min ≥ S2-20's λ^surface, the samples that
/// carry a force) only if its speed relative to the member exceeds this [m/s]; a dry sample says
/// nothing about the flow, and the member's own motion in air (its sway under gravity) is not a
/// flow and must not turn the sample point.
const DIRECTION_MIN_SPEED: f64 = 1e-9;

/// The settings of one drag link, resolved against the case.
#[derive(Debug, Clone)]
pub struct DragSettings {
    /// Fluid density ρ [kg/m³].
    pub density: f64,
    /// Gravity vector g [m/s²] (S2-21).
    pub gravity: [f64; 3],
    /// Sub-member length d [m] (S2 §4(1)c).
    pub sub_member_length: f64,
    /// Drag width D and buoyancy area D² of every member instead of its section's.
    pub width: Option<f64>,
    pub initial_flow: Option<[f64; 3]>,
    pub section_axis: Option<[f64; 3]>,
    pub axial_drag: bool,
    pub drag_coefficient: Vec<[f64; 2]>,
}

impl DragSettings {
    /// The settings of `link` in `case` (validated: the fluid exists).
    pub fn from_case(case: &Case, link: &DragLink) -> Result<DragSettings, CouplerError> {
        let fluid = case.fluid.get(&link.fluid).ok_or_else(|| {
            CouplerError::Usage(format!(
                "coupling.drag: `{}` is not a fluid participant",
                link.fluid
            ))
        })?;
        Ok(DragSettings {
            density: fluid.density,
            gravity: fluid.gravity,
            sub_member_length: link.sub_member_length.unwrap_or(fluid.spacing),
            width: link.width,
            initial_flow: link.initial_flow,
            section_axis: link.section_axis,
            axial_drag: link.axial_drag,
            drag_coefficient: link.drag_coefficient.clone(),
        })
    }
}

/// One sub-member's share at one instant.
#[derive(Debug, Clone, Copy)]
pub struct SubMemberLoad {
    /// Where the fluid is sampled.
    pub sample_point: Vector3<f64>,
    /// Centroid, where the reaction acts on the fluid.
    pub centroid: Vector3<f64>,
    /// Force of the fluid on the sub-member: drag (+ axial drag) + buoyancy [N].
    pub force: Vector3<f64>,
    /// The two nodes and their shares of `force` (S2-22, S2-23).
    pub nodes: [usize; 2],
    pub node_forces: [Vector3<f64>; 2],
}

/// The drag law between fluid participant `fluid` and structure participant `structure`.
pub struct Drag {
    fluid: usize,
    structure: usize,
    nodes: usize,
    settings: DragSettings,
    table: DragTable,
    section_axis: Option<Vector3<f64>>,
    pieces: Vec<SubMember>,
    /// Unit flow direction at each sub-member, from the last accepted window (None: unknown).
    directions: Vec<Option<Vector3<f64>>>,
    /// Support radius of the kernel that spreads a reaction on the fluid (S2-24), when bound to a case.
    reaction_support: Option<f64>,
}

impl Drag {
    /// Binds `link` of `case` to the running participants.
    pub fn bind(
        case: &Case,
        link: &DragLink,
        names: &[String],
        decls: &[InterfaceDecl],
    ) -> Result<Drag, CouplerError> {
        let fluid = participant_index(names, &link.fluid, &link.fluid)?;
        let structure = participant_index(names, &link.structure, &link.structure)?;
        let nodes = decls[structure].frame_nodes as usize;
        let mut law = Drag::new(DragSettings::from_case(case, link)?, fluid, structure, nodes);
        law.reaction_support = case
            .fluid
            .get(&link.fluid)
            .map(|f| KERNEL_SUPPORT_IN_SPACINGS * f.spacing);
        Ok(law)
    }

    /// A law for a structure of `nodes` frame nodes, before any geometry is known.
    pub fn new(settings: DragSettings, fluid: usize, structure: usize, nodes: usize) -> Drag {
        Drag {
            fluid,
            structure,
            nodes,
            table: DragTable::new(&settings.drag_coefficient),
            section_axis: settings.section_axis.map(Vector3::from),
            settings,
            pieces: Vec::new(),
            directions: Vec::new(),
            reaction_support: None,
        }
    }

    /// The sub-members, as cut from the last geometry.
    pub fn sub_members(&self) -> &[SubMember] {
        &self.pieces
    }

    /// Cuts a (new) geometry with the node positions `positions` (3 per node); every flow
    /// direction starts again from the case's `initial_flow`.
    pub fn set_geometry(&mut self, geometry: &Geometry, positions: &[f64]) -> Result<(), String> {
        let first = self.pieces.is_empty();
        self.pieces = sub_members::cut(geometry, positions, self.settings.sub_member_length)?;
        if let Some(w) = self.settings.width {
            for s in &mut self.pieces {
                (s.width, s.area) = (w, w * w);
            }
        }
        let initial = self.settings.initial_flow.map(|v| Vector3::from(v).normalize());
        self.directions = vec![initial; self.pieces.len()];
        if first {
            self.warn_if_too_wide();
        }
        Ok(())
    }

    /// A `warning: ` line (at the first geometry) when a member is wider than the radius of the
    /// kernel that spreads a reaction on the fluid (S2-24; `fluid-solver/src/unresolved/spreading.rs`).
    /// The fluid spreads such a member's reaction over the water in its footprint (a sphere of
    /// radius (D − Δs)/2 around each sub-member's centroid, plus the kernel's tail), so its drag
    /// no longer lands on the few particles near its axis (at Δs = 5 mm the 0.05 m prism of
    /// `cases/prism-dam-break`, 4 radii wide, was stopped by the detector at 0.21 s before it
    /// did; it now runs to the end). That keeps the run stable; it does not make the drag law
    /// right for the member: the flow around a member this wide is resolved by the particles, and
    /// a quasi-steady drag from the flow one width upstream is not its force.
    fn warn_if_too_wide(&self) {
        let (Some(support), Some(widest)) = (
            self.reaction_support,
            self.pieces.iter().map(|p| p.width).max_by(f64::total_cmp),
        ) else {
            return;
        };
        if widest > support {
            crate::say!(
                "warning: coupling.drag: a member {widest} m wide is {:.1} times the radius {support:.4} m of the \
                 kernel that spreads its reaction on the fluid (S2-24: {} particle spacings). The fluid spreads \
                 it over the water in the member's footprint, so the drag does not throw out the particles \
                 near its axis; but the unresolved law is for members thinner than a particle: the flow \
                 around a member this wide is resolved by the particles, and its drag from the flow one \
                 width upstream is not its force (cases/prism-dam-break, 0.05 m at 5 mm: 0.71 of the \
                 resolved prism's impulse to 0.3 s, 0.41 of its peak). Resolve members this wide as \
                 bodies, or coarsen the fluid",
                widest / support,
                KERNEL_SUPPORT_IN_SPACINGS
            );
        }
    }

    /// Every sub-member's sample point, centroid and force at one instant, from the structure's
    /// outputs `structure` and the fluid's `fluid` (its samples at the points of this law).
    pub fn evaluate(&self, structure: &Fields, fluid: &Fields) -> Vec<SubMemberLoad> {
        let x = &structure.node_position;
        let v = &structure.node_velocity;
        let count = self.pieces.len();
        let sampled = fluid.sampled_velocity.len() == 3 * count && fluid.sampled_lambda_min.len() == count;
        let rho = self.settings.density;
        let g = Vector3::from(self.settings.gravity);
        self.pieces
            .iter()
            .zip(&self.directions)
            .enumerate()
            .map(|(i, (s, dir))| {
                let [a, b] = s.nodes;
                let (xa, xb) = (vec3(x, 3 * a), vec3(x, 3 * b));
                let (n1, n2) = (0.5 * (1.0 - s.xi), 0.5 * (1.0 + s.xi));
                let centroid = xa * n1 + xb * n2;
                let span = xb - xa;
                let length = span.norm();
                let sample_point = match dir {
                    Some(d) => centroid - d * s.width,
                    None => centroid,
                };
                let mut force = Vector3::zeros();
                let l = if sampled && length > 0.0 {
                    force::submerged_length(fluid.sampled_lambda_min[i], s.fraction * length)
                } else {
                    0.0
                };
                // dry (l = 0): every term below is 0, none is evaluated
                if l > 0.0 {
                    let axis = span / length;
                    let member_velocity = if v.len() >= 6 * self.nodes {
                        vec3(v, 6 * a) * n1 + vec3(v, 6 * b) * n2
                    } else {
                        Vector3::zeros()
                    };
                    let v_rel = vec3(&fluid.sampled_velocity, 3 * i) - member_velocity;
                    let (across, along) = force::split(&v_rel, &axis);
                    let alpha = attack_angle(&across, &axis, self.section_axis.as_ref());
                    let cd = self.table.at(alpha);
                    force += force::drag(cd, rho, &across, projected_width(s.width, alpha), l);
                    if self.settings.axial_drag {
                        force += force::drag(cd, rho, &along, s.width, l);
                    }
                    force += force::buoyancy(rho, &g, s.area, l);
                }
                SubMemberLoad {
                    sample_point,
                    centroid,
                    force,
                    nodes: s.nodes,
                    node_forces: force::to_nodes(s.xi, &force),
                }
            })
            .collect()
    }
}

/// The 3-vector at `values[at..at + 3]` (zero where the array is short).
fn vec3(values: &[f64], at: usize) -> Vector3<f64> {
    values
        .get(at..at + 3)
        .map_or_else(Vector3::zeros, |s| Vector3::new(s[0], s[1], s[2]))
}

impl Law for Drag {
    fn add_inputs(&self, p: usize, at: Instant, inputs: &mut Fields) {
        if p != self.fluid && p != self.structure {
            return;
        }
        let loads = self.evaluate(at.start[self.structure], at.start[self.fluid]);
        if p == self.structure {
            let mut f = F64s::zeros(6 * self.nodes);
            for load in &loads {
                for (node, nf) in load.nodes.iter().zip(&load.node_forces) {
                    (0..3).for_each(|c| f[6 * node + c] += nf[c]);
                }
            }
            inputs.node_force = f;
        }
        if p == self.fluid {
            inputs.sample_point = F64s(
                loads
                    .iter()
                    .flat_map(|l| l.sample_point.iter().copied())
                    .collect(),
            );
            inputs.reaction = F64s(
                loads
                    .iter()
                    .flat_map(|l| l.centroid.iter().copied().chain(l.force.iter().map(|f| -f)))
                    .collect(),
            );
            // the fluid spreads a wide member's reaction over its footprint
            inputs.reaction_width = F64s(self.pieces.iter().map(|s| s.width).collect());
        }
    }

    /// The structure's node arrays must hold the same nodes (3 and 6 values per node) and at
    /// least the nodes declared so far: a fracture adds nodes within a window, and the law takes
    /// them on when the structure re-declares its geometry at the window's end
    /// ([`Law::geometry`]).
    fn check_outputs(&self, p: usize, outputs: &Fields) -> Result<(), String> {
        if p == self.structure {
            let (positions, velocities) = (outputs.node_position.len(), outputs.node_velocity.len());
            let n = positions / 3;
            if positions % 3 != 0 || velocities != 6 * n {
                return Err(format!(
                    "node_position has {positions} values and node_velocity {velocities}; 3 and 6 per frame node are needed"
                ));
            }
            if n < self.nodes {
                return Err(format!(
                    "node_position has {positions} values; the {} declared frame nodes need {} (a frame may gain nodes by fracture, never lose them)",
                    self.nodes,
                    3 * self.nodes
                ));
            }
        }
        if p == self.fluid && outputs.sampled_velocity.len() != 3 * outputs.sampled_lambda_min.len() {
            return Err(format!(
                "sampled_velocity has {} values for {} values of sampled_lambda_min; 3 per sample point are needed",
                outputs.sampled_velocity.len(),
                outputs.sampled_lambda_min.len()
            ));
        }
        Ok(())
    }

    /// The structure: the node forces handed to it; the fluid: the point reactions.
    fn force_given(&self, p: usize, inputs: &Fields, _outputs: &Fields) -> [f64; 3] {
        if p == self.structure {
            sum_vectors(&inputs.node_force, 6, 0)
        } else if p == self.fluid {
            sum_vectors(&inputs.reaction, 6, 3)
        } else {
            [0.0; 3]
        }
    }

    /// Work of the node forces along the node positions (the fluid's side is not known here).
    fn window_work(&self, p: usize, inputs: &[Fields], outputs: &[Fields]) -> f64 {
        if p != self.structure {
            return 0.0;
        }
        let f: Vec<&[f64]> = inputs.iter().map(|i| &i.node_force[..]).collect();
        let x: Vec<&[f64]> = outputs.iter().map(|o| &o.node_position[..]).collect();
        trapezoid_work(&f, &x, 6, 3)
    }

    /// The structure: work of the node forces along the node positions; the fluid: work of the
    /// point reactions −f at the velocity the fluid reports at their sample points,
    /// Σ_j ½ (P_j + P_{j+1}) Δt_j with P_j = Σ_i (−f_i)·v_i. Drag dissipates: the two sum to
    /// −Σ f·(v_fluid − v_member) Δt ≤ 0 for the drag part. Buoyancy's reaction does work on
    /// water moving up or down past the member (the falling column of a dam break with a member
    /// standing in it: +3e-8 J a window against a stiff member's 1e-14 J), which the sums count
    /// as created; the scale it is judged against is the energy the forces exchange with the flow
    /// whatever its sign, `exchanged` = Σ_j ½ (Q_j + Q_{j+1}) Δt_j with Q_j = Σ_i |f_i| |v_i|,
    /// which bounds that work and does not grow with the member's own motion.
    fn window_energy(&self, times: &[f64], inputs: &[Vec<Fields>], outputs: &[Vec<Fields>]) -> LawEnergy {
        let mut work = vec![0.0; inputs.len()];
        work[self.structure] =
            self.window_work(self.structure, &inputs[self.structure], &outputs[self.structure]);
        let norm = |v: &[f64]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let (power, magnitude): (Vec<f64>, Vec<f64>) = inputs[self.fluid]
            .iter()
            .zip(&outputs[self.fluid])
            .map(|(i, o)| {
                i.reaction
                    .chunks_exact(6)
                    .zip(o.sampled_velocity.chunks_exact(3))
                    .map(|(r, v)| (r[3] * v[0] + r[4] * v[1] + r[5] * v[2], norm(&r[3..6]) * norm(v)))
                    .fold((0.0, 0.0), |(p, q), (a, b)| (p + a, q + b))
            })
            .unzip();
        let trapezoid = |values: &[f64]| {
            values
                .windows(2)
                .zip(times.windows(2))
                .map(|(p, t)| 0.5 * (p[0] + p[1]) * (t[1] - t[0]))
                .sum::<f64>()
        };
        work[self.fluid] += trapezoid(&power);
        let f: Vec<&[f64]> = inputs[self.structure].iter().map(|i| &i.node_force[..]).collect();
        let x: Vec<&[f64]> = outputs[self.structure]
            .iter()
            .map(|o| &o.node_position[..])
            .collect();
        LawEnergy {
            work,
            stored: [0.0; 2],
            rounding: work_rounding(&f, &x, 6, 3),
            exchanged: trapezoid(&magnitude),
        }
    }

    /// The structure's `node_velocity` enters only as the member's velocity subtracted from the
    /// sampled flow velocity (S2-19 with the relative velocity): its scale is the flow's, the
    /// RMS of `sampled_velocity` over the window's samples after its start. A stiff member's own
    /// vibration (1e-4 m/s against 1 m/s of flow) changes the drag by 1e-4 and must not decide
    /// the iteration.
    fn field_scale(&self, p: usize, field: &str, outputs: &[Vec<Fields>]) -> f64 {
        if p != self.structure || field != "node_velocity" {
            return 0.0;
        }
        let values: Vec<f64> = outputs[self.fluid]
            .iter()
            .skip(1)
            .flat_map(|o| o.sampled_velocity.iter().copied())
            .collect();
        if values.is_empty() {
            return 0.0;
        }
        (values.iter().map(|v| v * v).sum::<f64>() / values.len() as f64).sqrt()
    }

    /// A (re-)declared geometry: at the start, and at the end of a window in which a fracture
    /// split an element (new node, new connectivity). The node count becomes that of the
    /// structure's outputs, and the sub-members are cut again; the fluid's samples at the old
    /// sample points no longer match the new cut and are completed dry ([`Law::complete_outputs`]),
    /// so the next window's first sweep gives no force: an explicit window without drag; an
    /// implicit window's later sweeps have the fluid's answer at the new points.
    fn geometry(&mut self, p: usize, geometry: &Geometry, outputs: &Fields) -> Result<(), String> {
        if p == self.structure {
            self.set_geometry(geometry, &outputs.node_position)?;
            self.nodes = outputs.node_position.len() / 3;
        }
        Ok(())
    }

    /// The fluid has no sample point before its first window, nor at the new sample points of a
    /// re-cut geometry: its samples start dry (velocity 0, λ_min 0, so no force at t = 0 and for
    /// the first sweep after a fracture; an implicit window's later sweeps have the fluid's answer).
    fn complete_outputs(&self, p: usize, outputs: &mut Fields) {
        if p == self.fluid
            && (outputs.sampled_lambda_min.len() != self.pieces.len()
                || outputs.sampled_velocity.len() != 3 * self.pieces.len())
        {
            outputs.sampled_velocity = F64s::zeros(3 * self.pieces.len());
            outputs.sampled_lambda_min = F64s::zeros(self.pieces.len());
        }
    }

    /// Each sub-member's flow direction becomes that of the velocity relative to the member
    /// sampled at the window's end where the sample is wet (kept where it is wet but still); a
    /// dry sample returns it to the case's `initial_flow` (none: the centroid is sampled). A
    /// direction kept at a dry sample locked the wide prism's sample points in its dry wake: at
    /// Δs = 5 mm the water the 0.05 m prism reflected turned them downstream at 0.19 s, and the
    /// prism took no drag for the rest of the run (`cases/prism-dam-break/README.md`).
    fn accept(&mut self, outputs: &[Vec<Fields>]) {
        let (Some(s), Some(f)) = (outputs[self.structure].last(), outputs[self.fluid].last()) else {
            return;
        };
        if f.sampled_velocity.len() != 3 * self.pieces.len() {
            return;
        }
        let initial = self.settings.initial_flow.map(|v| Vector3::from(v).normalize());
        for (i, (piece, dir)) in self.pieces.iter().zip(&mut self.directions).enumerate() {
            let [a, b] = piece.nodes;
            let member = vec3(&s.node_velocity, 6 * a) * (0.5 * (1.0 - piece.xi))
                + vec3(&s.node_velocity, 6 * b) * (0.5 * (1.0 + piece.xi));
            let v = vec3(&f.sampled_velocity, 3 * i) - member;
            if f.sampled_lambda_min[i] < force::LAMBDA_SURFACE {
                *dir = initial;
            } else if v.norm() > DIRECTION_MIN_SPEED {
                *dir = Some(v.normalize());
            }
        }
    }

    /// The sub-members (cut with the positions of when the geometry was declared, which a resumed
    /// run does not have) and their flow directions.
    fn save(&self) -> Vec<u8> {
        let state = (&self.pieces, &self.directions);
        // encoding into a Vec cannot fail
        bincode::serde::encode_to_vec(state, bincode::config::standard()).unwrap_or_default()
    }

    fn restore(&mut self, saved: &[u8]) -> Result<(), String> {
        type Saved = (Vec<SubMember>, Vec<Option<Vector3<f64>>>);
        let ((pieces, directions), _): (Saved, usize) =
            bincode::serde::decode_from_slice(saved, bincode::config::standard())
                .map_err(|e| format!("the drag law's state does not read back: {e}"))?;
        if pieces.len() != directions.len() || pieces.iter().any(|p| p.nodes.iter().any(|&n| n >= self.nodes))
        {
            return Err("the drag law's state does not fit the structure's frame".into());
        }
        (self.pieces, self.directions) = (pieces, directions);
        Ok(())
    }
}
