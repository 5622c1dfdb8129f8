//! A GPU test that finds no adapter says so where a user sees it (issue 41, item 10): without
//! `REQUIRE_GPU=1` it passes by skipping, and the harness shows nothing of a passing test's
//! output, so the skip line goes straight to the process's stderr (`gpu_common::device`).

use crate::gpu_common;

use std::process::Command;

/// Opens the device, or skips (the child of the test below).
#[test]
fn a_gpu_test_opens_the_device() {
    let Some(device) = gpu_common::device() else {
        return;
    };
    assert!(!device.description().is_empty());
}

/// The full name of [`a_gpu_test_opens_the_device`] in this binary (its module path without the
/// crate's name: the tests are modules of the package's one test binary).
fn child_test_name() -> String {
    let module = module_path!().split_once("::").map_or("", |(_, m)| m);
    format!("{module}::a_gpu_test_opens_the_device")
}

/// This test binary run again on [`a_gpu_test_opens_the_device`] alone, with the Vulkan loader
/// pointed at no driver and `REQUIRE_GPU` unset: it passes (a skip) and its stderr says that the
/// GPU path was not tested, and why.
#[test]
fn without_an_adapter_a_skipped_gpu_test_says_so_on_stderr() {
    let exe = std::env::current_exe().unwrap_or_else(|e| panic!("{e}"));
    let out = Command::new(exe)
        .args(["--exact", &child_test_name(), "--test-threads", "1"])
        .env("VK_ICD_FILENAMES", "/nonexistent/icd.json")
        .env("VK_DRIVER_FILES", "/nonexistent/icd.json")
        .env_remove("REQUIRE_GPU")
        .output()
        .unwrap_or_else(|e| panic!("cannot run the test binary: {e}"));
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(
        out.status.success(),
        "the skipped test failed:\n{stdout}\n{stderr}"
    );
    assert!(stdout.contains("1 passed"), "the child ran no test:\n{stdout}");
    assert!(
        stderr.contains("GPU test skipped, the GPU path is NOT tested here")
            && stderr.contains("REQUIRE_GPU=1"),
        "no visible skip line on stderr:\n{stderr}"
    );
}
