//! A closed terminal or pipe does not stop a run: with standard error (or output) closed before
//! the coupler writes its first line (`coupler run … 2>&1 | head -3` once `head` has gone), the
//! coupler drops its lines and the run ends as it would have, its outputs whole.

use stack_tests::{binary, oscillator_case, out_dir};
use std::os::fd::{FromRawFd, OwnedFd};
use std::process::{Command, Stdio};

/// A pipe whose reading end is already closed: a write into it fails with EPIPE.
fn closed_pipe() -> Stdio {
    let mut fds = [0; 2];
    // SAFETY: pipe(2) fills the two descriptors, which are then owned here.
    assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0, "pipe(2) failed");
    // SAFETY: fds[0] is the pipe's reading end, owned by nothing else; dropping it closes it.
    drop(unsafe { OwnedFd::from_raw_fd(fds[0]) });
    // SAFETY: fds[1] is the pipe's writing end, owned by nothing else.
    Stdio::from(unsafe { OwnedFd::from_raw_fd(fds[1]) })
}

#[test]
fn a_run_with_its_standard_error_and_output_closed_ends_as_usual() {
    let dir = out_dir("closed-streams");
    let case = oscillator_case(&dir, &[]);
    let out = dir.join("out");
    let run = Command::new(binary("coupler"))
        .args([
            "run",
            case.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
        ])
        .stdout(closed_pipe())
        .stderr(closed_pipe())
        .status()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    assert_eq!(run.code(), Some(0), "the run ends as usual: {run:?}");
    let ledger = std::fs::read_to_string(out.join("ledger.csv")).unwrap_or_default();
    assert_eq!(
        ledger.lines().count(),
        101,
        "a header and 100 windows in the ledger"
    );

    let check = Command::new(binary("coupler"))
        .args(["check", case.to_str().unwrap_or_default()])
        .stdout(closed_pipe())
        .stderr(closed_pipe())
        .status()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    assert_eq!(check.code(), Some(0), "check ends as usual: {check:?}");
}
