//! Tests of `schemas::link::liveness`.

use schemas::link::process_alive;

#[test]
fn own_process_is_alive() {
    assert_eq!(process_alive(std::process::id()), Ok(()));
}

#[test]
fn exited_and_reaped_child_is_gone() {
    let mut child = std::process::Command::new("true").spawn().expect("spawn `true`");
    let pid = child.id();
    child.wait().expect("wait for `true`");
    // The pid could in principle be reused at once; on Linux pids are handed out cyclically.
    assert!(process_alive(pid).is_err());
}

#[test]
fn exited_unreaped_child_is_gone() {
    let mut child = std::process::Command::new("true").spawn().expect("spawn `true`");
    let pid = child.id();
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(5);
    while process_alive(pid).is_ok() {
        assert!(
            std::time::Instant::now() < deadline,
            "zombie child {pid} still reported alive"
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    child.wait().expect("reap `true`");
}

#[test]
fn pid_zero_is_rejected() {
    assert!(process_alive(0).is_err());
    assert!(process_alive(u32::MAX).is_err());
}
