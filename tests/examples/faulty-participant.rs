//! A structure-solver participant with faults injected on request, for the stack's tests:
//! a wrong protocol version at the handshake, answers perturbed from a given window on (so a
//! replay must depart there), a hang in a given window, or an exit in a given window (a crash).

use clap::{Parser, Subcommand};
use schemas::message::{Fields, InterfaceDecl, Role, Waveform, PROTOCOL_VERSION};
use schemas::participant::{serve_announcing, Participant, ParticipantArgs};
use std::process::ExitCode;
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
    /// exits with code 3 in window W without answering.
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
        if inputs.end() > self.window_end {
            if self.window_end > 0.0 || inputs.start() > 0.0 {
                self.window += 1;
            }
            self.window_end = inputs.end();
        }
        if self.hang_at == Some(self.window) {
            loop {
                std::thread::sleep(std::time::Duration::from_secs(3600));
            }
        }
        if self.exit_at == Some(self.window) {
            eprintln!("faulty participant: exiting in window {} as asked", self.window);
            std::process::exit(3);
        }
        let mut outputs = self.inner.advance(inputs)?;
        if self.perturb_from.is_some_and(|w| self.window >= w) {
            for sample in &mut outputs {
                for (_, array) in sample.arrays_mut() {
                    array.iter_mut().for_each(|v| *v *= 1.0 + 1e-6);
                }
            }
        }
        Ok(outputs)
    }
    fn finish(&mut self) -> Result<(), String> {
        self.inner.finish()
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
    };
    match serve_announcing(&args, hash, &mut faulty, announce_protocol) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
