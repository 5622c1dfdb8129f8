//! Tests of `schemas::atomic_file`.

use schemas::atomic_file::*;
use std::fs;
use std::io;
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("atomic-file-{name}-{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir
}

#[test]
fn the_file_is_replaced_whole() {
    let dir = scratch("whole");
    let path = dir.join("a.pvd");
    write(&path, "old").unwrap_or_else(|e| panic!("{e}"));
    write(&path, "new contents").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(fs::read_to_string(&path).ok().as_deref(), Some("new contents"));
    assert!(!dir.join("a.pvd.tmp").exists());
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn a_failed_write_keeps_the_old_file_and_leaves_no_temporary_file() {
    let dir = scratch("failed");
    let path = dir.join("a.vtu");
    write(&path, "old").unwrap_or_else(|e| panic!("{e}"));
    let err = write_with(&path, |out| {
        out.write_all(b"half")?;
        Err(io::Error::other("disk full"))
    })
    .expect_err("the fill failed");
    assert_eq!(err.to_string(), "disk full");
    assert_eq!(fs::read_to_string(&path).ok().as_deref(), Some("old"));
    assert!(!dir.join("a.vtu.tmp").exists());
    let _ = fs::remove_dir_all(&dir);
}
