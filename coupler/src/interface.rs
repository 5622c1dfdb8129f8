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

/// The interface laws of a case, bound to the participants' declared interfaces.
pub struct Interface {
    names: Vec<String>,
    decls: Vec<InterfaceDecl>,
    springs: Vec<Spring>,
}

impl Interface {
    /// Binds the case's laws to the interfaces the participants declared at the handshake.
    pub fn bind(case: &Case, names: &[String], decls: &[InterfaceDecl]) -> Result<Interface, CouplerError> {
        let mut springs = Vec::new();
        if let Some(coupling) = &case.coupling {
            for s in &coupling.spring {
                springs.push(Spring {
                    a: point_ref(names, decls, &s.a)?,
                    b: point_ref(names, decls, &s.b)?,
                    stiffness: s.stiffness,
                });
            }
        }
        Ok(Interface { names: names.to_vec(), decls: decls.to_vec(), springs })
    }

    /// Inputs of participant `p` given every participant's outputs at one instant.
    pub fn inputs(&self, p: usize, outputs: &[&Fields]) -> Fields {
        let mut inputs = Fields::default();
        let points = self.decls[p].points.len();
        if self.springs.iter().any(|s| s.a.participant == p || s.b.participant == p) {
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
        let reads_points = self.springs.iter().any(|s| s.a.participant == p || s.b.participant == p);
        if reads_points && outputs.point_displacement.len() != 3 * decl.points.len() {
            return Err(format!(
                "point_displacement has {} values; {} declared points need {}",
                outputs.point_displacement.len(),
                decl.points.len(),
                3 * decl.points.len()
            ));
        }
        if let Some((name, _)) = outputs.arrays().into_iter().find(|(_, a)| a.iter().any(|v| !v.is_finite())) {
            return Err(format!("`{name}` holds a non-finite value (NaN or infinity): the solver went unstable"));
        }
        Ok(())
    }

    /// Participant names, in serial order.
    pub fn names(&self) -> &[String] {
        &self.names
    }
}

fn point_ref(names: &[String], decls: &[InterfaceDecl], text: &str) -> Result<PointRef, CouplerError> {
    let (participant, point) = text.split_once('/').unwrap_or((text, ""));
    let p = names.iter().position(|n| n == participant).ok_or_else(|| {
        CouplerError::Usage(format!("coupling spring end `{text}`: no participant `{participant}` is running"))
    })?;
    let i = decls[p].points.iter().position(|n| n == point).ok_or_else(|| CouplerError::Participant {
        name: participant.to_string(),
        window: None,
        message: format!(
            "declared points {:?} at the handshake, but the coupling spring needs `{point}`",
            decls[p].points
        ),
    })?;
    Ok(PointRef { participant: p, point: i })
}

/// Sum of the force vectors in a participant's inputs: point forces, body forces,
/// node forces and point reactions (3 components).
pub fn force_sum(inputs: &Fields) -> [f64; 3] {
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
            (&inputs[j].point_force, &inputs[j + 1].point_force, &outputs[j].point_displacement, &outputs[j + 1].point_displacement, 3, 3),
            (&inputs[j].body_force, &inputs[j + 1].body_force, &outputs[j].body_pose, &outputs[j + 1].body_pose, 6, 7),
        ];
        for (f0, f1, x0, x1, fs, xs) in pairs {
            for (k, (a, b)) in f0.chunks_exact(fs).zip(f1.chunks_exact(fs)).enumerate() {
                let (Some(p0), Some(p1)) = (x0.get(k * xs..k * xs + 3), x1.get(k * xs..k * xs + 3)) else { continue };
                work += (0..3).map(|c| 0.5 * (a[c] + b[c]) * (p1[c] - p0[c])).sum::<f64>();
            }
        }
    }
    work
}
