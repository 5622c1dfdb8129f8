//! The frames' writer thread (`fluid_solver::output::background`): writes run one at a time in
//! the order they were started, a failed write stops the caller at its next start or wait with
//! the write's message, the bytes a write reports reach the waiting caller's progress sink, and
//! a writer dropped with a write under way lets it finish.

use fluid_solver::output::background::BackgroundWriter;
use schemas::participant::ProgressSink;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// A progress sink that counts the bytes it is told of.
#[derive(Default)]
struct Bytes(u64);

impl ProgressSink for Bytes {
    fn step_done(&mut self, _time: f64) {}
    fn bytes_written(&mut self, bytes: u64) {
        self.0 += bytes;
    }
}

#[test]
fn writes_run_in_turn_and_their_bytes_reach_the_waiter() {
    let mut writer = BackgroundWriter::new(Vec::<u32>::new());
    let mut progress = Bytes::default();
    for k in 0..5u32 {
        writer
            .start(&mut progress, move |log, progress| {
                // a slow write: the next start must wait for it, not overtake it
                std::thread::sleep(Duration::from_millis(20));
                log.push(k);
                progress.bytes_written(1000);
                Ok(())
            })
            .unwrap_or_else(|e| panic!("{e}"));
    }
    let log = writer
        .wait(&mut progress)
        .unwrap_or_else(|e| panic!("{e}"))
        .clone();
    assert_eq!(log, vec![0, 1, 2, 3, 4]);
    assert_eq!(progress.0, 5000, "every write's bytes reach the waiter");
}

#[test]
fn a_failed_write_stops_the_next_start_and_the_wait_with_its_message() {
    let mut writer = BackgroundWriter::new(0u32);
    let mut progress = Bytes::default();
    writer
        .start(&mut progress, |_, _| {
            Err("cannot write frame_00003.vtu: disk full".into())
        })
        .unwrap_or_else(|e| panic!("starting the failing write: {e}"));
    let e = writer
        .start(&mut progress, |n, _| {
            *n += 1;
            Ok(())
        })
        .err()
        .unwrap_or_default();
    assert_eq!(e, "cannot write frame_00003.vtu: disk full");
    // the state is back and usable once the error is told
    writer
        .start(&mut progress, |n, _| {
            *n += 1;
            Ok(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(*writer.wait(&mut progress).unwrap_or_else(|e| panic!("{e}")), 1);

    let mut failing = BackgroundWriter::new(());
    failing
        .start(&mut progress, |_, _| Err("cannot write the PVD".into()))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        failing.wait(&mut progress).err().unwrap_or_default(),
        "cannot write the PVD"
    );
}

#[test]
fn a_writer_dropped_with_a_write_under_way_lets_it_finish() {
    let done = Arc::new(Mutex::new(false));
    {
        let mut writer = BackgroundWriter::new(());
        let flag = Arc::clone(&done);
        writer
            .start(&mut Bytes::default(), move |_, _| {
                std::thread::sleep(Duration::from_millis(100));
                *flag.lock().unwrap_or_else(|e| e.into_inner()) = true;
                Ok(())
            })
            .unwrap_or_else(|e| panic!("{e}"));
    }
    assert!(
        *done.lock().unwrap_or_else(|e| e.into_inner()),
        "the write finished before the writer was gone"
    );
}
