//! Coupling windows: serial explicit (one sweep per window) and serial implicit (sweeps from
//! checkpoints until the interface converges, with acceleration).
//!
//! A sweep advances the participants in serial order. Two-sided laws (springs) are evaluated
//! once per sweep, on the estimate of every participant's outputs as it stands when the sweep
//! starts, so each end gets exactly `+f` and `−f` (evaluating a spring again after its first end
//! moved would hand the second end a force that is not the reaction of the first). One-way
//! transfers (a body's force from the fluid to the structure, its motion back) are evaluated when
//! their receiver advances, so the serial order passes fresh data on. The estimate starts from the last window's
//! outputs, held constant or extended linearly (`coupling.predictor`); implicit coupling
//! iterates it to the fixed point.

use crate::acceleration::{self, Accelerator};
use crate::checkpoint::{self, CouplerState, Manifest};
use crate::error::CouplerError;
use crate::interface::Interface;
use crate::ledger::{Ledger, WindowEnd};
use crate::progress::Progress;
use crate::stability::Detector;
use crate::stack::{variant, Stack};
use crate::state;
use schemas::case::coupling::{CouplingConfig, Predictor, Scheme};
use schemas::message::{
    Checkpoint, Fields, FromParticipant, Geometry, Header, ToParticipant, Waveform, PROTOCOL_VERSION,
};

/// What a finished run did.
#[derive(Debug, Clone, Default)]
pub struct Summary {
    pub windows: u64,
    pub iterations: u64,
    pub max_iterations: u32,
    pub worst_balance: f64,
    pub balance_violations: u64,
}

/// Drives the windows of a run.
pub struct Windows<'a> {
    pub stack: &'a mut Stack,
    pub interface: &'a mut Interface,
    pub config: &'a CouplingConfig,
    pub ledger: Ledger,
    pub progress: Progress,
    /// The coupling-instability detector ([`crate::stability`]).
    pub detector: Detector,
    /// Magnitude of each output field so far, the floor of the convergence measure.
    pub reference: state::Magnitudes,
    /// Checkpoints to take (`coupling.checkpoint_interval`), if any.
    pub checkpoints: Option<CheckpointPlan>,
}

/// Where and how often a run takes checkpoints.
pub struct CheckpointPlan {
    /// Windows between two checkpoints.
    pub every: u64,
    /// The run's output folder.
    pub out: std::path::PathBuf,
    /// What the run was started with ([`schemas::case::Case::input_hashes`]).
    pub inputs: Vec<(String, u64)>,
}

/// bincode bytes of `value` (the coupler's checkpoint keeps message types this way).
fn encode<T: bincode::Encode>(value: &T) -> Vec<u8> {
    // encoding into a Vec cannot fail
    bincode::encode_to_vec(value, bincode::config::standard()).unwrap_or_default()
}

fn decode<T: bincode::Decode<()>>(bytes: &[u8], what: &str) -> Result<T, CouplerError> {
    bincode::decode_from_slice(bytes, bincode::config::standard())
        .map(|(v, _)| v)
        .map_err(|e| {
            CouplerError::Usage(format!(
                "--resume: the checkpoint's {what} does not read back: {e}"
            ))
        })
}

/// The number of windows of a run to `end_time` with windows of `window` seconds: the last one
/// ends at `end_time`, shorter than the others when `end_time` is not a whole number of them.
pub fn window_count(end_time: f64, window: f64) -> u64 {
    ((end_time / window) - 1e-9).ceil().max(1.0) as u64
}

/// Whether the last window of a run to `end_time` ends where the same window of a longer run
/// does, exactly (`end_time` is a whole number of windows, and the window ends computed from it
/// equal). A run whose end is then also a checkpoint time takes that checkpoint, from which it
/// can be extended ([`crate::checkpoint`]).
pub fn ends_on_window(end_time: f64, window: f64) -> bool {
    window_count(end_time, window) as f64 * window == end_time
}

impl Windows<'_> {
    /// Runs every window from 0 to `end_time`, starting from the participants' initial outputs.
    pub fn run(self, end_time: f64, initial: Vec<Fields>) -> Result<Summary, CouplerError> {
        let last: Vec<Waveform> = initial
            .into_iter()
            .map(|f| Waveform {
                times: vec![0.0],
                samples: vec![f],
            })
            .collect();
        let accelerator = acceleration::from_config(self.config);
        self.run_from(end_time, 0, last, accelerator, Summary::default())
    }

    /// Runs the windows after a checkpoint to `end_time`, from the coupler's state kept in it.
    pub fn resume(mut self, end_time: f64, state: &CouplerState) -> Result<Summary, CouplerError> {
        let last: Vec<Waveform> = decode(&state.last, "last window")?;
        let geometry: Vec<Option<Geometry>> = decode(&state.geometry, "member geometry")?;
        if last.len() != self.stack.sessions.len() || geometry.len() != last.len() {
            return Err(CouplerError::Usage(format!(
                "--resume: the checkpoint is of {} participants, the case has {}",
                last.len(),
                self.stack.sessions.len()
            )));
        }
        for (p, g) in geometry.into_iter().enumerate() {
            if let (Some(g), Some(outputs)) = (&g, last[p].last()) {
                self.interface.geometry(p, g, outputs)?;
            }
            self.stack.sessions[p].geometry = g;
        }
        self.interface
            .restore_laws(&state.laws)
            .map_err(|e| CouplerError::Usage(format!("--resume: {e}")))?;
        let mut accelerator = acceleration::from_config(self.config);
        accelerator
            .restore(&state.accelerator)
            .map_err(CouplerError::Usage)?;
        self.reference.restore(&state.magnitudes);
        self.ledger.worst_balance = state.worst_balance;
        self.ledger.violations = state.balance_violations;
        self.detector
            .restore(&state.detector)
            .map_err(CouplerError::Usage)?;
        let summary = Summary {
            windows: state.windows,
            iterations: state.iterations,
            max_iterations: state.max_iterations,
            ..Summary::default()
        };
        self.run_from(end_time, state.next_window, last, accelerator, summary)
    }

    fn run_from(
        mut self,
        end_time: f64,
        first: u64,
        mut last: Vec<Waveform>,
        mut accelerator: Box<dyn Accelerator>,
        mut summary: Summary,
    ) -> Result<Summary, CouplerError> {
        let dt = self.config.window;
        let total = window_count(end_time, dt);
        let whole_last_window = ends_on_window(end_time, dt);
        for w in first..total {
            let t0 = w as f64 * dt;
            let t1 = if w + 1 == total {
                end_time
            } else {
                (w + 1) as f64 * dt
            };
            let times = Waveform::grid(t0, t1, self.config.samples);
            let mut estimate: Vec<Vec<Fields>> = last.iter().map(|w| self.predict(w, &times)).collect();
            let geometry_before: Vec<_> = self.stack.sessions.iter().map(|s| s.geometry.clone()).collect();
            let (inputs, iterations, residual) = match self.config.scheme {
                Scheme::Explicit => (self.sweep(w, 0, Checkpoint::None, &times, &mut estimate)?, 1, 0.0),
                Scheme::Implicit => self.implicit(w, &times, &mut estimate, accelerator.as_mut())?,
            };
            let end = WindowEnd {
                window: w,
                time: t1,
                iterations,
                residual,
            };
            self.ledger.window(end, self.interface, &inputs, &estimate)?;
            self.detector
                .window(w, &times, self.interface, &inputs, &estimate)?;
            let mut redeclared = false;
            for (p, session) in self.stack.sessions.iter().enumerate() {
                if session.geometry != geometry_before[p] {
                    if let (Some(g), Some(outputs)) = (&session.geometry, estimate[p].last()) {
                        self.interface.geometry(p, g, outputs)?;
                        redeclared = true;
                    }
                }
            }
            if redeclared {
                // what the laws read and the new geometry changed the shape of starts neutral
                // (e.g. dry samples at new sample points), so the next window keeps one shape
                for (p, samples) in estimate.iter_mut().enumerate() {
                    samples
                        .iter_mut()
                        .for_each(|fields| self.interface.complete_outputs(p, fields));
                }
            }
            self.interface.accept(&estimate);
            self.reference.observe(&estimate);
            last = estimate
                .into_iter()
                .map(|samples| Waveform {
                    times: times.clone(),
                    samples,
                })
                .collect();
            summary.windows += 1;
            summary.iterations += u64::from(iterations);
            summary.max_iterations = summary.max_iterations.max(iterations);
            self.progress.update(t1, end_time, w + 1, total);
            if let Some(plan) = &self.checkpoints {
                // at the end too, when a longer run would take this checkpoint: a run extended
                // from it then does what that run does (checkpoints change a frame's arithmetic)
                if (w + 1) % plan.every == 0 && (w + 1 < total || whole_last_window) {
                    self.write_checkpoint(w, t1, end_time, &last, accelerator.as_ref(), &summary)?;
                }
            }
        }
        self.progress.finish();
        self.detector.finish();
        summary.worst_balance = self.ledger.worst_balance;
        summary.balance_violations = self.ledger.violations;
        Ok(summary)
    }

    /// The checkpoint at the end of window `w` (see [`crate::checkpoint`]) of a run to `end_time`:
    /// every participant's state, then the manifest.
    fn write_checkpoint(
        &mut self,
        w: u64,
        time: f64,
        end_time: f64,
        last: &[Waveform],
        accelerator: &dyn Accelerator,
        summary: &Summary,
    ) -> Result<(), CouplerError> {
        let Some(plan) = &self.checkpoints else {
            return Ok(());
        };
        let out = plan.out.clone();
        let inputs = plan.inputs.clone();
        checkpoint::create_folder(&out)?;
        let names: Vec<String> = self.stack.sessions.iter().map(|s| s.name.clone()).collect();
        for (p, name) in names.iter().enumerate() {
            let path = schemas::checkpoint::file(&out, name, w);
            self.stack.write_checkpoint(p, w, &path)?;
        }
        let geometry: Vec<Option<Geometry>> =
            self.stack.sessions.iter().map(|s| s.geometry.clone()).collect();
        let manifest = Manifest {
            inputs,
            window: w,
            time,
            end_time,
            wall: self.stack.wall_seconds(),
            participants: names,
            coupler: CouplerState {
                next_window: w + 1,
                last: encode(&last.to_vec()),
                geometry: encode(&geometry),
                accelerator: accelerator.save(),
                magnitudes: self.reference.saved(),
                worst_balance: self.ledger.worst_balance,
                balance_violations: self.ledger.violations,
                windows: summary.windows,
                iterations: summary.iterations,
                max_iterations: summary.max_iterations,
                detector: self.detector.save(),
                laws: self.interface.save_laws(),
            },
            files: checkpoint::output_files(&out)?,
        };
        checkpoint::write_manifest(&out, &manifest)
    }

    /// First estimate of a participant's outputs at `times` from its last window `last`; the
    /// window-start sample is the last window's end exactly.
    fn predict(&self, last: &Waveform, times: &[f64]) -> Vec<Fields> {
        let end = last.last().cloned().unwrap_or_default();
        let mut samples = vec![end; times.len()];
        if self.config.predictor == Predictor::Linear {
            for (sample, &t) in samples.iter_mut().zip(times).skip(1) {
                *sample = last.extrapolate(t);
            }
        }
        samples
    }

    /// Repeats the window until every output block's relative residual is below the tolerance.
    ///
    /// A sweep in which a participant re-declares its member geometry (a frame fractured: new
    /// nodes, new connectivity) ends the window, not converged: a fracture is a discrete event
    /// that a fixed-point iteration cannot converge across (a repeated sweep restores the unbroken
    /// structure, which may or may not break again, and every vector of the interface changes
    /// length). The coupler keeps that sweep, as explicit coupling would keep its one sweep; the
    /// geometry is declared to the laws at the window end ([`Windows::run_from`]) and the next
    /// window iterates on the new topology.
    fn implicit(
        &mut self,
        w: u64,
        times: &[f64],
        estimate: &mut [Vec<Fields>],
        accelerator: &mut dyn Accelerator,
    ) -> Result<(Vec<Vec<Fields>>, u32, f64), CouplerError> {
        let mut scales = Vec::new();
        let mut history = Vec::new();
        let start_geometry: Vec<_> = self.stack.sessions.iter().map(|s| s.geometry.clone()).collect();
        for k in 0..self.config.max_iterations {
            if k > 0 {
                // a repeated sweep starts from the window start's geometry, as the participants do
                for (s, g) in self.stack.sessions.iter_mut().zip(&start_geometry) {
                    s.geometry.clone_from(g);
                }
            }
            let (x, blocks) = state::flatten(estimate);
            let checkpoint = if k == 0 {
                Checkpoint::Save
            } else {
                Checkpoint::Restore
            };
            let inputs = self.sweep(w, k, checkpoint, times, estimate)?;
            let changed = self
                .stack
                .sessions
                .iter()
                .zip(&start_geometry)
                .position(|(s, g)| s.geometry != *g);
            if let Some(p) = changed {
                // a topology change ends the window with the sweep that made it
                accelerator.end_window();
                crate::say!(
                    "note: window {w}: {}'s member geometry changed (a fracture) in sweep {}; the window ends with \
                     that sweep, not converged (residual NaN in ledger.csv)",
                    self.stack.sessions[p].name,
                    k + 1
                );
                return Ok((inputs, k + 1, f64::NAN));
            }
            let (h, after) = state::flatten(estimate);
            if h.len() != x.len() || after.len() != blocks.len() {
                return Err(CouplerError::Usage(format!(
                    "window {w}: the participants' outputs changed size within an implicit window ({} → {} values); \
                     use coupling.scheme = \"explicit\" for cases whose interface changes shape",
                    x.len(),
                    h.len()
                )));
            }
            let law_scales: Vec<f64> = blocks
                .iter()
                .map(|b| self.interface.field_scale(b.participant, b.name, estimate))
                .collect();
            let (residual, block) = state::worst_residual(&x, &h, &blocks, &self.reference, &law_scales);
            history.push(residual);
            if residual <= self.config.tolerance {
                accelerator.end_window();
                return Ok((inputs, k + 1, residual));
            }
            if k + 1 == self.config.max_iterations {
                let field = block
                    .map(|b| format!("{}.{}", self.interface.names()[b.participant], b.name))
                    .unwrap_or_default();
                return Err(CouplerError::NotConverged {
                    window: w,
                    time: times.last().copied().unwrap_or(0.0),
                    iterations: k + 1,
                    residual,
                    field,
                    history,
                });
            }
            state::grow_scales(&mut scales, &h, &blocks);
            scales
                .iter_mut()
                .zip(&law_scales)
                .for_each(|(s, l)| *s = s.max(*l));
            let weights = state::weights(h.len(), &blocks, &scales);
            let next = accelerator.next(&x, &h, &weights, k);
            state::unflatten(&next, &blocks, estimate);
        }
        unreachable!("max_iterations ≥ 1 is checked when the case is loaded")
    }

    /// Advances every participant once over the window, in serial order; returns the inputs each got.
    fn sweep(
        &mut self,
        w: u64,
        k: u32,
        checkpoint: Checkpoint,
        times: &[f64],
        estimate: &mut [Vec<Fields>],
    ) -> Result<Vec<Vec<Fields>>, CouplerError> {
        let t_end = times.last().copied().unwrap_or(0.0);
        let start = estimate.to_vec();
        let mut given = Vec::with_capacity(estimate.len());
        for p in 0..estimate.len() {
            let inputs: Vec<Fields> = (0..times.len())
                .map(|j| {
                    let at_start: Vec<&Fields> = start.iter().map(|s| &s[j]).collect();
                    let current: Vec<&Fields> = estimate.iter().map(|s| &s[j]).collect();
                    self.interface.inputs(p, &at_start, &current)
                })
                .collect();
            let header = Header {
                protocol: PROTOCOL_VERSION,
                window: w,
                iteration: k,
                time: t_end,
            };
            let waveform = Waveform {
                times: times.to_vec(),
                samples: inputs.clone(),
            };
            self.stack.send(
                p,
                ToParticipant::Advance {
                    header,
                    checkpoint,
                    inputs: waveform,
                },
                Some(w),
            )?;
            let name = self.stack.sessions[p].name.clone();
            let refuse = |message: String| CouplerError::Participant {
                name: name.clone(),
                window: Some(w),
                message,
            };
            match self.stack.recv(p, Some(w))? {
                FromParticipant::Advanced {
                    header: h,
                    outputs,
                    geometry,
                } => {
                    if h.window != w || h.iteration != k {
                        return Err(refuse(format!(
                            "answered window {} iteration {}, expected window {w} iteration {k}",
                            h.window, h.iteration
                        )));
                    }
                    let window_length = times.last().unwrap_or(&0.0) - times.first().unwrap_or(&0.0);
                    if (h.time - t_end).abs() > 1e-9 * window_length {
                        return Err(refuse(format!(
                            "reached t = {:.15} s, but the window ends at t = {t_end:.15} s; every solver must land \
                             exactly on the window end",
                            h.time
                        )));
                    }
                    if outputs.samples.len() != times.len() {
                        return Err(refuse(format!(
                            "sent {} output samples for {} window times",
                            outputs.samples.len(),
                            times.len()
                        )));
                    }
                    for sample in &outputs.samples {
                        self.interface.check_outputs(p, sample).map_err(&refuse)?;
                    }
                    if geometry.is_some() {
                        self.stack.sessions[p].geometry = geometry;
                    }
                    estimate[p] = outputs.samples;
                }
                other => {
                    return Err(refuse(format!(
                        "protocol error: expected Advanced, got {}",
                        variant(&other)
                    )))
                }
            }
            given.push(inputs);
        }
        Ok(given)
    }
}
