//! A structure-solver participant with faults injected on request, for the stack's tests:
//! a wrong protocol version at the handshake, answers perturbed from a given window on (so a
//! replay must depart there), a hang in a given window, an exit in a given window (a crash), or a
//! window that takes long while the participant keeps reporting progress.

use clap::{Parser, Subcommand};
use schemas::message::{Fields, InterfaceDecl, Role, Waveform, PROTOCOL_VERSION};
use schemas::participant::{serve_announcing, DiscardProgress, Participant, ParticipantArgs, ProgressSink};
use std::process::ExitCode;
use std::time::{Duration, Instant};
use structure_solver::participant::StructureParticipant;

#[derive(Parser)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Take part in a coupled run, like `structure-solver participant`. Faults come from the
    /// environment (the coupler passes its own to its children): `FAULTY_PROTOCOL=N` announces
    /// protocol N, `FAULTY_PERTURB_FROM_WINDOW=W` multiplies every output by (1 + 1e-6) from
    /// window W on, `FAULTY_HANG_AT_WINDOW=W` stops answering in window W, `FAULTY_EXIT_AT_WINDOW=W`
    /// exits with code 3 in window W without answering, `FAULTY_SLOW_AT_WINDOW=W` with
    /// `FAULTY_SLOW_SECONDS=S` works S wall seconds at the start of window W (its first sweep),
    /// reporting a step every 50 ms, and says so in its log.
    Participant {
        #[command(flatten)]
        args: ParticipantArgs,
    },
}

fn env_number<T: std::str::FromStr>(name: &str) -> Option<T> {
    std::env::var(name).ok().and_then(|v| v.parse().ok())
}

/// The real structure participant with faults around it.
struct Faulty<P> {
    inner: P,
    window: u64,
    window_end: f64,
    perturb_from: Option<u64>,
    hang_at: Option<u64>,
    exit_at: Option<u64>,
    /// The window that is slow, and for how many wall seconds (once).
    slow: Option<(u64, f64)>,
}

/// Wall time between the steps a slow window reports.
const SLOW_STEP: Duration = Duration::from_millis(50);

/// Works `seconds` of wall time in steps of [`SLOW_STEP`], reporting each at simulated time `time`.
fn work_slowly(seconds: f64, time: f64, progress: &mut dyn ProgressSink) {
    let end = Instant::now() + Duration::try_from_secs_f64(seconds).unwrap_or_default();
    while Instant::now() < end {
        std::thread::sleep(SLOW_STEP);
        progress.step_done(time);
    }
}

impl<P: Participant> Participant for Faulty<P> {
    fn role(&self) -> Role {
        self.inner.role()
    }
    fn time(&self) -> f64 {
        self.inner.time()
    }
    fn interface(&self) -> InterfaceDecl {
        self.inner.interface()
    }
    fn initial_outputs(&mut self) -> Fields {
        self.inner.initial_outputs()
    }
    fn save_checkpoint(&mut self) {
        self.inner.save_checkpoint()
    }
    fn restore_checkpoint(&mut self) -> Result<(), String> {
        self.inner.restore_checkpoint()
    }
    fn advance(&mut self, inputs: &Waveform) -> Result<Vec<Fields>, String> {
        self.advance_reporting(inputs, &mut DiscardProgress)
    }
    fn advance_reporting(
        &mut self,
        inputs: &Waveform,
        progress: &mut dyn ProgressSink,
    ) -> Result<Vec<Fields>, String> {
        if inputs.end() > self.window_end {
            if self.window_end > 0.0 || inputs.start() > 0.0 {
                self.window += 1;
            }
            self.window_end = inputs.end();
        }
        if self.hang_at == Some(self.window) {
            loop {
                std::thread::sleep(Duration::from_secs(3600));
            }
        }
        if self.exit_at == Some(self.window) {
            eprintln!("faulty participant: exiting in window {} as asked", self.window);
            std::process::exit(3);
        }
        if let Some((window, seconds)) = self.slow.filter(|(w, _)| *w == self.window) {
            self.slow = None;
            eprintln!("faulty participant: working {seconds} s in window {window} as asked");
            work_slowly(seconds, inputs.start(), progress);
        }
        let mut outputs = self.inner.advance_reporting(inputs, progress)?;
        if self.perturb_from.is_some_and(|w| self.window >= w) {
            for sample in &mut outputs {
                for (_, array) in sample.arrays_mut() {
                    array.iter_mut().for_each(|v| *v *= 1.0 + 1e-6);
                }
            }
        }
        Ok(outputs)
    }
    fn finish(&mut self, progress: &mut dyn ProgressSink) -> Result<(), String> {
        self.inner.finish(progress)
    }
}

fn main() -> ExitCode {
    let Command::Participant { args } = Cli::parse().command;
    let announce_protocol = env_number("FAULTY_PROTOCOL").unwrap_or(PROTOCOL_VERSION);
    let perturb_from_window = env_number("FAULTY_PERTURB_FROM_WINDOW");
    let hang_at_window = env_number("FAULTY_HANG_AT_WINDOW");
    let loaded = schemas::case::Case::load(&args.case)
        .map_err(|e| e.to_string())
        .and_then(|case| {
            StructureParticipant::from_case(&case, &args.name, args.out.as_deref()).map(|p| (p, case.hash))
        });
    let (inner, hash) = match loaded {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let mut faulty = Faulty {
        inner,
        window: 0,
        window_end: 0.0,
        perturb_from: perturb_from_window,
        hang_at: hang_at_window,
        exit_at: env_number("FAULTY_EXIT_AT_WINDOW"),
        slow: env_number("FAULTY_SLOW_AT_WINDOW").zip(env_number("FAULTY_SLOW_SECONDS")),
    };
    match serve_announcing(&args, hash, &mut faulty, announce_protocol) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
