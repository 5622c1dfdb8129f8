//! `[[coupling.body]]`: a resolved rigid body, its particles in a fluid participant and its
//! dynamics in a structure participant. The fluid's `body_force` goes to the structure; the
//! structure's `body_pose` and `body_velocity` go to the fluid, which reports the reaction it
//! took in `body_reaction`.

use super::reference::{item_ref, Item, ItemRef};
use super::{sum_vectors, trapezoid_work, Instant, Law};
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
}
