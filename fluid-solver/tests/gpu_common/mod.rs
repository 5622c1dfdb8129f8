//! The GPU tests' device: lavapipe in CI (`.ci/run` installs it), a real GPU where there is one.
//! Without an adapter a test is skipped with a line on stderr, unless `REQUIRE_GPU=1`: then it
//! fails, so that CI cannot pass green without running the GPU code.

use fluid_solver::gpu::GpuDevice;

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
            eprintln!("skipped (set REQUIRE_GPU=1 to fail instead): {e}");
            None
        }
    }
}
