//! Output written on a thread of its own while the solver steps on: a frame of 10⁷ particles
//! takes seconds to encode and write (docs/notes/gpu-speed.md), as long as many steps of a GPU
//! run. One write is under way at a time: the next one, a checkpoint's flush and the run's end
//! first wait for it, and a write that failed stops the run at that point with its error. The
//! bytes the thread writes reach the waiting thread's progress sink while it waits, so a long
//! write still tells the coupler the participant is working; dropped with a write under way,
//! the writer waits for it, so a run that stops keeps its frames whole.

use schemas::participant::ProgressSink;
use std::sync::mpsc::{channel, Receiver, Sender};
use std::thread::JoinHandle;

/// The error once a panicked write took the writer's state with it.
const LOST: &str = "the output writer lost its files when its thread panicked";

/// A write under way: its thread (which hands the writer's state back with its result) and the
/// bytes it reports.
struct Running<S> {
    thread: JoinHandle<(S, Result<(), String>)>,
    bytes: Receiver<u64>,
}

/// The writing thread's progress sink: the bytes go to whoever waits for it.
struct BytesToWaiter(Sender<u64>);

impl ProgressSink for BytesToWaiter {
    fn step_done(&mut self, _time: f64) {}
    fn bytes_written(&mut self, bytes: u64) {
        // the waiter may be gone (a run stopping): the bytes are then nobody's news
        let _ = self.0.send(bytes);
    }
}

/// A writer of outputs on a thread of its own, over a state `S` (its files and series) that
/// each write borrows in turn.
pub struct BackgroundWriter<S: Send + 'static> {
    idle: Option<S>,
    running: Option<Running<S>>,
}

impl<S: Send + 'static> BackgroundWriter<S> {
    /// A writer over `state`, nothing under way.
    pub fn new(state: S) -> BackgroundWriter<S> {
        BackgroundWriter {
            idle: Some(state),
            running: None,
        }
    }

    /// Waits for the write under way, if any (passing its bytes on to `progress`), and gives
    /// the state back: the error of that write if it failed.
    pub fn wait(&mut self, progress: &mut dyn ProgressSink) -> Result<&mut S, String> {
        if let Some(Running { thread, bytes }) = self.running.take() {
            // ends when the thread is done and drops its sender
            for b in bytes.iter() {
                progress.bytes_written(b);
            }
            let (state, result) = thread
                .join()
                .map_err(|_| "the output writer's thread panicked; its outputs are incomplete".to_string())?;
            self.idle = Some(state);
            result?;
        }
        self.idle.as_mut().ok_or_else(|| LOST.to_string())
    }

    /// Starts `write` on the state on a thread of its own, once the write before it is done
    /// (whose error it returns instead of starting).
    pub fn start(
        &mut self,
        progress: &mut dyn ProgressSink,
        write: impl FnOnce(&mut S, &mut dyn ProgressSink) -> Result<(), String> + Send + 'static,
    ) -> Result<(), String> {
        self.wait(progress)?;
        let mut state = self.idle.take().ok_or_else(|| LOST.to_string())?;
        let (sender, bytes) = channel();
        let thread = std::thread::Builder::new()
            .name("output writer".into())
            .spawn(move || {
                let mut sink = BytesToWaiter(sender);
                let result = write(&mut state, &mut sink);
                (state, result)
            })
            .map_err(|e| format!("cannot start the output writer's thread: {e}"))?;
        self.running = Some(Running { thread, bytes });
        Ok(())
    }
}

impl<S: Send + 'static> Drop for BackgroundWriter<S> {
    /// Lets a write under way finish, so that a run that stops for another reason leaves its
    /// last frame whole (its error, if any, is the lesser news then).
    fn drop(&mut self) {
        if let Some(Running { thread, .. }) = self.running.take() {
            let _ = thread.join();
        }
    }
}
