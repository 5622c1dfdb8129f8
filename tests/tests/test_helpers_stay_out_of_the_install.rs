//! The fault-injecting `faulty-participant` is a test helper: it must not be a binary target, or
//! `cargo build --release` and `cargo install` would put it beside the real solvers.

use std::process::Command;

#[test]
fn faulty_participant_is_an_example_not_a_binary() {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args(["metadata", "--no-deps", "--format-version", "1", "--offline"])
        .current_dir(stack_tests::workspace())
        .output()
        .unwrap_or_else(|e| panic!("cannot run cargo metadata: {e}"));
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let meta = String::from_utf8_lossy(&out.stdout);
    // Each target is `{"kind":["bin"],…,"name":"…"`: find the one named faulty-participant.
    let target = meta
        .split("{\"kind\":")
        .find(|t| t.contains("\"name\":\"faulty-participant\""))
        .unwrap_or_else(|| panic!("no faulty-participant target"));
    assert!(
        target.starts_with("[\"example\"]"),
        "faulty-participant must be an example: {target}"
    );
    let mut bins: Vec<&str> = meta
        .split("{\"kind\":[\"bin\"]")
        .skip(1)
        .filter_map(|t| t.split("\"name\":\"").nth(1)?.split('"').next())
        .collect();
    bins.sort_unstable();
    assert_eq!(
        bins,
        ["coupler", "fluid-solver", "structure-solver"],
        "installed binaries"
    );
}
