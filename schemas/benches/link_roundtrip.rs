//! Round trips over the iceoryx2 link between this process and a real echo peer process (this
//! binary re-executed with `LINK_BENCH_ROLE=echo`), compared with a plain `copy_from_slice`, and
//! the CPU time the waiting side burns.
//!
//! Run: `cargo bench -p schemas --bench link_roundtrip`.
//! Reference (crates.md, measured here): iceoryx2 + events ≈ 14 µs round trip; preCICE over
//! sockets 50–65 µs for one value and ≈ 4 ms for 800 kB. Goals: ≤ 20 µs for small messages,
//! waiting side ≤ 2 % of a core.

use schemas::link::{process_alive, Link, LinkError, Side};
use std::fmt::Display;
use std::hint::black_box;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const PARTICIPANT: &str = "bench";
const CONNECT_TIMEOUT: Duration = Duration::from_secs(30);

#[derive(bincode::Encode, bincode::Decode)]
enum BenchMsg {
    Payload(Vec<u8>),
    Stop,
}

/// Prints `what` and the error, then exits: a benchmark has nobody to hand errors to.
fn or_die<T, E: Display>(result: Result<T, E>, what: &str) -> T {
    result.unwrap_or_else(|e| {
        eprintln!("link_roundtrip: {what}: {e}");
        std::process::exit(1)
    })
}

fn env(name: &str) -> String {
    or_die(std::env::var(name), name)
}

/// The echo peer: returns every payload, after `LINK_BENCH_WORK_US` µs of busy work.
fn run_echo_peer() {
    let run = env("LINK_BENCH_RUN");
    let work = Duration::from_micros(or_die(env("LINK_BENCH_WORK_US").parse(), "LINK_BENCH_WORK_US"));
    let parent: u32 = or_die(env("LINK_BENCH_PARENT").parse(), "LINK_BENCH_PARENT");
    let mut alive = move || process_alive(parent);
    let link = or_die(
        Link::open(&run, PARTICIPANT, Side::Participant),
        "peer opens the link",
    );
    or_die(
        link.wait_for_peer(Instant::now() + CONNECT_TIMEOUT, &mut alive),
        "peer connects",
    );
    loop {
        match or_die(link.recv::<BenchMsg>(None, &mut alive), "peer receives") {
            BenchMsg::Stop => return,
            msg => {
                busy_work(work);
                or_die(link.send(&msg), "peer echoes");
            }
        }
    }
}

/// Stands in for a solver step: keeps the core busy for `work`.
fn busy_work(work: Duration) {
    let start = Instant::now();
    while start.elapsed() < work {
        std::hint::spin_loop();
    }
}

/// CPU time (user + system) of the calling thread.
fn thread_cpu_time() -> Duration {
    // SAFETY: getrusage only writes the struct it is given.
    let usage = unsafe {
        let mut usage = std::mem::zeroed::<libc::rusage>();
        libc::getrusage(libc::RUSAGE_THREAD, &mut usage);
        usage
    };
    rusage_time(&usage)
}

fn rusage_time(usage: &libc::rusage) -> Duration {
    let tv = |t: libc::timeval| Duration::new(t.tv_sec as u64, t.tv_usec as u32 * 1000);
    tv(usage.ru_utime) + tv(usage.ru_stime)
}

/// One measured series against one freshly started peer.
struct Series {
    round_trips: Vec<Duration>,
    wall: Duration,
    main_cpu: Duration,
    peer_cpu: Duration,
}

impl Series {
    fn percentile(&self, p: usize) -> f64 {
        let mut sorted = self.round_trips.clone();
        sorted.sort();
        let i = (sorted.len() * p / 100).min(sorted.len() - 1);
        sorted[i].as_secs_f64() * 1e6
    }

    fn cpu_percent(&self, cpu: Duration) -> f64 {
        100.0 * cpu.as_secs_f64() / self.wall.as_secs_f64()
    }
}

/// Starts an echo peer doing `work_us` of work per message and times `count` round trips of `len` bytes.
fn measure(len: usize, count: usize, work_us: u64) -> Series {
    static RUNS: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
    let run = format!(
        "bench-{}-{}",
        std::process::id(),
        RUNS.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
    );
    let exe = or_die(std::env::current_exe(), "path of the benchmark binary");
    let mut child = or_die(
        Command::new(exe)
            .env("LINK_BENCH_ROLE", "echo")
            .env("LINK_BENCH_RUN", &run)
            .env("LINK_BENCH_WORK_US", work_us.to_string())
            .env("LINK_BENCH_PARENT", std::process::id().to_string())
            .stdout(Stdio::null())
            .spawn(),
        "spawn the echo peer",
    );
    let mut alive = || match child.try_wait() {
        Ok(None) => Ok(()),
        Ok(Some(status)) => Err(format!("echo peer exited: {status}")),
        Err(e) => Err(e.to_string()),
    };
    let link = or_die(Link::open(&run, PARTICIPANT, Side::Coupler), "open the link");
    or_die(
        link.wait_for_peer(Instant::now() + CONNECT_TIMEOUT, &mut alive),
        "peer connects",
    );

    let msg = BenchMsg::Payload((0..len).map(|i| i as u8).collect());
    let round_trip = |alive: &mut dyn FnMut() -> Result<(), String>| -> Result<Duration, LinkError> {
        let start = Instant::now();
        link.send(&msg)?;
        let reply = link.recv::<BenchMsg>(None, alive)?;
        let took = start.elapsed();
        black_box(reply);
        Ok(took)
    };
    for _ in 0..(count / 10).max(5) {
        or_die(round_trip(&mut alive), "warm-up round trip");
    }
    let (wall_start, cpu_start) = (Instant::now(), thread_cpu_time());
    let round_trips: Vec<Duration> = (0..count)
        .map(|_| or_die(round_trip(&mut alive), "round trip"))
        .collect();
    let (wall, main_cpu) = (wall_start.elapsed(), thread_cpu_time() - cpu_start);

    or_die(link.send(&BenchMsg::Stop), "stop the peer");
    let peer_cpu = reap_cpu_time(child.id());
    Series {
        round_trips,
        wall,
        main_cpu,
        peer_cpu,
    }
}

/// Waits for the peer to exit and returns the CPU time it used over its whole life.
fn reap_cpu_time(pid: u32) -> Duration {
    let pid = or_die(libc::pid_t::try_from(pid), "peer pid");
    // SAFETY: wait4 writes only the status and rusage it is given; the pid is our child.
    let usage = unsafe {
        let mut status = 0;
        let mut usage = std::mem::zeroed::<libc::rusage>();
        if libc::wait4(pid, &mut status, 0, &mut usage) != pid {
            eprintln!(
                "link_roundtrip: cannot reap the echo peer: {}",
                std::io::Error::last_os_error()
            );
            std::process::exit(1);
        }
        usage
    };
    rusage_time(&usage)
}

/// Median time (µs) of `op` on a `len`-byte payload, timed in batches so tiny copies are visible.
fn median_copy_time(len: usize, mut op: impl FnMut(&[u8])) -> f64 {
    let src: Vec<u8> = (0..len).map(|i| i as u8).collect();
    let batch = (1 << 20) / len.max(64) + 1;
    let mut samples: Vec<f64> = (0..200)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..batch {
                op(black_box(&src));
            }
            start.elapsed().as_secs_f64() * 1e6 / batch as f64
        })
        .collect();
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}

/// A plain `copy_from_slice` into a buffer allocated once (cache-hot).
fn copy_time(len: usize) -> f64 {
    let mut dst = vec![0u8; len];
    median_copy_time(len, |src| black_box(&mut dst).copy_from_slice(src))
}

/// Allocating a new `Vec` and copying into it: what a receiver of an owned message pays at least.
fn alloc_copy_time(len: usize) -> f64 {
    median_copy_time(len, |src| drop(black_box(src.to_vec())))
}

fn main() {
    if std::env::var("LINK_BENCH_ROLE").is_ok() {
        run_echo_peer();
        return;
    }
    println!("iceoryx2 link round trips to an echo peer process (bincode Vec<u8> messages)");
    println!("one-way = round trip / 2: encode into shared memory + wake-up + decode out of it (2 copies)");
    println!("copy = copy_from_slice into a reused buffer; alloc+copy = to_vec (new Vec each time)");
    println!("per copy = (one-way - one-way of 8 B) / 2: the size-dependent cost of each of the 2 copies");
    println!(
        "{:>7} {:>6} {:>10} {:>8} {:>10} {:>8} {:>13} {:>12} {:>12} {:>15} {:>9} {:>9}",
        "payload",
        "trips",
        "median µs",
        "p99 µs",
        "one-way µs",
        "copy µs",
        "alloc+copy µs",
        "one-way/copy",
        "per copy µs",
        "per copy/copy",
        "main CPU%",
        "peer CPU%"
    );
    let mut small_one_way = None;
    for (label, len, count) in [
        ("8 B", 8, 20_000),
        ("10 kB", 10_000, 10_000),
        ("1 MB", 1_000_000, 1_000),
    ] {
        let s = measure(len, count, 0);
        let one_way = s.percentile(50) / 2.0;
        let base = *small_one_way.get_or_insert(one_way);
        let per_copy = (one_way - base).max(0.0) / 2.0;
        let (copy, alloc_copy) = (copy_time(len), alloc_copy_time(len));
        println!(
            "{label:>7} {count:>6} {:>10.1} {:>8.1} {one_way:>10.1} {copy:>8.2} {alloc_copy:>13.2} {:>12.2} \
             {per_copy:>12.2} {:>15.2} {:>9.1} {:>9.1}",
            s.percentile(50),
            s.percentile(99),
            one_way / copy,
            per_copy / copy,
            s.cpu_percent(s.main_cpu),
            s.cpu_percent(s.peer_cpu),
        );
    }
    println!();
    println!("waiting on a peer that computes before each reply (the coupler waiting for a solver)");
    println!(
        "{:>9} {:>9} {:>7} {:>11} {:>9} {:>13} {:>20}",
        "payload", "work µs", "trips", "median µs", "p99 µs", "overhead µs", "waiting CPU % core"
    );
    for work_us in [1_000u64, 10_000] {
        let count = if work_us >= 10_000 { 100 } else { 1_000 };
        let s = measure(8, count, work_us);
        let median = s.percentile(50);
        println!(
            "{:>9} {work_us:>9} {count:>7} {median:>11.1} {:>9.1} {:>13.1} {:>20.2}",
            "8 B",
            s.percentile(99),
            median - work_us as f64,
            s.cpu_percent(s.main_cpu),
        );
    }
}
