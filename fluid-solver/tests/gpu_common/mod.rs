//! The GPU tests' device: lavapipe in CI (`.ci/run` installs it), a real GPU where there is one.
//! Without an adapter a test is skipped with a line on the process's stderr that the test harness
//! does not capture (`gpu_skips.rs`), unless `REQUIRE_GPU=1`: then it fails, so that CI cannot
//! pass green without running the GPU code.

pub mod compare;
pub mod probe_rows;

use fluid_solver::gpu::GpuDevice;
use std::io::Write;

/// The device, or `None` (skip) when there is none and `REQUIRE_GPU` is not `1`.
pub fn device() -> Option<GpuDevice> {
    match GpuDevice::open() {
        Ok(d) => {
            eprintln!("GPU: {}", d.description());
            Some(d)
        }
        Err(e) if std::env::var("REQUIRE_GPU").as_deref() == Ok("1") => {
            panic!("REQUIRE_GPU=1 and no GPU adapter: {e}")
        }
        Err(e) => {
            // Straight to the process's stderr: the test harness captures `eprintln!` of a test
            // that passes, and a skipped test passes, so the line would never be seen.
            let _ = writeln!(
                std::io::stderr(),
                "GPU test skipped, the GPU path is NOT tested here: {e}; set REQUIRE_GPU=1 to fail instead, or install Mesa's software Vulkan device (mesa-vulkan-drivers) to run it"
            );
            None
        }
    }
}
