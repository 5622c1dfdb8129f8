//! What the fluid benchmarks read about their own process and machine (Linux; neutral values
//! elsewhere).

/// CPU seconds this process has used (user + system, from /proc/self/stat; 0 where absent):
/// on a loaded machine the wall time counts other processes' turns, the CPU time does not.
pub fn cpu_seconds() -> f64 {
    let ticks_per_second = 100.0; // USER_HZ on Linux
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            let rest = &s[s.rfind(')')? + 2..];
            let f: Vec<&str> = rest.split_whitespace().collect();
            Some((f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?) / ticks_per_second)
        })
        .unwrap_or(0.0)
}

/// The 1-minute load average (other processes share the cores).
#[allow(dead_code)] // surface_mesh reads only the CPU time
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_owned))
        .unwrap_or_else(|| "?".into())
}
