//! `[[coupling.spring]]`: a linear spring between point masses of two participants,
//! `f_a = k (u_b − u_a)`, `f_b = −f_a` (u: displacements of the points).

use super::reference::{item_ref, Item, ItemRef};
use super::{sum_vectors, trapezoid_work, work_rounding, Instant, Law, LawEnergy};
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

    /// ½ k |u_b − u_a|² summed over the springs, from the outputs `at` one instant.
    fn stored(&self, at: &[&Fields]) -> f64 {
        self.springs
            .iter()
            .map(|s| {
                let ua = at[s.a.participant]
                    .point_displacement
                    .get(3 * s.a.index..3 * s.a.index + 3);
                let ub = at[s.b.participant]
                    .point_displacement
                    .get(3 * s.b.index..3 * s.b.index + 3);
                match (ua, ub) {
                    (Some(ua), Some(ub)) => {
                        0.5 * s.stiffness * (0..3).map(|c| (ub[c] - ua[c]).powi(2)).sum::<f64>()
                    }
                    _ => 0.0,
                }
            })
            .sum()
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

    /// Work of `point_force` along each side's displacements, and the springs' ½ k d² at the
    /// window's start and end.
    fn window_energy(&self, _times: &[f64], inputs: &[Vec<Fields>], outputs: &[Vec<Fields>]) -> LawEnergy {
        let work = (0..inputs.len())
            .map(|p| {
                if self.touches(p) {
                    self.window_work(p, &inputs[p], &outputs[p])
                } else {
                    0.0
                }
            })
            .collect();
        let rounding = (0..inputs.len())
            .filter(|&p| self.touches(p))
            .map(|p| {
                let f: Vec<&[f64]> = inputs[p].iter().map(|i| &i.point_force[..]).collect();
                let x: Vec<&[f64]> = outputs[p].iter().map(|o| &o.point_displacement[..]).collect();
                work_rounding(&f, &x, 3, 3)
            })
            .sum();
        let first: Vec<&Fields> = outputs.iter().filter_map(|o| o.first()).collect();
        let last: Vec<&Fields> = outputs.iter().filter_map(|o| o.last()).collect();
        if first.len() != outputs.len() || last.len() != outputs.len() {
            return LawEnergy {
                work,
                stored: [0.0; 2],
                rounding,
                exchanged: 0.0,
            };
        }
        LawEnergy {
            work,
            stored: [self.stored(&first), self.stored(&last)],
            rounding,
            exchanged: 0.0,
        }
    }
}
