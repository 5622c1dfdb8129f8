//! Starting participant processes, watching them, and stopping them.

use crate::error::CouplerError;
use schemas::case::{Case, Kind};
use std::collections::BTreeMap;
use std::fs::File;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

/// The executable for participant `name`: `--exe` beats the case's `case.executables`, which
/// beats the solver binary beside the coupler's own executable.
pub fn executable_for(
    case: &Case,
    name: &str,
    kind: Kind,
    overrides: &BTreeMap<String, PathBuf>,
) -> Result<PathBuf, CouplerError> {
    let (path, source) = if let Some(p) = overrides.get(name) {
        (p.clone(), format!("--exe {name}=…"))
    } else if let Some(p) = case.info.executables.get(name) {
        (
            case.resolve(p),
            format!("case.executables.{name} in {}", case.path.display()),
        )
    } else {
        let here = std::env::current_exe()
            .map_err(|e| CouplerError::Io(format!("cannot locate the coupler's own executable: {e}")))?;
        let dir = here.parent().map(Path::to_path_buf).unwrap_or_default();
        (dir.join(kind.binary_name()), "the coupler's folder".to_string())
    };
    if !path.is_file() {
        return Err(CouplerError::Usage(format!(
            "participant `{name}`: no executable at {} (from {source}); build the workspace with \
             `cargo build --release`, or name one with --exe {name}=PATH",
            path.display()
        )));
    }
    runnable(&path).map_err(|why| {
        CouplerError::Usage(format!(
            "participant `{name}`: {} (from {source}) is not a program the system can run: {why}",
            path.display()
        ))
    })?;
    Ok(path)
}

/// The launcher that starts participant `name` on its MPI ranks (`mpirun -np 2`), its program
/// found on `PATH`; empty when the participant runs as one process (a structure, or a fluid
/// with `ranks` ≤ 1). An error naming the section's `launcher` key when the program is not found,
/// so `check` refuses what would fail at the start.
pub fn launcher_for(case: &Case, name: &str) -> Result<Vec<String>, CouplerError> {
    let Some(fluid) = case.fluid.get(name).filter(|f| f.rank_count() > 1) else {
        return Ok(Vec::new());
    };
    let words = fluid.launcher_words();
    let program = words.first().map(String::as_str).unwrap_or_default();
    if on_path(program).is_none() {
        return Err(CouplerError::Usage(format!(
            "{}: fluid.{name}.launcher: fluid `{name}` runs on {} MPI ranks through `{program}`, which is not a program on PATH; install OpenMPI (Debian: `apt-get install openmpi-bin`) or name the cluster's launcher (e.g. launcher = \"srun -n {{ranks}}\")",
            case.path.display(),
            fluid.rank_count()
        )));
    }
    Ok(words)
}

/// `program` itself when it names a file (holds a `/`), else the first file of that name in a
/// folder of `PATH`.
fn on_path(program: &str) -> Option<PathBuf> {
    if program.contains('/') {
        return Path::new(program).is_file().then(|| PathBuf::from(program));
    }
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|dir| dir.join(program))
        .find(|p| p.is_file())
}

/// `exe args…` started by `launcher` (its program, its arguments, then `exe args…`), or as is
/// when there is none.
pub fn behind_launcher(launcher: &[String], exe: &Path, args: &[String]) -> (PathBuf, Vec<String>) {
    match launcher.split_first() {
        None => (exe.to_path_buf(), args.to_vec()),
        Some((program, own)) => {
            let mut all = own.to_vec();
            all.push(exe.display().to_string());
            all.extend_from_slice(args);
            (PathBuf::from(program), all)
        }
    }
}

/// Whether the kernel can start `path`: it has an execute permission bit and is a program
/// (an ELF binary) or a script (`#!` and its interpreter). Checked before anything starts, so
/// `check` refuses what `exec` would refuse with "Permission denied" or "Exec format error".
fn runnable(path: &Path) -> Result<(), String> {
    use std::io::Read;
    use std::os::unix::fs::PermissionsExt;
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read it: {e}"))?;
    if meta.permissions().mode() & 0o111 == 0 {
        return Err("it is not executable (no execute permission: `chmod +x` it, if it is a program)".into());
    }
    let mut head = [0u8; 4];
    let read = File::open(path)
        .and_then(|mut f| f.read(&mut head))
        .map_err(|e| format!("cannot read it: {e}"))?;
    let head = &head[..read];
    if head.starts_with(b"\x7fELF") || head.starts_with(b"#!") {
        Ok(())
    } else {
        Err("it is neither a program (ELF) nor a script starting with `#!`".into())
    }
}

/// One started participant process.
pub struct Child {
    pub name: String,
    pub pid: u32,
    process: std::process::Child,
    status: Option<ExitStatus>,
    /// It has answered `Finish`: its exit is expected, not a failure of the run.
    finished: bool,
}

/// The participant processes of a run.
#[derive(Default)]
pub struct Children {
    list: Vec<Child>,
}

impl Children {
    /// Starts `exe args…` in its own process group (so Ctrl-C reaches only the coupler),
    /// with stdout and stderr going to `log` (appended to with `append`: a resumed run).
    pub fn spawn(
        &mut self,
        name: &str,
        exe: &Path,
        args: &[String],
        log: &Path,
        append: bool,
    ) -> Result<u32, CouplerError> {
        let io = |e: std::io::Error| CouplerError::Io(format!("cannot write {}: {e}", log.display()));
        let out = if append {
            std::fs::OpenOptions::new().create(true).append(true).open(log)
        } else {
            File::create(log)
        }
        .map_err(io)?;
        let err = out.try_clone().map_err(io)?;
        let process = Command::new(exe)
            .args(args)
            .stdin(Stdio::null())
            .stdout(out)
            .stderr(err)
            .process_group(0)
            .spawn()
            .map_err(|e| CouplerError::Participant {
                name: name.to_string(),
                window: None,
                message: format!("cannot start {}: {e}", exe.display()),
            })?;
        let pid = process.id();
        self.list.push(Child {
            name: name.to_string(),
            pid,
            process,
            status: None,
            finished: false,
        });
        Ok(pid)
    }

    /// Marks participant `name` as done (it answered `Finish`): [`Children::check`] no longer
    /// counts its exit as a failure while the others finish; [`Children::wait_all`] still
    /// reports its status.
    pub fn finished(&mut self, name: &str) {
        self.list
            .iter_mut()
            .filter(|c| c.name == name)
            .for_each(|c| c.finished = true);
    }

    /// `Err((name, what happened))` for the first participant that has exited without having
    /// finished ([`Children::finished`]).
    pub fn check(&mut self) -> Result<(), (String, String)> {
        for child in self.list.iter_mut().filter(|c| !c.finished) {
            if child.status.is_none() {
                if let Ok(Some(status)) = child.process.try_wait() {
                    child.status = Some(status);
                }
            }
            if let Some(status) = child.status {
                return Err((
                    child.name.clone(),
                    format!("process {} exited ({})", child.pid, describe(status)),
                ));
            }
        }
        Ok(())
    }

    /// Waits up to `grace` for every participant to exit by itself; returns the statuses.
    pub fn wait_all(&mut self, grace: Duration) -> Vec<(String, Option<ExitStatus>)> {
        let deadline = Instant::now() + grace;
        for child in &mut self.list {
            while child.status.is_none() {
                match child.process.try_wait() {
                    Ok(Some(s)) => child.status = Some(s),
                    Ok(None) if Instant::now() < deadline => std::thread::sleep(Duration::from_millis(10)),
                    _ => break,
                }
            }
        }
        self.list.iter().map(|c| (c.name.clone(), c.status)).collect()
    }

    /// Stops every participant still running: SIGTERM, then SIGKILL after `grace`.
    pub fn stop_all(&mut self, grace: Duration) {
        for child in self.list.iter_mut().filter(|c| c.status.is_none()) {
            // SAFETY: kill(2) on a pid this process started and has not reaped.
            unsafe {
                libc::kill(child.pid as libc::pid_t, libc::SIGTERM);
            }
        }
        self.wait_all(grace);
        for child in self.list.iter_mut().filter(|c| c.status.is_none()) {
            let _ = child.process.kill();
            child.status = child.process.wait().ok();
        }
    }
}

impl Drop for Children {
    fn drop(&mut self) {
        self.stop_all(Duration::from_millis(500));
    }
}

/// "exit code 3", "killed by signal 9 (SIGKILL)".
pub fn describe(status: ExitStatus) -> String {
    use std::os::unix::process::ExitStatusExt;
    match (status.code(), status.signal()) {
        (Some(code), _) => format!("exit code {code}"),
        (None, Some(sig)) => format!("killed by signal {sig}{}", signal_name(sig)),
        _ => "unknown status".into(),
    }
}

fn signal_name(sig: i32) -> &'static str {
    match sig {
        libc::SIGKILL => " (SIGKILL)",
        libc::SIGTERM => " (SIGTERM)",
        libc::SIGSEGV => " (SIGSEGV)",
        libc::SIGABRT => " (SIGABRT)",
        libc::SIGINT => " (SIGINT)",
        _ => "",
    }
}

/// The lines of a participant's log that warn the user (they start with `warning: `), without that
/// prefix.
pub fn log_warnings(log: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(log).unwrap_or_default();
    text.lines()
        .filter_map(|l| l.strip_prefix("warning: "))
        .map(str::to_string)
        .collect()
}

/// The last `n` lines of a participant's log, for error messages.
pub fn log_tail(log: &Path, n: usize) -> String {
    let text = std::fs::read_to_string(log).unwrap_or_default();
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The end of a run: a participant that answered `Finish` and exited is not reported as
    /// having died while the coupler waits for the others (CI once failed with "participant
    /// `mass-left` before the first window: process … exited (exit code 0)" when the first
    /// participant exited before the second answered `Finish`).
    #[test]
    fn a_finished_participant_that_exits_is_not_a_failure() {
        let log = std::env::temp_dir().join(format!("coupler-finished-{}.log", std::process::id()));
        let mut children = Children::default();
        children
            .spawn("first", Path::new("/bin/true"), &[], &log, false)
            .unwrap_or_else(|e| panic!("{e}"));
        let statuses = children.wait_all(Duration::from_secs(5));
        assert!(matches!(statuses[0].1, Some(s) if s.success()), "{statuses:?}");
        let (name, what) = children.check().err().unwrap_or_default();
        assert_eq!(name, "first", "an exit before Finish is a failure");
        assert!(what.contains("exit code 0"), "{what}");
        children.finished("first");
        assert_eq!(children.check(), Ok(()), "an exit after Finish is not");
        let _ = std::fs::remove_file(&log);
    }

    #[test]
    fn warnings_are_the_log_lines_that_start_with_the_prefix() {
        let log = std::env::temp_dir().join(format!("coupler-log-warnings-{}.log", std::process::id()));
        std::fs::write(
            &log,
            "started\nwarning: structure.b.frame: 3 of 9 frame steps …\nno warning: here\n  warning: indented\n",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            log_warnings(&log),
            vec!["structure.b.frame: 3 of 9 frame steps …".to_string()]
        );
        let _ = std::fs::remove_file(&log);
        assert!(log_warnings(&log).is_empty(), "a missing log has no warnings");
    }
}
