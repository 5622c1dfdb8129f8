//! Faults: a participant killed mid-run, a participant that hangs or is frozen (SIGSTOP), a
//! participant that speaks another protocol version, Ctrl-C — each stops the run cleanly with a
//! message that names who and when, and the next run on the same machine starts cleanly. A
//! window longer than the timeout is no fault while its participant reports progress.

use schemas::message::{FromParticipant, ToParticipant};
use schemas::recording::Message;
use stack_tests::{binary, coupler, coupler_run, oscillator_case, oscillator_error, out_dir, stderr};
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// Starts `coupler run CASE` with stderr streamed line by line.
fn start(case: &Path, out: &Path, env: &[(&str, &str)]) -> (Child, mpsc::Receiver<String>) {
    let mut child = Command::new(binary("coupler"))
        .args([
            "run",
            case.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
        ])
        .envs(env.iter().copied())
        .stderr(Stdio::piped())
        .stdout(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    let rx = stream_stderr(&mut child);
    (child, rx)
}

/// The child's stderr (piped), line by line.
fn stream_stderr(child: &mut Child) -> mpsc::Receiver<String> {
    let (tx, rx) = mpsc::channel();
    let err = child.stderr.take().unwrap_or_else(|| panic!("no stderr pipe"));
    std::thread::spawn(move || {
        for line in BufReader::new(err).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    rx
}

/// Waits for a line containing `needle`; returns it.
fn wait_line(rx: &mpsc::Receiver<String>, needle: &str, lines: &mut Vec<String>) -> String {
    let deadline = Instant::now() + Duration::from_secs(30);
    while Instant::now() < deadline {
        if let Ok(line) = rx.recv_timeout(Duration::from_millis(100)) {
            lines.push(line.clone());
            if line.contains(needle) {
                return line;
            }
        }
    }
    panic!("no line with `{needle}` in 30 s; got:\n{}", lines.join("\n"))
}

/// The pid in "started NAME (EXE, pid N)".
fn pid_of(line: &str) -> i32 {
    line.rsplit("pid ")
        .next()
        .and_then(|s| s.trim_end_matches(')').parse().ok())
        .unwrap_or_else(|| panic!("no pid in `{line}`"))
}

/// Waits for the child to exit; returns its status and how long it took.
fn wait_exit(child: &mut Child, limit: Duration) -> (std::process::ExitStatus, Duration) {
    let t0 = Instant::now();
    loop {
        if let Ok(Some(status)) = child.try_wait() {
            return (status, t0.elapsed());
        }
        if t0.elapsed() > limit {
            let _ = child.kill();
            panic!("the coupler did not exit within {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

fn alive(pid: i32) -> bool {
    // SAFETY: signal 0 only checks that the process exists.
    unsafe { libc::kill(pid, 0) == 0 }
}

/// A long explicit run (many small windows) so there is time to act mid-run.
fn long_case(dir: &Path) -> std::path::PathBuf {
    oscillator_case(
        dir,
        &[
            ("end_time", "200.0"),
            ("window", "0.001"),
            ("scheme", "\"explicit\""),
            ("samples", "1 "),
        ],
    )
}

#[test]
fn a_killed_participant_stops_the_run_within_two_seconds_and_is_named() {
    let dir = out_dir("kill");
    let case = long_case(&dir);
    let (mut child, rx) = start(&case, &dir.join("out"), &[]);
    let mut lines = Vec::new();
    let left = pid_of(&wait_line(&rx, "started mass-left", &mut lines));
    let right = pid_of(&wait_line(&rx, "started mass-right", &mut lines));
    std::thread::sleep(Duration::from_millis(700));
    // SAFETY: SIGKILL to the participant this test's coupler started.
    unsafe { libc::kill(right, libc::SIGKILL) };
    let (status, took) = wait_exit(&mut child, Duration::from_secs(10));
    lines.extend(rx.try_iter());
    let text = lines.join("\n");
    println!("{text}\ncoupler exited {took:?} after the kill");
    assert!(!status.success(), "the coupler must fail when a participant dies");
    assert!(
        took < Duration::from_secs(2),
        "the coupler took {took:?} to notice"
    );
    assert!(
        text.contains("participant `mass-right` in window"),
        "names who and when: {text}"
    );
    assert!(text.contains("SIGKILL"), "says how it died: {text}");
    std::thread::sleep(Duration::from_millis(300));
    assert!(!alive(left), "the other participant is stopped too");
    let ledger = std::fs::read_to_string(dir.join("out/ledger.csv")).unwrap_or_default();
    assert!(
        ledger.lines().count() > 10,
        "output written so far stays: {} ledger lines",
        ledger.lines().count()
    );
    let rec = schemas::recording::Recording::read(&dir.join("out/recording.rec"));
    assert!(
        rec.is_ok_and(|r| r.frames.len() > 10),
        "the recording stays readable"
    );

    // The next run on the same machine starts cleanly.
    let dir2 = out_dir("after-kill");
    let case2 = oscillator_case(&dir2, &[]);
    let run = coupler(&[
        "run",
        case2.to_str().unwrap_or_default(),
        "--out",
        dir2.join("out").to_str().unwrap_or_default(),
    ]);
    assert!(run.status.success(), "a run after the kill: {}", stderr(&run));
    assert!(oscillator_error(&dir2.join("out/recording.rec")) < 1e-4);
}

#[test]
fn a_hung_participant_is_stopped_after_the_case_timeout() {
    let dir = out_dir("hang");
    let case = oscillator_case(&dir, &[("max_iterations", "30\ntimeout = 1.0")]);
    let faulty = binary("faulty-participant");
    let out = dir.join("out");
    let t0 = Instant::now();
    let run = Command::new(binary("coupler"))
        .args([
            "run",
            case.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
        ])
        .arg(format!("--exe=mass-right={}", faulty.display()))
        .env("FAULTY_HANG_AT_WINDOW", "5")
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    let err = stderr(&run);
    println!("{err}");
    assert!(!run.status.success());
    assert!(err.contains("participant `mass-right` in window 5"), "{err}");
    assert!(
        err.contains("no answer and no progress report for 1.0 s (hung?); it reported no step"),
        "{err}"
    );
    assert!(t0.elapsed() < Duration::from_secs(8), "took {:?}", t0.elapsed());
}

/// The oscillator with `coupling.timeout = 1 s`.
fn one_second_timeout_case(dir: &Path) -> std::path::PathBuf {
    oscillator_case(dir, &[("max_iterations", "30\ntimeout = 1.0")])
}

/// `coupler ARGS…` with `mass-right` played by the faulty participant, working `seconds` of wall
/// time at the start of window `window` while it reports progress.
fn with_slow_window(args: &[&str], window: u64, seconds: f64) -> Command {
    let mut command = Command::new(binary("coupler"));
    command
        .args(args)
        .env("FAULTY_SLOW_AT_WINDOW", window.to_string())
        .env("FAULTY_SLOW_SECONDS", seconds.to_string());
    command
}

#[test]
fn a_window_longer_than_the_timeout_completes_while_its_participant_reports_progress() {
    let dir = out_dir("slow-window");
    let case = one_second_timeout_case(&dir);
    let out = dir.join("out");
    let faulty = binary("faulty-participant");
    let exe = format!("--exe=mass-right={}", faulty.display());
    let run = with_slow_window(
        &[
            "run",
            case.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
            &exe,
        ],
        3,
        3.0,
    )
    .output()
    .unwrap_or_else(|e| panic!("{e}"));
    let err = stderr(&run);
    println!("{err}");
    assert!(
        run.status.success(),
        "a slow window that reports progress is no hang: {err}"
    );
    let log = std::fs::read_to_string(out.join("mass-right.log")).unwrap_or_default();
    assert!(log.contains("working 3 s in window 3"), "{log}");

    // The answer took three timeouts; the reports that kept it alive are not recorded.
    let rec =
        schemas::recording::Recording::read(&out.join("recording.rec")).unwrap_or_else(|e| panic!("{e}"));
    let asked = rec.frames.iter().position(|f| {
        f.participant == "mass-right"
            && matches!(&f.message, Message::To(ToParticipant::Advance { header, .. }) if header.window == 3)
    });
    let asked = asked.unwrap_or_else(|| panic!("no Advance of window 3 to mass-right recorded"));
    let answered = &rec.frames[asked + 1];
    assert!(
        matches!(answered.message, Message::From(FromParticipant::Advanced { .. })),
        "the answer follows the request in the recording: {:?}",
        answered.message
    );
    let took = answered.wall_time - rec.frames[asked].wall_time;
    assert!(took >= 3.0, "window 3 took {took} s of wall time");
    assert!(
        !rec.frames
            .iter()
            .any(|f| matches!(f.message, Message::From(FromParticipant::Progress { .. }))),
        "progress reports are not recorded"
    );

    // A replay waits for the slow answer as the run did.
    let rec_path = out.join("recording.rec");
    let replay_exe = format!("--exe={}", faulty.display());
    let replay_out = dir.join("replay");
    let replay = with_slow_window(
        &[
            "replay",
            rec_path.to_str().unwrap_or_default(),
            "--participant",
            "mass-right",
            &replay_exe,
            "--out",
            replay_out.to_str().unwrap_or_default(),
        ],
        3,
        2.0,
    )
    .output()
    .unwrap_or_else(|e| panic!("{e}"));
    let text = format!("{}{}", String::from_utf8_lossy(&replay.stdout), stderr(&replay));
    println!("{text}");
    assert!(replay.status.success(), "{text}");
    assert!(text.contains("PASS"), "{text}");
}

#[test]
fn a_participant_frozen_in_a_long_window_is_stopped_after_the_timeout_and_named() {
    let dir = out_dir("frozen");
    let case = one_second_timeout_case(&dir);
    let out = dir.join("out");
    let exe = format!("--exe=mass-right={}", binary("faulty-participant").display());
    let mut child = with_slow_window(
        &[
            "run",
            case.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
            &exe,
        ],
        2,
        60.0,
    )
    .stderr(Stdio::piped())
    .stdout(Stdio::null())
    .spawn()
    .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    let rx = stream_stderr(&mut child);
    let mut lines = Vec::new();
    let right = pid_of(&wait_line(&rx, "started mass-right", &mut lines));
    let log = out.join("mass-right.log");
    let t0 = Instant::now();
    while !std::fs::read_to_string(&log).is_ok_and(|l| l.contains("working 60 s in window 2")) {
        assert!(t0.elapsed() < Duration::from_secs(30), "window 2 did not start");
        std::thread::sleep(Duration::from_millis(20));
    }
    // Working and reporting, it outlives the timeout.
    std::thread::sleep(Duration::from_millis(2500));
    assert!(
        matches!(child.try_wait(), Ok(None)),
        "the coupler stopped a participant that reports progress"
    );
    // SAFETY: SIGSTOP to the participant this test's coupler started: alive, but no progress.
    unsafe { libc::kill(right, libc::SIGSTOP) };
    let (status, took) = wait_exit(&mut child, Duration::from_secs(20));
    lines.extend(rx.try_iter());
    let text = lines.join("\n");
    println!("{text}\ncoupler exited {took:?} after the SIGSTOP");
    if alive(right) {
        // SAFETY: as above; the coupler left it behind, which the assertion below reports.
        unsafe { libc::kill(right, libc::SIGKILL) };
        panic!("the frozen participant was left running");
    }
    assert!(!status.success(), "{text}");
    assert!(text.contains("participant `mass-right` in window 2"), "{text}");
    assert!(
        text.contains("no answer and no progress report for 1.0 s (hung?); it last reported step"),
        "{text}"
    );
    assert!(
        took < Duration::from_secs(6),
        "took {took:?} to stop a frozen participant"
    );
}

#[test]
fn a_participant_with_another_protocol_version_is_refused_at_the_handshake() {
    let dir = out_dir("protocol");
    let case = oscillator_case(&dir, &[]);
    let faulty = binary("faulty-participant");
    let run = Command::new(binary("coupler"))
        .args([
            "run",
            case.to_str().unwrap_or_default(),
            "--out",
            dir.join("out").to_str().unwrap_or_default(),
        ])
        .arg(format!("--exe=mass-left={}", faulty.display()))
        .env("FAULTY_PROTOCOL", "99")
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    let err = stderr(&run);
    println!("{err}");
    assert!(!run.status.success());
    assert!(
        err.contains("participant `mass-left` before the first window: refused at the handshake"),
        "{err}"
    );
    assert!(err.contains("protocol version 99"), "{err}");
}

#[test]
fn ctrl_c_stops_the_coupler_and_its_participants() {
    let dir = out_dir("ctrl-c");
    let case = long_case(&dir);
    let (mut child, rx) = start(&case, &dir.join("out"), &[]);
    let mut lines = Vec::new();
    let left = pid_of(&wait_line(&rx, "started mass-left", &mut lines));
    let right = pid_of(&wait_line(&rx, "started mass-right", &mut lines));
    // Mid-run: once windows are done (on a loaded machine the handshake alone can take 0.5 s).
    let t0 = Instant::now();
    while std::fs::read_to_string(dir.join("out/ledger.csv"))
        .map(|t| t.lines().count())
        .unwrap_or(0)
        < 10
        && t0.elapsed() < Duration::from_secs(30)
    {
        std::thread::sleep(Duration::from_millis(20));
    }
    // SAFETY: SIGINT to the coupler this test started, as Ctrl-C would.
    unsafe { libc::kill(child.id() as i32, libc::SIGINT) };
    let (status, took) = wait_exit(&mut child, Duration::from_secs(10));
    lines.extend(rx.try_iter());
    let text = lines.join("\n");
    println!("{text}");
    assert_eq!(status.code(), Some(130), "exit code 130 after Ctrl-C");
    assert!(took < Duration::from_secs(2), "took {took:?}");
    assert!(text.contains("interrupted in window"), "{text}");
    std::thread::sleep(Duration::from_millis(300));
    assert!(!alive(left) && !alive(right), "participants stopped");
}

#[test]
fn two_runs_at_once_do_not_interfere() {
    let dirs = [out_dir("concurrent-a"), out_dir("concurrent-b")];
    let cases = [
        oscillator_case(&dirs[0], &[("window", "0.01")]),
        oscillator_case(&dirs[1], &[("window", "0.02")]),
    ];
    let runs: Vec<Child> = (0..2)
        .map(|i| {
            Command::new(binary("coupler"))
                .args([
                    "run",
                    cases[i].to_str().unwrap_or_default(),
                    "--out",
                    dirs[i].join("out").to_str().unwrap_or_default(),
                ])
                .stderr(Stdio::piped())
                .spawn()
                .unwrap_or_else(|e| panic!("{e}"))
        })
        .collect();
    for (i, run) in runs.into_iter().enumerate() {
        let out = run.wait_with_output().unwrap_or_else(|e| panic!("{e}"));
        assert!(out.status.success(), "run {i}: {}", stderr(&out));
    }
    // Each run reproduces what it gives alone (runs alone are checked in oscillator.rs): both
    // accurate, and different from each other because their windows differ.
    let e = [
        oscillator_error(&dirs[0].join("out/recording.rec")),
        oscillator_error(&dirs[1].join("out/recording.rec")),
    ];
    println!("concurrent errors: {e:?}");
    assert!(e[0] < 1.6e-5 && e[1] < 1e-3, "{e:?}");
    assert_ne!(e[0], e[1]);
}

/// The structure solver reports its steps too (`Structure::advance_reporting`): the oscillator
/// with `mass-left` stepped at 4e-8 s, 250 000 substeps per window (about 0.5 s of wall time each
/// on the 2-core machine), under a 0.2 s timeout, completes. Before the structure solver reported,
/// such a run stopped at window 0: "no answer and no progress report for 0.5 s (hung?)" (measured
/// with 1e-8 s steps and a 0.5 s timeout).
#[test]
fn a_structure_window_longer_than_the_timeout_completes() {
    let dir = out_dir("slow-structure-window");
    let case = oscillator_case(
        &dir,
        &[
            ("end_time", "0.04"),
            ("max_step", "4.0e-8"),
            ("scheme", "\"explicit\""),
            ("max_iterations", "30\ntimeout = 0.2"),
        ],
    );
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    let err = stderr(&run);
    println!("{err}");
    assert!(
        run.status.success(),
        "a structure that reports its steps is no hang: {err}"
    );
    let rec =
        schemas::recording::Recording::read(&out.join("recording.rec")).unwrap_or_else(|e| panic!("{e}"));
    let waits: Vec<f64> = rec
        .frames
        .windows(2)
        .filter(|f| {
            f[0].participant == "mass-left"
                && matches!(f[0].message, Message::To(ToParticipant::Advance { .. }))
                && matches!(f[1].message, Message::From(FromParticipant::Advanced { .. }))
        })
        .map(|f| f[1].wall_time - f[0].wall_time)
        .collect();
    println!("mass-left's answers took {waits:?} s");
    assert_eq!(waits.len(), 4, "four windows answered by mass-left");
    // The test means something only where a window outlasts the timeout.
    assert!(
        waits.iter().any(|&w| w > 0.2),
        "no window of mass-left took longer than the 0.2 s timeout: {waits:?}; step it finer"
    );
}
