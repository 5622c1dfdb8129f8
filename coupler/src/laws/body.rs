//! `[[coupling.body]]`: a resolved rigid body, its particles in a fluid participant and its
//! dynamics in a structure participant. The fluid's `body_force` goes to the structure; the
//! structure's `body_pose` and `body_velocity` go to the fluid, which reports the reaction it
//! took in `body_reaction`.

use super::reference::{item_ref, Item, ItemRef};
use super::{sum_vectors, trapezoid_work, work_rounding, Instant, Law, LawEnergy};
use crate::error::CouplerError;
use schemas::case::coupling::BodyLink;
use schemas::message::{Fields, InterfaceDecl};
use schemas::F64s;

#[derive(Debug, Clone)]
struct Transfer {
    fluid: ItemRef,
    structure: ItemRef,
}

/// Every coupled body of a case; writes `body_force`, `body_pose` and `body_velocity`.
pub struct Bodies {
    transfers: Vec<Transfer>,
    /// Declared bodies of each participant.
    bodies: Vec<usize>,
}

impl Bodies {
    /// Binds the case's body links to the declared bodies.
    pub fn bind(
        links: &[BodyLink],
        names: &[String],
        decls: &[InterfaceDecl],
    ) -> Result<Bodies, CouplerError> {
        let transfers = links
            .iter()
            .map(|b| {
                Ok(Transfer {
                    fluid: item_ref(names, decls, &b.fluid, Item::Body)?,
                    structure: item_ref(names, decls, &b.structure, Item::Body)?,
                })
            })
            .collect::<Result<_, CouplerError>>()?;
        Ok(Bodies {
            transfers,
            bodies: decls.iter().map(|d| d.bodies.len()).collect(),
        })
    }
}

impl Law for Bodies {
    fn add_inputs(&self, p: usize, at: Instant, inputs: &mut Fields) {
        let count = self.bodies[p];
        for b in &self.transfers {
            if b.structure.participant == p {
                if inputs.body_force.is_empty() {
                    inputs.body_force = F64s::zeros(6 * count);
                }
                let (f, s) = (b.fluid.index, b.structure.index);
                let from = &at.current[b.fluid.participant].body_force[6 * f..6 * f + 6];
                inputs.body_force[6 * s..6 * s + 6].copy_from_slice(from);
            }
            if b.fluid.participant == p {
                if inputs.body_pose.is_empty() {
                    inputs.body_pose = F64s::zeros(7 * count);
                    inputs.body_velocity = F64s::zeros(6 * count);
                }
                let from = at.current[b.structure.participant];
                let (s, f) = (b.structure.index, b.fluid.index);
                inputs.body_pose[7 * f..7 * f + 7].copy_from_slice(&from.body_pose[7 * s..7 * s + 7]);
                inputs.body_velocity[6 * f..6 * f + 6].copy_from_slice(&from.body_velocity[6 * s..6 * s + 6]);
            }
        }
    }

    fn check_outputs(&self, p: usize, outputs: &Fields) -> Result<(), String> {
        let bodies = self.bodies[p];
        let fluid = self.transfers.iter().any(|b| b.fluid.participant == p);
        let structure = self.transfers.iter().any(|b| b.structure.participant == p);
        let sizes = [
            (fluid, "body_force", outputs.body_force.len(), 6 * bodies),
            (structure, "body_pose", outputs.body_pose.len(), 7 * bodies),
            (
                structure,
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
        Ok(())
    }

    /// The structure: the body forces handed to it; the fluid: the reactions it reports taking.
    fn force_given(&self, _p: usize, inputs: &Fields, outputs: &Fields) -> [f64; 3] {
        let given = sum_vectors(&inputs.body_force, 6, 0);
        let taken = sum_vectors(&outputs.body_reaction, 6, 0);
        [given[0] + taken[0], given[1] + taken[1], given[2] + taken[2]]
    }

    fn window_work(&self, _p: usize, inputs: &[Fields], outputs: &[Fields]) -> f64 {
        let f: Vec<&[f64]> = inputs.iter().map(|i| &i.body_force[..]).collect();
        let x: Vec<&[f64]> = outputs.iter().map(|o| &o.body_pose[..]).collect();
        trapezoid_work(&f, &x, 6, 7)
    }

    /// The structure: work of `body_force` (force and moment) along the pose it reports; the
    /// fluid: work of the reaction it reports (`body_reaction`) along the pose it was handed.
    fn window_energy(&self, _times: &[f64], inputs: &[Vec<Fields>], outputs: &[Vec<Fields>]) -> LawEnergy {
        let mut work = vec![0.0; inputs.len()];
        let mut rounding = 0.0;
        for b in &self.transfers {
            let (s, f) = (b.structure.participant, b.fluid.participant);
            let (si, fi) = (b.structure.index, b.fluid.index);
            let on_structure: Vec<(&[f64], &[f64])> = inputs[s]
                .iter()
                .zip(&outputs[s])
                .filter_map(|(i, o)| {
                    Some((
                        i.body_force.get(6 * si..6 * si + 6)?,
                        o.body_pose.get(7 * si..7 * si + 7)?,
                    ))
                })
                .collect();
            let on_fluid: Vec<(&[f64], &[f64])> = outputs[f]
                .iter()
                .zip(&inputs[f])
                .filter_map(|(o, i)| {
                    Some((
                        o.body_reaction.get(6 * fi..6 * fi + 6)?,
                        i.body_pose.get(7 * fi..7 * fi + 7)?,
                    ))
                })
                .collect();
            work[s] += rigid_work(&on_structure);
            work[f] += rigid_work(&on_fluid);
            rounding += [on_structure, on_fluid]
                .iter()
                .map(|samples| {
                    let (f, x): (Vec<&[f64]>, Vec<&[f64]>) = samples.iter().copied().unzip();
                    work_rounding(&f, &x, 6, 7)
                })
                .sum::<f64>();
        }
        LawEnergy {
            work,
            stored: [0.0; 2],
            rounding,
            exchanged: 0.0,
        }
    }
}

/// Work of a force and moment (6, about the centre) along poses (centre, quaternion w x y z)
/// over a window's samples, trapezoidal: Σ_j ½ (F_j + F_{j+1}) · Δc_j + ½ (M_j + M_{j+1}) · Δθ_j,
/// with Δθ_j the rotation vector from q_j to q_{j+1}.
fn rigid_work(samples: &[(&[f64], &[f64])]) -> f64 {
    samples
        .windows(2)
        .map(|pair| {
            let ((f0, p0), (f1, p1)) = (pair[0], pair[1]);
            let turn = rotation_vector([p0[3], p0[4], p0[5], p0[6]], [p1[3], p1[4], p1[5], p1[6]]);
            (0..3)
                .map(|c| 0.5 * (f0[c] + f1[c]) * (p1[c] - p0[c]) + 0.5 * (f0[c + 3] + f1[c + 3]) * turn[c])
                .sum::<f64>()
        })
        .sum()
}

/// Rotation vector (axis × angle, global axes) of the turn from unit quaternion `q0` to `q1`
/// (w x y z): Δq = q1 q0*.
fn rotation_vector(q0: [f64; 4], q1: [f64; 4]) -> [f64; 3] {
    let [a, b, c, d] = q1;
    let [e, f, g, h] = [q0[0], -q0[1], -q0[2], -q0[3]];
    let w = a * e - b * f - c * g - d * h;
    let v = [
        a * f + b * e + c * h - d * g,
        a * g - b * h + c * e + d * f,
        a * h + b * g - c * f + d * e,
    ];
    let (w, v) = if w < 0.0 { (-w, v.map(|x| -x)) } else { (w, v) };
    let norm = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if norm == 0.0 {
        return [0.0; 3];
    }
    let angle = 2.0 * norm.atan2(w);
    v.map(|x| x / norm * angle)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quarter_turn_about_z_is_its_rotation_vector() {
        let h = std::f64::consts::FRAC_PI_4;
        let r = rotation_vector([1.0, 0.0, 0.0, 0.0], [h.cos(), 0.0, 0.0, h.sin()]);
        assert!(
            (r[2] - 2.0 * h).abs() < 1e-15 && r[0] == 0.0 && r[1] == 0.0,
            "{r:?}"
        );
        // from a turned start: the turn between them, not the absolute one
        let q0 = [h.cos(), h.sin(), 0.0, 0.0];
        let (c, s) = (h.cos(), h.sin());
        let q1 = [c * c, s * c, s * s, s * c]; // a quarter turn about z after q0

        let r = rotation_vector(q0, q1);
        assert!(
            r[0].abs() < 1e-15 && r[1].abs() < 1e-15 && (r[2] - 2.0 * h).abs() < 1e-14,
            "{r:?}"
        );
    }
}
