//! Tests of `schemas::checkpoint`.

use schemas::checkpoint::*;
use serde::Serialize;
use std::fs::{self};

#[derive(Debug, PartialEq, Serialize, serde::Deserialize)]
struct State {
    window: u64,
    values: Vec<f64>,
    name: String,
}

#[test]
fn a_state_reads_back_bit_for_bit_and_damage_is_reported() {
    let dir = std::env::temp_dir().join(format!("checkpoint-test-{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join("s.bin");
    let state = State {
        window: 7,
        values: vec![0.1 + 0.2, -0.0, f64::MIN_POSITIVE, 1e300],
        name: "tank".into(),
    };
    write(&path, &state, &mut schemas::participant::DiscardProgress).unwrap_or_else(|e| panic!("{e}"));
    let back: State = read(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back, state);
    assert!(back
        .values
        .iter()
        .zip(&state.values)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    assert!(!dir.join("s.bin.tmp").exists());
    let mut bytes = fs::read(&path).unwrap_or_default();
    let last = bytes.len() - 1;
    bytes[last] ^= 1;
    fs::write(&path, &bytes).unwrap_or_else(|e| panic!("{e}"));
    let err = read::<State>(&path).expect_err("a flipped bit");
    assert!(err.contains("damaged"), "{err}");
    fs::write(&path, &bytes[..bytes.len() - 3]).unwrap_or_else(|e| panic!("{e}"));
    let err = read::<State>(&path).expect_err("cut");
    assert!(err.contains("cut short"), "{err}");
    let _ = fs::remove_dir_all(&dir);
}
