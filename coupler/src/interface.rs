//! Interface laws: from every participant's outputs at one instant to each participant's inputs.
//!
//! Each law is evaluated once per instant and gives `+f` to one side and `−f` to the other, so
//! action equals reaction by construction; the ledger ([`crate::ledger`]) checks it every window.

use crate::error::CouplerError;
use schemas::case::Case;
use schemas::message::{Fields, InterfaceDecl};
use schemas::F64s;

/// A point of a participant: (participant index, point index).
#[derive(Debug, Clone, Copy)]
struct PointRef {
    participant: usize,
    point: usize,
}

/// `[[coupling.spring]]`: `f_a = k (u_b − u_a)`, `f_b = −f_a`.
#[derive(Debug, Clone)]
struct Spring {
    a: PointRef,
    b: PointRef,
    stiffness: f64,
}

/// `[[coupling.body]]`: a body's force goes from the fluid to the structure, its pose and
/// velocity from the structure to the fluid.
#[derive(Debug, Clone)]
struct BodyTransfer {
    fluid: PointRef,
    structure: PointRef,
}

/// The interface laws of a case, bound to the participants' declared interfaces.
pub struct Interface {
    names: Vec<String>,
    decls: Vec<InterfaceDecl>,
    springs: Vec<Spring>,
    bodies: Vec<BodyTransfer>,
}

impl Interface {
    /// Binds the case's laws to the interfaces the participants declared at the handshake.
    pub fn bind(case: &Case, names: &[String], decls: &[InterfaceDecl]) -> Result<Interface, CouplerError> {
        let mut springs = Vec::new();
        let mut bodies = Vec::new();
        if let Some(coupling) = &case.coupling {
            for s in &coupling.spring {
                springs.push(Spring {
                    a: item_ref(names, decls, &s.a, Item::Point)?,
                    b: item_ref(names, decls, &s.b, Item::Point)?,
                    stiffness: s.stiffness,
                });
            }
            for b in &coupling.body {
                bodies.push(BodyTransfer {
                    fluid: item_ref(names, decls, &b.fluid, Item::Body)?,
                    structure: item_ref(names, decls, &b.structure, Item::Body)?,
                });
            }
        }
        Ok(Interface {
            names: names.to_vec(),
            decls: decls.to_vec(),
            springs,
            bodies,
        })
    }

    /// Inputs of participant `p` at one instant. Two-sided laws (springs) read `start`, the
    /// outputs as they stood when the sweep began, so both ends get the same `±f`; one-way
    /// transfers (bodies) read `current`, which holds the fresh outputs of the participants
    /// already advanced in this sweep.
    pub fn inputs(&self, p: usize, start: &[&Fields], current: &[&Fields]) -> Fields {
        let mut inputs = self.spring_inputs(p, start);
        let count = self.decls[p].bodies.len();
        for b in &self.bodies {
            if b.structure.participant == p {
                if inputs.body_force.is_empty() {
                    inputs.body_force = F64s::zeros(6 * count);
                }
                let f = &current[b.fluid.participant].body_force[6 * b.fluid.point..6 * b.fluid.point + 6];
                inputs.body_force[6 * b.structure.point..6 * b.structure.point + 6].copy_from_slice(f);
            }
            if b.fluid.participant == p {
                if inputs.body_pose.is_empty() {
                    inputs.body_pose = F64s::zeros(7 * count);
                    inputs.body_velocity = F64s::zeros(6 * count);
                }
                let from = current[b.structure.participant];
                let (s, f) = (b.structure.point, b.fluid.point);
                inputs.body_pose[7 * f..7 * f + 7].copy_from_slice(&from.body_pose[7 * s..7 * s + 7]);
                inputs.body_velocity[6 * f..6 * f + 6].copy_from_slice(&from.body_velocity[6 * s..6 * s + 6]);
            }
        }
        inputs
    }

    /// Point forces of participant `p` from the coupling springs: `f_a = k (u_b − u_a)`, `f_b = −f_a`.
    fn spring_inputs(&self, p: usize, outputs: &[&Fields]) -> Fields {
        let mut inputs = Fields::default();
        let points = self.decls[p].points.len();
        if self
            .springs
            .iter()
            .any(|s| s.a.participant == p || s.b.participant == p)
        {
            inputs.point_force = F64s::zeros(3 * points);
        }
        for s in &self.springs {
            let ua = &outputs[s.a.participant].point_displacement[3 * s.a.point..3 * s.a.point + 3];
            let ub = &outputs[s.b.participant].point_displacement[3 * s.b.point..3 * s.b.point + 3];
            for c in 0..3 {
                let f = s.stiffness * (ub[c] - ua[c]);
                if s.a.participant == p {
                    inputs.point_force[3 * s.a.point + c] += f;
                }
                if s.b.participant == p {
                    inputs.point_force[3 * s.b.point + c] -= f;
                }
            }
        }
        inputs
    }

    /// Checks that participant `p`'s outputs hold every array the laws read, at the declared sizes.
    pub fn check_outputs(&self, p: usize, outputs: &Fields) -> Result<(), String> {
        let decl = &self.decls[p];
        let reads_points = self
            .springs
            .iter()
            .any(|s| s.a.participant == p || s.b.participant == p);
        if reads_points && outputs.point_displacement.len() != 3 * decl.points.len() {
            return Err(format!(
                "point_displacement has {} values; {} declared points need {}",
                outputs.point_displacement.len(),
                decl.points.len(),
                3 * decl.points.len()
            ));
        }
        let bodies = decl.bodies.len();
        let sizes = [
            (
                self.bodies.iter().any(|b| b.fluid.participant == p),
                "body_force",
                outputs.body_force.len(),
                6 * bodies,
            ),
            (
                self.bodies.iter().any(|b| b.structure.participant == p),
                "body_pose",
                outputs.body_pose.len(),
                7 * bodies,
            ),
            (
                self.bodies.iter().any(|b| b.structure.participant == p),
                "body_velocity",
                outputs.body_velocity.len(),
                6 * bodies,
            ),
        ];
        for (read, name, len, wanted) in sizes {
            if read && len != wanted {
                return Err(format!(
                    "{name} has {len} values; {bodies} declared bodies need {wanted}"
                ));
            }
        }
        if let Some((name, _)) = outputs
            .arrays()
            .into_iter()
            .find(|(_, a)| a.iter().any(|v| !v.is_finite()))
        {
            return Err(format!(
                "`{name}` holds a non-finite value (NaN or infinity): the solver went unstable"
            ));
        }
        Ok(())
    }

    /// Participant names, in serial order.
    pub fn names(&self) -> &[String] {
        &self.names
    }
}

/// What a `participant/name` reference of the case names.
#[derive(Clone, Copy)]
enum Item {
    Point,
    Body,
}

/// Finds `participant/name` among the running participants and what they declared.
fn item_ref(
    names: &[String],
    decls: &[InterfaceDecl],
    text: &str,
    item: Item,
) -> Result<PointRef, CouplerError> {
    let (participant, name) = text.split_once('/').unwrap_or((text, ""));
    let p = names.iter().position(|n| n == participant).ok_or_else(|| {
        CouplerError::Usage(format!(
            "coupling reference `{text}`: no participant `{participant}` is running"
        ))
    })?;
    let (declared, what) = match item {
        Item::Point => (&decls[p].points, "points"),
        Item::Body => (&decls[p].bodies, "bodies"),
    };
    let i = declared
        .iter()
        .position(|n| n == name)
        .ok_or_else(|| CouplerError::Participant {
            name: participant.to_string(),
            window: None,
            message: format!("declared {what} {declared:?} at the handshake, but the case couples `{name}`"),
        })?;
    Ok(PointRef {
        participant: p,
        point: i,
    })
}

/// The force a participant took across the interface: the forces handed to it (point, body and
/// node forces, point reactions) plus the body reactions it reports taking itself (3 components).
pub fn force_taken(inputs: &Fields, outputs: &Fields) -> [f64; 3] {
    let given = force_sum(inputs);
    let mut reaction = [0.0; 3];
    for chunk in outputs.body_reaction.chunks_exact(6) {
        (0..3).for_each(|c| reaction[c] += chunk[c]);
    }
    [
        given[0] + reaction[0],
        given[1] + reaction[1],
        given[2] + reaction[2],
    ]
}

/// Sum of the force vectors in a participant's inputs: point forces, body forces,
/// node forces and point reactions (3 components).
fn force_sum(inputs: &Fields) -> [f64; 3] {
    let mut sum = [0.0; 3];
    let mut add = |values: &[f64], stride: usize, offset: usize| {
        for chunk in values.chunks_exact(stride) {
            for c in 0..3 {
                sum[c] += chunk[offset + c];
            }
        }
    };
    add(&inputs.point_force, 3, 0);
    add(&inputs.body_force, 6, 0);
    add(&inputs.node_force, 6, 0);
    add(&inputs.reaction, 6, 3);
    sum
}

/// Work done on a participant over a window by its point and body forces:
/// Σ ½ (f_j + f_{j+1}) · (x_{j+1} − x_j) over the samples (trapezoidal rule).
pub fn window_work(inputs: &[Fields], outputs: &[Fields]) -> f64 {
    let mut work = 0.0;
    for j in 0..inputs.len().saturating_sub(1) {
        let pairs = [
            (
                &inputs[j].point_force,
                &inputs[j + 1].point_force,
                &outputs[j].point_displacement,
                &outputs[j + 1].point_displacement,
                3,
                3,
            ),
            (
                &inputs[j].body_force,
                &inputs[j + 1].body_force,
                &outputs[j].body_pose,
                &outputs[j + 1].body_pose,
                6,
                7,
            ),
        ];
        for (f0, f1, x0, x1, fs, xs) in pairs {
            for (k, (a, b)) in f0.chunks_exact(fs).zip(f1.chunks_exact(fs)).enumerate() {
                let (Some(p0), Some(p1)) = (x0.get(k * xs..k * xs + 3), x1.get(k * xs..k * xs + 3)) else {
                    continue;
                };
                work += (0..3).map(|c| 0.5 * (a[c] + b[c]) * (p1[c] - p0[c])).sum::<f64>();
            }
        }
    }
    work
}
