//! Is a process (by pid) still running? Used by a participant to notice that its coupler died.

/// Liveness of a process by pid: `Ok(())` while it runs, `Err(message)` once it no longer exists
/// or has exited and waits to be reaped (a zombie). Reaping children is the caller's business.
pub fn process_alive(pid: u32) -> Result<(), String> {
    let raw = match libc::pid_t::try_from(pid) {
        Ok(raw) if raw > 0 => raw,
        _ => return Err(format!("{pid} is not a valid process id")),
    };
    // SAFETY: signal 0 performs only the existence and permission checks, it sends nothing.
    let rc = unsafe { libc::kill(raw, 0) };
    if rc != 0 {
        let err = std::io::Error::last_os_error();
        return match err.raw_os_error() {
            // The process exists but belongs to another user: it is alive.
            Some(libc::EPERM) => Ok(()),
            Some(libc::ESRCH) => Err(format!("process {pid} no longer exists")),
            _ => Err(format!("cannot check process {pid}: {err}")),
        };
    }
    if is_zombie(pid) {
        return Err(format!("process {pid} has exited"));
    }
    Ok(())
}

/// True when `/proc/{pid}/stat` reports state `Z` (exited, not yet reaped). Without procfs: false.
fn is_zombie(pid: u32) -> bool {
    let Ok(stat) = std::fs::read_to_string(format!("/proc/{pid}/stat")) else {
        return false;
    };
    // Format: "pid (comm) S ...": comm may contain spaces or ')', so take the text after the last ')'.
    stat.rsplit_once(')')
        .and_then(|(_, rest)| rest.split_whitespace().next())
        .is_some_and(|state| state == "Z")
}
