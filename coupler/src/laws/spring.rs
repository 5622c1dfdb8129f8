//! `[[coupling.spring]]`: a linear spring between point masses of two participants,
//! `f_a = k (u_b − u_a)`, `f_b = −f_a` (u: displacements of the points).

use super::reference::{item_ref, Item, ItemRef};
use super::{sum_vectors, trapezoid_work, Instant, Law};
use crate::error::CouplerError;
use schemas::case::coupling::SpringLink;
use schemas::message::{Fields, InterfaceDecl};
use schemas::F64s;

#[derive(Debug, Clone)]
struct Spring {
    a: ItemRef,
    b: ItemRef,
    stiffness: f64,
}

/// Every coupling spring of a case; writes `point_force`.
pub struct Springs {
    springs: Vec<Spring>,
    /// Declared points of each participant.
    points: Vec<usize>,
}

impl Springs {
    /// Binds the case's springs to the declared points.
    pub fn bind(
        links: &[SpringLink],
        names: &[String],
        decls: &[InterfaceDecl],
    ) -> Result<Springs, CouplerError> {
        let springs = links
            .iter()
            .map(|s| {
                Ok(Spring {
                    a: item_ref(names, decls, &s.a, Item::Point)?,
                    b: item_ref(names, decls, &s.b, Item::Point)?,
                    stiffness: s.stiffness,
                })
            })
            .collect::<Result<_, CouplerError>>()?;
        Ok(Springs {
            springs,
            points: decls.iter().map(|d| d.points.len()).collect(),
        })
    }

    fn touches(&self, p: usize) -> bool {
        self.springs
            .iter()
            .any(|s| s.a.participant == p || s.b.participant == p)
    }
}

impl Law for Springs {
    fn add_inputs(&self, p: usize, at: Instant, inputs: &mut Fields) {
        if !self.touches(p) {
            return;
        }
        inputs.point_force = F64s::zeros(3 * self.points[p]);
        for s in &self.springs {
            let ua = &at.start[s.a.participant].point_displacement[3 * s.a.index..3 * s.a.index + 3];
            let ub = &at.start[s.b.participant].point_displacement[3 * s.b.index..3 * s.b.index + 3];
            for c in 0..3 {
                let f = s.stiffness * (ub[c] - ua[c]);
                if s.a.participant == p {
                    inputs.point_force[3 * s.a.index + c] += f;
                }
                if s.b.participant == p {
                    inputs.point_force[3 * s.b.index + c] -= f;
                }
            }
        }
    }

    fn check_outputs(&self, p: usize, outputs: &Fields) -> Result<(), String> {
        let points = self.points[p];
        if self.touches(p) && outputs.point_displacement.len() != 3 * points {
            return Err(format!(
                "point_displacement has {} values; {points} declared points need {}",
                outputs.point_displacement.len(),
                3 * points
            ));
        }
        Ok(())
    }

    fn force_given(&self, _p: usize, inputs: &Fields, _outputs: &Fields) -> [f64; 3] {
        sum_vectors(&inputs.point_force, 3, 0)
    }

    fn window_work(&self, _p: usize, inputs: &[Fields], outputs: &[Fields]) -> f64 {
        let f: Vec<&[f64]> = inputs.iter().map(|i| &i.point_force[..]).collect();
        let x: Vec<&[f64]> = outputs.iter().map(|o| &o.point_displacement[..]).collect();
        trapezoid_work(&f, &x, 3, 3)
    }
}
