//! Ctrl-C (SIGINT), SIGTERM and SIGHUP (the terminal closed): noted in a flag that every wait
//! checks, so a process stops cleanly between two steps of its work — the coupler after the
//! window it is in, a participant after the answer it is computing — instead of dying in the
//! middle of writing an output file. The flag keeps which signal came, so the stop can name it.

use std::sync::atomic::{AtomicI32, Ordering};

/// The last stopping signal received, 0 before any.
static RECEIVED: AtomicI32 = AtomicI32::new(0);

extern "C" fn on_signal(sig: libc::c_int) {
    RECEIVED.store(sig, Ordering::SeqCst);
}

/// Routes SIGINT, SIGTERM and SIGHUP to the flag.
pub fn install() {
    let handler = on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
    // SAFETY: the handler only stores to an atomic, which is async-signal-safe.
    unsafe {
        for sig in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
            libc::signal(sig, handler);
        }
    }
}

/// Whether a stopping signal has arrived.
pub fn interrupted() -> bool {
    RECEIVED.load(Ordering::SeqCst) != 0
}

/// The stopping signal that arrived, in words ("SIGHUP (the terminal closed)"); None before any.
pub fn received() -> Option<&'static str> {
    match RECEIVED.load(Ordering::SeqCst) {
        0 => None,
        libc::SIGINT => Some("SIGINT (Ctrl-C)"),
        libc::SIGTERM => Some("SIGTERM"),
        libc::SIGHUP => Some("SIGHUP (the terminal closed)"),
        _ => Some("a stopping signal"),
    }
}
