//! The iceoryx2 link between real processes: this test binary re-executes itself as the peer
//! (the ignored test `link_child`, selected by `LINK_ROLE`).

use schemas::link::{process_alive, Link, LinkError, Side, SUBSCRIBER_BUFFER};
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

const PARTICIPANT: &str = "echo";
/// Generous: a child process has to start, map shared memory and connect on a busy 2-core machine.
const CONNECT_TIMEOUT: Duration = Duration::from_secs(20);
const REPLY_TIMEOUT: Duration = Duration::from_secs(20);
/// Printed by a child of role `hold` or `mute` once it is connected.
const READY: &str = "LINK-CHILD-READY";

#[derive(bincode::Encode, bincode::Decode, Debug, Clone, PartialEq)]
enum Msg {
    Data { run: String, seq: u64, bytes: Vec<u8> },
    Stop,
}

/// A run id no other test (or earlier test run) uses.
fn fresh_run_id(tag: &str) -> String {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.subsec_nanos())
        .unwrap_or(0);
    format!(
        "t{}-{tag}-{}-{nanos}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    )
}

/// Deterministic payload of `len` bytes for message `seq`, so corruption or reordering shows.
fn payload(seq: u64, len: usize) -> Vec<u8> {
    (0..len)
        .map(|i| (i as u64).wrapping_mul(31).wrapping_add(seq * 7) as u8)
        .collect()
}

/// The full name of the test [`link_child`] in this binary (its module path without the crate's
/// name: the tests are modules of the package's one test binary).
fn child_test_name() -> String {
    let module = module_path!().split_once("::").map_or("", |(_, m)| m);
    format!("{module}::link_child")
}

/// A child process playing `role`; killed and reaped when dropped.
struct Peer {
    child: Child,
}

impl Peer {
    fn spawn(role: &str, run_id: &str, side: &str, stdout: Stdio) -> Peer {
        let exe = std::env::current_exe().expect("path of the test binary");
        let child = Command::new(exe)
            .args([
                child_test_name().as_str(),
                "--exact",
                "--ignored",
                "--nocapture",
                "--test-threads=1",
            ])
            .env("LINK_ROLE", role)
            .env("LINK_RUN", run_id)
            .env("LINK_SIDE", side)
            .env("LINK_PARENT", std::process::id().to_string())
            .stdout(stdout)
            .spawn()
            .expect("spawn the test binary as a peer");
        Peer { child }
    }

    /// Starts an echo participant for `run_id`.
    fn echo(run_id: &str) -> Peer {
        Peer::spawn("echo", run_id, "participant", Stdio::null())
    }

    /// `alive` closure for the link: Err once the child has exited.
    fn alive(&mut self) -> impl FnMut() -> Result<(), String> + '_ {
        move || match self.child.try_wait() {
            Ok(None) => Ok(()),
            Ok(Some(status)) => Err(format!("peer process exited: {status}")),
            Err(e) => Err(format!("cannot check the peer process: {e}")),
        }
    }

    fn sigkill(&self) {
        kill_pid(self.child.id());
    }

    /// Waits (bounded) for the child to exit and asserts it succeeded.
    fn expect_clean_exit(mut self) {
        let deadline = Instant::now() + REPLY_TIMEOUT;
        loop {
            match self.child.try_wait().expect("check the peer process") {
                Some(status) => {
                    assert!(status.success(), "peer process failed: {status}");
                    return;
                }
                None if Instant::now() > deadline => panic!("peer process did not exit"),
                None => std::thread::sleep(Duration::from_millis(10)),
            }
        }
    }

    /// Waits (bounded) until the child prints [`READY`] (children of role `hold` and `mute`).
    fn wait_ready(&mut self) {
        let stdout = self.child.stdout.take().expect("child stdout is piped");
        let (tx, rx) = std::sync::mpsc::channel();
        // The test harness prints `test link_child ... ` before the marker on the same line.
        std::thread::spawn(move || {
            let ready = BufReader::new(stdout)
                .lines()
                .map_while(Result::ok)
                .any(|l| l.contains(READY));
            let _ = tx.send(ready);
        });
        let ready = rx.recv_timeout(CONNECT_TIMEOUT).unwrap_or(false);
        assert!(
            ready,
            "peer process did not print {READY} within {CONNECT_TIMEOUT:?}"
        );
    }
}

impl Drop for Peer {
    fn drop(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            self.sigkill();
        }
        let _ = self.child.wait();
    }
}

fn kill_pid(pid: u32) {
    let pid = libc::pid_t::try_from(pid).expect("pid fits pid_t");
    // SAFETY: plain kill(2) of our own child.
    unsafe { libc::kill(pid, libc::SIGKILL) };
}

/// Sends `count` messages of each size, each echoed back, and checks every reply.
fn ping_pong(link: &Link, peer: &mut Peer, run: &str, sizes: &[usize], count: u64) {
    let mut seq = 0;
    for _ in 0..count {
        for &len in sizes {
            let sent = Msg::Data {
                run: run.to_owned(),
                seq,
                bytes: payload(seq, len),
            };
            link.send(&sent).expect("send to the echo peer");
            let deadline = Some(Instant::now() + REPLY_TIMEOUT);
            let got: Msg = link.recv(deadline, &mut peer.alive()).expect("echo reply");
            assert!(
                got == sent,
                "reply {seq} ({len} bytes) differs from what was sent"
            );
            seq += 1;
        }
    }
}

fn connect_coupler(run: &str, peer: &mut Peer) -> Link {
    let link = Link::open(run, PARTICIPANT, Side::Coupler).expect("open the coupler side");
    link.wait_for_peer(Instant::now() + CONNECT_TIMEOUT, &mut peer.alive())
        .expect("peer connects");
    link
}

fn stop(link: &Link, peer: Peer) {
    link.send(&Msg::Stop).expect("send Stop");
    peer.expect_clean_exit();
}

#[test]
fn messages_of_8_bytes_to_100_megabytes_arrive_intact_and_in_order() {
    let run = fresh_run_id("pingpong");
    let mut peer = Peer::echo(&run);
    let link = connect_coupler(&run, &mut peer);
    assert_eq!(
        link.peer_pid(),
        Some(peer.child.id()),
        "the link finds the peer's pid"
    );
    // Small after large too: the publisher's grown shared memory must still serve small messages.
    ping_pong(&link, &mut peer, &run, &[8, 10_000, 4_000_000, 8], 5);
    // The largest message the solvers send is about 100 MB (issue); once is enough.
    ping_pong(&link, &mut peer, &run, &[100_000_000, 8], 1);
    stop(&link, peer);
}

#[test]
fn several_messages_in_a_row_are_all_delivered() {
    let run = fresh_run_id("burst");
    let mut peer = Peer::echo(&run);
    let link = connect_coupler(&run, &mut peer);
    // Three times the subscriber buffer: the sender must wait for the echo instead of dropping.
    let n = 3 * SUBSCRIBER_BUFFER as u64;
    let pid = peer.child.id();
    let replies = std::thread::scope(|s| {
        let reader = s.spawn(|| {
            let mut alive = || process_alive(pid);
            (0..n)
                .map(|_| link.recv::<Msg>(Some(Instant::now() + REPLY_TIMEOUT), &mut alive))
                .collect::<Result<Vec<_>, _>>()
        });
        for seq in 0..n {
            link.send(&Msg::Data {
                run: run.clone(),
                seq,
                bytes: payload(seq, 1000),
            })
            .expect("send");
        }
        reader.join().expect("reader thread")
    })
    .expect("all replies");
    for (seq, got) in (0..n).zip(&replies) {
        assert_eq!(
            got,
            &Msg::Data {
                run: run.clone(),
                seq,
                bytes: payload(seq, 1000)
            }
        );
    }
    stop(&link, peer);
}

#[test]
fn killed_peer_is_reported_by_recv_within_one_second() {
    let run = fresh_run_id("death");
    let mut peer = Peer::echo(&run);
    let link = connect_coupler(&run, &mut peer);
    ping_pong(&link, &mut peer, &run, &[8], 1);
    let pid = peer.child.id();
    let killed_at = std::thread::scope(|s| {
        let killer = s.spawn(move || {
            std::thread::sleep(Duration::from_millis(300));
            kill_pid(pid);
            Instant::now()
        });
        let result = link.recv::<Msg>(None, &mut peer.alive());
        let returned_at = Instant::now();
        let killed_at = killer.join().expect("killer thread");
        assert!(
            matches!(result, Err(LinkError::PeerGone(_))),
            "recv returned {result:?}"
        );
        returned_at.duration_since(killed_at)
    });
    // Issue requirement: PeerGone within 1 s of the kill.
    println!("recv reported PeerGone {killed_at:?} after the SIGKILL");
    assert!(
        killed_at < Duration::from_secs(1),
        "PeerGone came {killed_at:?} after the kill"
    );
}

#[test]
fn send_to_a_killed_peer_with_a_full_buffer_fails_instead_of_hanging() {
    let run = fresh_run_id("fullbuf");
    let mut peer = Peer::spawn("mute", &run, "participant", Stdio::null());
    let link = connect_coupler(&run, &mut peer);
    assert!(link.peer_pid().is_some());
    for seq in 0..SUBSCRIBER_BUFFER as u64 {
        link.send(&Msg::Data {
            run: run.clone(),
            seq,
            bytes: vec![1; 8],
        })
        .expect("fill the peer's buffer");
    }
    let pid = peer.child.id();
    let outcome = std::thread::scope(|s| {
        s.spawn(move || {
            std::thread::sleep(Duration::from_millis(300));
            kill_pid(pid);
        });
        link.send(&Msg::Stop)
    });
    assert!(
        matches!(outcome, Err(LinkError::PeerGone(_))),
        "send returned {outcome:?}"
    );
}

#[test]
fn a_run_after_a_sigkilled_run_works_with_the_same_and_a_new_run_id() {
    let run = fresh_run_id("restart");
    // A whole run (coupler and participant processes) killed with SIGKILL while connected.
    let mut coupler = Peer::spawn("hold", &run, "coupler", Stdio::piped());
    let mut participant = Peer::spawn("hold", &run, "participant", Stdio::piped());
    coupler.wait_ready();
    participant.wait_ready();
    drop(coupler);
    drop(participant);

    // Same run id: opening the node cleans the dead nodes' shared memory up.
    let mut peer = Peer::echo(&run);
    let link = connect_coupler(&run, &mut peer);
    ping_pong(&link, &mut peer, &run, &[8, 10_000], 3);
    // Now kill the participant in the middle of the run and restart it under the same link.
    drop(peer);
    drop(link);
    let mut peer = Peer::echo(&run);
    let link = connect_coupler(&run, &mut peer);
    ping_pong(&link, &mut peer, &run, &[8, 10_000], 3);
    stop(&link, peer);

    let new_run = fresh_run_id("restart-new");
    let mut peer = Peer::echo(&new_run);
    let link = connect_coupler(&new_run, &mut peer);
    ping_pong(&link, &mut peer, &new_run, &[8, 10_000], 3);
    stop(&link, peer);
}

#[test]
fn two_runs_at_once_do_not_see_each_others_messages() {
    let (run_a, run_b) = (fresh_run_id("iso-a"), fresh_run_id("iso-b"));
    let mut peer_a = Peer::echo(&run_a);
    let mut peer_b = Peer::echo(&run_b);
    let link_a = connect_coupler(&run_a, &mut peer_a);
    let link_b = connect_coupler(&run_b, &mut peer_b);
    for seq in 0..10 {
        // The echo child checks the run id in every message and fails on a foreign one.
        let to_a = Msg::Data {
            run: run_a.clone(),
            seq,
            bytes: payload(seq, 64),
        };
        let to_b = Msg::Data {
            run: run_b.clone(),
            seq,
            bytes: payload(seq + 1000, 64),
        };
        link_a.send(&to_a).expect("send on run a");
        link_b.send(&to_b).expect("send on run b");
        let deadline = Some(Instant::now() + REPLY_TIMEOUT);
        assert_eq!(
            link_a
                .recv::<Msg>(deadline, &mut peer_a.alive())
                .expect("reply on a"),
            to_a
        );
        assert_eq!(
            link_b
                .recv::<Msg>(deadline, &mut peer_b.alive())
                .expect("reply on b"),
            to_b
        );
    }
    assert_eq!(
        link_a.try_recv::<Msg>().expect("poll a"),
        None,
        "run a got an extra message"
    );
    assert_eq!(
        link_b.try_recv::<Msg>().expect("poll b"),
        None,
        "run b got an extra message"
    );
    stop(&link_a, peer_a);
    stop(&link_b, peer_b);
}

#[test]
fn recv_times_out_at_its_deadline_and_checks_alive() {
    let run = fresh_run_id("timeout");
    let mut peer = Peer::spawn("mute", &run, "participant", Stdio::null());
    let link = connect_coupler(&run, &mut peer);
    let start = Instant::now();
    let mut checks = 0;
    let result = link.recv::<Msg>(Some(start + Duration::from_millis(350)), &mut || {
        checks += 1;
        Ok(())
    });
    let waited = start.elapsed();
    assert_eq!(result, Err(LinkError::Timeout));
    assert!(
        waited >= Duration::from_millis(350) && waited < Duration::from_millis(1000),
        "{waited:?}"
    );
    // Waits are at most 100 ms, so `alive` ran at least 350 / 100 = 3 times.
    assert!(checks >= 3, "alive checked only {checks} times");
}

#[test]
fn wait_for_peer_times_out_without_a_peer_and_reports_a_dead_one() {
    let run = fresh_run_id("nopeer");
    let link = Link::open(&run, PARTICIPANT, Side::Coupler).expect("open");
    let start = Instant::now();
    let result = link.wait_for_peer(start + Duration::from_millis(200), &mut || Ok(()));
    assert_eq!(result, Err(LinkError::Timeout));
    assert!(start.elapsed() < Duration::from_secs(1));
    let result = link.wait_for_peer(Instant::now() + CONNECT_TIMEOUT, &mut || Err("it crashed".into()));
    assert_eq!(result, Err(LinkError::PeerGone("it crashed".into())));
    // Sending before the peer is connected would lose the message: it is an error instead.
    assert!(matches!(link.send(&Msg::Stop), Err(LinkError::NotConnected(_))));
}

#[test]
fn bad_names_and_a_second_coupler_are_clear_errors() {
    assert!(matches!(
        Link::open("run/1", PARTICIPANT, Side::Coupler),
        Err(LinkError::InvalidName(_))
    ));
    assert!(matches!(
        Link::open("run", "", Side::Participant),
        Err(LinkError::InvalidName(_))
    ));
    let run = fresh_run_id("twice");
    let _first = Link::open(&run, PARTICIPANT, Side::Coupler).expect("open");
    match Link::open(&run, PARTICIPANT, Side::Coupler) {
        Err(LinkError::Iceoryx(msg)) => assert!(msg.contains("another process"), "{msg}"),
        other => panic!("second coupler on one run: {:?}", other.map(|_| "a link")),
    }
}

/// Child process roles (run by the tests above, never on its own):
/// - `echo`: participant that returns every message until `Stop`, checking the run id;
/// - `mute`: participant that connects and then never reads;
/// - `hold`: either side, connects, prints [`READY`] and sleeps until killed.
#[test]
#[ignore = "peer process role, started by the other tests of this file"]
fn link_child() {
    let role = std::env::var("LINK_ROLE").expect("LINK_ROLE");
    let run = std::env::var("LINK_RUN").expect("LINK_RUN");
    let side = match std::env::var("LINK_SIDE").expect("LINK_SIDE").as_str() {
        "coupler" => Side::Coupler,
        _ => Side::Participant,
    };
    let parent: u32 = std::env::var("LINK_PARENT")
        .expect("LINK_PARENT")
        .parse()
        .expect("parent pid");
    let mut parent_alive = move || process_alive(parent);
    let link = Link::open(&run, PARTICIPANT, side).expect("child opens its side");
    link.wait_for_peer(Instant::now() + CONNECT_TIMEOUT, &mut parent_alive)
        .expect("child connects");
    match role.as_str() {
        "echo" => loop {
            match link.recv::<Msg>(None, &mut parent_alive).expect("child receives") {
                Msg::Stop => return,
                Msg::Data { run: msg_run, .. } if msg_run != run => {
                    panic!("run {run} received a message of run {msg_run}")
                }
                msg => {
                    link.send(&msg).expect("child echoes");
                }
            }
        },
        "mute" | "hold" => {
            println!("{READY}");
            while parent_alive().is_ok() {
                std::thread::sleep(Duration::from_millis(50));
            }
        }
        other => panic!("unknown LINK_ROLE {other}"),
    }
}

#[test]
fn both_sides_in_one_process_exchange_empty_and_unit_messages() {
    // Also shows that a Link can move to another thread (the coupler may run one per participant).
    let run = fresh_run_id("inproc");
    let participant = Link::open(&run, PARTICIPANT, Side::Participant).expect("open participant");
    let coupler = Link::open(&run, PARTICIPANT, Side::Coupler).expect("open coupler");
    let deadline = Instant::now() + CONNECT_TIMEOUT;
    let participant = std::thread::spawn(move || {
        participant
            .wait_for_peer(deadline, &mut || Ok(()))
            .map(|()| participant)
    });
    coupler
        .wait_for_peer(deadline, &mut || Ok(()))
        .expect("coupler connects");
    let participant = participant
        .join()
        .expect("participant thread")
        .expect("participant connects");
    assert_eq!(coupler.peer_pid(), Some(std::process::id()));
    // Calling it again once connected returns at once.
    coupler
        .wait_for_peer(Instant::now(), &mut || Ok(()))
        .expect("second wait_for_peer");

    assert_eq!(coupler.send(&()).expect("send ()"), 0, "() encodes to zero bytes");
    participant
        .recv::<()>(Some(Instant::now() + REPLY_TIMEOUT), &mut || Ok(()))
        .expect("recv ()");
    assert_eq!(participant.send(&Vec::<u8>::new()).expect("send empty vec"), 1);
    let got: Vec<u8> = coupler
        .recv(Some(Instant::now() + REPLY_TIMEOUT), &mut || Ok(()))
        .expect("recv");
    assert!(got.is_empty());
    // bincode carries no type tags; a message of another type is caught when its bytes do not
    // decode to exactly one value of the expected type (here: 2 bytes of string, 14 left over).
    participant.send(&vec![1.5f64, 2.5]).expect("send floats");
    let wrong = coupler.recv::<String>(Some(Instant::now() + REPLY_TIMEOUT), &mut || Ok(()));
    assert!(matches!(wrong, Err(LinkError::Decode(_))), "{wrong:?}");
}
