//! The interface of a run: the case's laws ([`crate::laws`]) bound to the participants'
//! declared interfaces, evaluated at each instant into every participant's inputs.
//!
//! Each law gives `+f` to one side and `−f` to the other, so action equals reaction by
//! construction; the ledger ([`crate::ledger`]) reads from the laws what each side got and checks
//! it every window.

use crate::error::CouplerError;
use crate::laws::body::Bodies;
use crate::laws::drag::Drag;
use crate::laws::spring::Springs;
use crate::laws::{Instant, Law, LawEnergy};
use schemas::case::Case;
use schemas::message::{Fields, Geometry, InterfaceDecl};

/// The interface laws of a case, bound to the participants' declared interfaces.
pub struct Interface {
    names: Vec<String>,
    laws: Vec<Box<dyn Law>>,
}

impl Interface {
    /// Binds the case's laws to the interfaces the participants declared at the handshake.
    pub fn bind(case: &Case, names: &[String], decls: &[InterfaceDecl]) -> Result<Interface, CouplerError> {
        let mut laws: Vec<Box<dyn Law>> = Vec::new();
        if let Some(coupling) = &case.coupling {
            if !coupling.spring.is_empty() {
                laws.push(Box::new(Springs::bind(&coupling.spring, names, decls)?));
            }
            if !coupling.body.is_empty() {
                laws.push(Box::new(Bodies::bind(&coupling.body, names, decls)?));
            }
            for link in &coupling.drag {
                laws.push(Box::new(Drag::bind(case, link, names, decls)?));
            }
        }
        Ok(Interface {
            names: names.to_vec(),
            laws,
        })
    }

    /// What each law keeps across windows ([`Law::save`]), for a checkpoint.
    pub fn save_laws(&self) -> Vec<Vec<u8>> {
        self.laws.iter().map(|l| l.save()).collect()
    }

    /// Puts back what [`Interface::save_laws`] gave.
    pub fn restore_laws(&mut self, saved: &[Vec<u8>]) -> Result<(), String> {
        if saved.len() != self.laws.len() {
            return Err(format!(
                "the checkpoint holds the state of {} interface laws, the case has {}",
                saved.len(),
                self.laws.len()
            ));
        }
        self.laws
            .iter_mut()
            .zip(saved)
            .try_for_each(|(law, s)| law.restore(s))
    }

    /// Inputs of participant `p` at one instant. Two-sided laws read `start`, the outputs as
    /// they stood when the sweep began, so both ends get the same `±f`; one-way transfers read
    /// `current`, which holds the fresh outputs of the participants already advanced in this sweep.
    pub fn inputs(&self, p: usize, start: &[&Fields], current: &[&Fields]) -> Fields {
        let mut inputs = Fields::default();
        let at = Instant { start, current };
        for law in &self.laws {
            law.add_inputs(p, at, &mut inputs);
        }
        inputs
    }

    /// Checks that participant `p`'s outputs hold every array the laws read, at the declared
    /// sizes, and only finite values.
    pub fn check_outputs(&self, p: usize, outputs: &Fields) -> Result<(), String> {
        for law in &self.laws {
            law.check_outputs(p, outputs)?;
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

    /// The force participant `p` took across the interface at one instant, as the laws report
    /// it (3 components).
    pub fn force_taken(&self, p: usize, inputs: &Fields, outputs: &Fields) -> [f64; 3] {
        let mut sum = [0.0; 3];
        for law in &self.laws {
            let f = law.force_given(p, inputs, outputs);
            (0..3).for_each(|c| sum[c] += f[c]);
        }
        sum
    }

    /// Work done on participant `p` over a window by the laws' forces.
    pub fn window_work(&self, p: usize, inputs: &[Fields], outputs: &[Fields]) -> f64 {
        self.laws
            .iter()
            .map(|law| law.window_work(p, inputs, outputs))
            .sum()
    }

    /// The energy account of one window over every law (see [`Law::window_energy`]).
    pub fn window_energy(&self, times: &[f64], inputs: &[Vec<Fields>], outputs: &[Vec<Fields>]) -> LawEnergy {
        let mut sum = LawEnergy {
            work: vec![0.0; self.names.len()],
            ..LawEnergy::default()
        };
        for law in &self.laws {
            let e = law.window_energy(times, inputs, outputs);
            sum.work.iter_mut().zip(&e.work).for_each(|(s, w)| *s += w);
            (0..2).for_each(|k| sum.stored[k] += e.stored[k]);
            sum.rounding += e.rounding;
            sum.exchanged += e.exchanged;
        }
        sum
    }

    /// The largest magnitude any law compares participant `p`'s output `field` with (see
    /// [`Law::field_scale`]); 0 where none sets one.
    pub fn field_scale(&self, p: usize, field: &str, outputs: &[Vec<Fields>]) -> f64 {
        self.laws
            .iter()
            .map(|law| law.field_scale(p, field, outputs))
            .fold(0.0, f64::max)
    }

    /// Participant `p` declared a (new) member geometry; `outputs` are its outputs as it did.
    pub fn geometry(&mut self, p: usize, geometry: &Geometry, outputs: &Fields) -> Result<(), CouplerError> {
        for law in &mut self.laws {
            law.geometry(p, geometry, outputs)
                .map_err(|message| CouplerError::Participant {
                    name: self.names[p].clone(),
                    window: None,
                    message: format!("its geometry: {message}"),
                })?;
        }
        Ok(())
    }

    /// Completes participant `p`'s outputs with what the laws read but `p` cannot give yet:
    /// before its first window, and after a re-declared geometry (see [`Law::complete_outputs`]).
    pub fn complete_outputs(&self, p: usize, outputs: &mut Fields) {
        for law in &self.laws {
            law.complete_outputs(p, outputs);
        }
    }

    /// A window was accepted with these outputs: the laws update what they keep across windows.
    pub fn accept(&mut self, outputs: &[Vec<Fields>]) {
        for law in &mut self.laws {
            law.accept(outputs);
        }
    }

    /// Participant names, in serial order.
    pub fn names(&self) -> &[String] {
        &self.names
    }
}
