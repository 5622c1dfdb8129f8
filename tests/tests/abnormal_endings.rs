//! Every abnormal ending leaves every output whole: the CI-sized floating box (fluid, structure,
//! coupler) is stopped mid-run by SIGKILL, SIGTERM and SIGINT sent to each of its three
//! processes, and by SIGHUP (a closed terminal) sent to the coupler — SIGINT to the coupler as
//! a terminal's Ctrl-C does, to its whole process group — and then every file is parsed: each
//! CSV (ledger, histories, probes) holds whole rows only and ends with a line end, each PVD
//! lists only complete frame files, the recording reads back. The participants run in process
//! groups of their own, so Ctrl-C reaches only the coupler, which stops them.

use schemas::recording::{Recording, RecordingEnd};
use stack_tests::{binary, case_from, out_dir};
use std::io::{BufRead, BufReader};
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// The floating box at Δs = 2 cm for 1 s, a frame every 0.01 s so that frames are being written
/// when a signal comes.
fn case(dir: &Path) -> PathBuf {
    case_from(
        "dam-break-floating-box",
        dir,
        &[
            ("end_time", "1.0"),
            ("spacing", "0.02"),
            ("output_interval", "0.01"),
            (
                "tank",
                "{ min = [0.0, 0.0, 0.0], max = [0.6, 0.44, 0.4], lid = true }",
            ),
        ],
    )
}

fn alive(pid: i32) -> bool {
    // SAFETY: signal 0 only checks that the process exists.
    unsafe { libc::kill(pid, 0) == 0 }
}

fn signal_name(sig: i32) -> &'static str {
    match sig {
        libc::SIGKILL => "SIGKILL",
        libc::SIGTERM => "SIGTERM",
        libc::SIGHUP => "SIGHUP",
        _ => "SIGINT",
    }
}

/// Runs the case, sends `sig` to `target` (`"coupler"`, `"tank"` or `"floater"`) once 30 windows
/// are in the ledger, and checks the ending and every output.
fn stop_mid_run(target: &str, sig: i32) {
    let what = format!("{} to {target}", signal_name(sig));
    let dir = out_dir(&format!("ending-{target}-{}", signal_name(sig)));
    let case = case(&dir);
    let out = dir.join("out");
    let mut coupler = Command::new(binary("coupler"))
        .args(["run", case.to_str().unwrap_or_default(), "--out"])
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .process_group(0)
        .spawn()
        .unwrap_or_else(|e| panic!("{e}"));
    let coupler_pid = coupler.id() as i32;
    let (tx, rx) = mpsc::channel();
    let err = coupler.stderr.take().unwrap_or_else(|| panic!("no stderr"));
    std::thread::spawn(move || {
        for line in BufReader::new(err).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    let mut lines = Vec::new();
    let mut pids = std::collections::BTreeMap::new();
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        lines.extend(rx.try_iter());
        for l in &lines {
            if let Some(rest) = l.strip_prefix("started ") {
                let name = rest.split(' ').next().unwrap_or_default().to_string();
                let pid: i32 = l
                    .rsplit("pid ")
                    .next()
                    .and_then(|s| s.trim_end_matches(')').parse().ok())
                    .unwrap_or(0);
                pids.insert(name, pid);
            }
        }
        let windows = std::fs::read_to_string(out.join("ledger.csv"))
            .map(|t| t.lines().count())
            .unwrap_or(0);
        if windows > 30 && pids.len() == 2 {
            break;
        }
        assert!(
            Instant::now() < deadline,
            "{what}: the run did not get going:\n{}",
            lines.join("\n")
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    for (name, &pid) in &pids {
        // SAFETY: getpgid(2) of a participant this test's coupler started.
        let group = unsafe { libc::getpgid(pid) };
        assert_ne!(
            group, coupler_pid,
            "{name} must not be in the coupler's process group"
        );
    }
    match (target, sig) {
        // SAFETY (all three): signals to processes this test started (or its coupler did).
        ("coupler", libc::SIGINT) => unsafe { libc::kill(-coupler_pid, libc::SIGINT) },
        ("coupler", _) => unsafe { libc::kill(coupler_pid, sig) },
        (name, _) => unsafe { libc::kill(pids[name], sig) },
    };
    let t0 = Instant::now();
    let status = loop {
        if let Ok(Some(s)) = coupler.try_wait() {
            break s;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(15),
            "{what}: the coupler did not stop"
        );
        std::thread::sleep(Duration::from_millis(10));
    };
    std::thread::sleep(Duration::from_millis(200));
    lines.extend(rx.try_iter());
    let text = lines.join("\n");
    let gone = Instant::now() + Duration::from_secs(5);
    while pids.values().any(|&p| alive(p)) && Instant::now() < gone {
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(
        !pids.values().any(|&p| alive(p)),
        "{what}: every participant stops"
    );
    match target {
        "coupler" if sig == libc::SIGKILL => {}
        "coupler" => {
            assert_eq!(status.code(), Some(130), "{what}: {text}");
            assert!(text.contains("interrupted in window"), "{what}: {text}");
            assert!(
                text.contains(&format!("by {}", signal_name(sig))),
                "{what}: the stop names the signal: {text}"
            );
        }
        name => {
            assert_eq!(status.code(), Some(1), "{what}: {text}");
            assert!(
                text.contains(&format!("participant `{name}` in window")),
                "{what}: {text}"
            );
        }
    }
    let killed = sig == libc::SIGKILL;
    let files = check_outputs(&out, &what, killed);
    let rec = Recording::read(&out.join("recording.rec")).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(rec.frames.len() > 60, "{what}: {} frames", rec.frames.len());
    if !(target == "coupler" && killed) {
        assert_eq!(rec.end, RecordingEnd::Whole, "{what}");
    }
    println!(
        "{what}: stopped {:?} after the signal; {files} output files whole",
        t0.elapsed()
    );
}

/// Parses every output file under `dir`; returns how many were checked.
fn check_outputs(dir: &Path, what: &str, killed: bool) -> usize {
    let mut files = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d)
            .unwrap_or_else(|e| panic!("{e}"))
            .filter_map(Result::ok)
        {
            if e.path().is_dir() {
                stack.push(e.path());
            } else {
                files.push(e.path());
            }
        }
    }
    let mut rows = std::collections::BTreeMap::new();
    for f in &files {
        let name = f.file_name().unwrap_or_default().to_string_lossy().into_owned();
        let ext = f.extension().unwrap_or_default().to_string_lossy().into_owned();
        match ext.as_str() {
            "csv" => {
                let text = std::fs::read_to_string(f).unwrap_or_default();
                assert!(text.ends_with('\n'), "{what}: {} ends inside a row", f.display());
                let mut lines = text.lines();
                let columns = lines.next().unwrap_or_default().split(',').count();
                let mut n = 0;
                for (i, line) in lines.enumerate() {
                    let cells: Vec<&str> = line.split(',').collect();
                    assert_eq!(
                        cells.len(),
                        columns,
                        "{what}: {} row {} is partial: `{line}`",
                        f.display(),
                        i + 1
                    );
                    n += 1;
                }
                rows.insert(name, n);
            }
            "pvd" => {
                let text = std::fs::read_to_string(f).unwrap_or_default();
                assert!(
                    text.trim_end().ends_with("</VTKFile>"),
                    "{what}: {} is cut",
                    f.display()
                );
                for listed in text.split("file=\"").skip(1) {
                    let frame = f.with_file_name(listed.split('"').next().unwrap_or_default());
                    let bytes = std::fs::read(&frame).unwrap_or_default();
                    let tail = String::from_utf8_lossy(&bytes[bytes.len().saturating_sub(32)..]).into_owned();
                    assert!(
                        tail.contains("</VTKFile>"),
                        "{what}: {} is listed but not whole",
                        frame.display()
                    );
                }
            }
            "vtu" | "vtp" => {
                let bytes = std::fs::read(f).unwrap_or_default();
                let tail = String::from_utf8_lossy(&bytes[bytes.len().saturating_sub(32)..]).into_owned();
                assert!(
                    tail.contains("</VTKFile>"),
                    "{what}: {} is not whole",
                    f.display()
                );
            }
            "tmp" => assert!(
                killed,
                "{what}: a stop by SIGTERM or SIGINT leaves no temporary file: {}",
                f.display()
            ),
            _ => {}
        }
    }
    for needed in ["ledger.csv", "body-box.csv", "tank_probes.csv"] {
        assert!(
            rows.get(needed).is_some_and(|&n| n > 0),
            "{what}: {needed} has rows: {rows:?}"
        );
    }
    files.len()
}

#[test]
fn sigkill_sigterm_and_sigint_to_the_fluid_leave_every_output_whole() {
    for sig in [libc::SIGKILL, libc::SIGTERM, libc::SIGINT] {
        stop_mid_run("tank", sig);
    }
}

#[test]
fn sigkill_sigterm_and_sigint_to_the_structure_leave_every_output_whole() {
    for sig in [libc::SIGKILL, libc::SIGTERM, libc::SIGINT] {
        stop_mid_run("floater", sig);
    }
}

#[test]
fn sigkill_sigterm_ctrl_c_and_sighup_to_the_coupler_stop_the_participants_and_leave_every_output_whole() {
    for sig in [libc::SIGKILL, libc::SIGTERM, libc::SIGINT, libc::SIGHUP] {
        stop_mid_run("coupler", sig);
    }
}
