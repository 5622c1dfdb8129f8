//! Tests of `schemas::case::report`.

use schemas::case::report::*;

#[test]
fn settings_reach_tables_and_arrays_of_tables() {
    let text = "[case]\nname = \"a\"\n[[s.body]]\nmass = 1.0\n[report]\ntarget_error = 1.0\n";
    let mut s = Settings::new();
    s.insert("s.body.0.mass".into(), toml::Value::Float(2.5));
    s.insert("case.end_time".into(), toml::Value::Float(3.0));
    let out: toml::Table = apply_settings(text, &s).unwrap().parse().unwrap();
    assert_eq!(out["s"]["body"][0]["mass"].as_float(), Some(2.5));
    assert_eq!(out["case"]["end_time"].as_float(), Some(3.0));
    assert!(out.get("report").is_none());
    s.insert("s.body.1.mass".into(), toml::Value::Float(1.0));
    assert!(apply_settings(text, &s).unwrap_err().contains("s.body.1"));
}

#[test]
fn unset_removes_a_key() {
    let text = "[case]\nname = \"a\"\n[f.tank]\nsound_speed = 12.1\nspacing = 0.02\n";
    let mut s = Settings::new();
    s.insert("f.tank.sound_speed".into(), toml::Value::String(UNSET.into()));
    let out: toml::Table = apply_settings(text, &s).unwrap().parse().unwrap();
    assert!(out["f"]["tank"].get("sound_speed").is_none());
    assert_eq!(out["f"]["tank"]["spacing"].as_float(), Some(0.02));
}
