//! Adapter selection: a Vulkan adapter only (wgpu's other backends would give a device without
//! the guarantees the kernels were checked on, see crates.md), a real GPU before a software one.

use std::fmt;

/// Storage buffers the kernels bind at once ([`super::buffers`]).
pub const STORAGE_BUFFERS: u32 = 23;

/// A wgpu device and queue on a Vulkan adapter.
pub struct GpuDevice {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
}

impl fmt::Debug for GpuDevice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "GpuDevice({})", self.description())
    }
}

/// No Vulkan adapter could be opened: the message says how to get one.
#[derive(Debug, Clone, PartialEq)]
pub struct NoAdapter(pub String);

impl fmt::Display for NoAdapter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "no GPU for backend = \"gpu\": {}. Install a Vulkan driver for your GPU (on Debian/Ubuntu without a GPU, `apt-get install mesa-vulkan-drivers libvulkan1` gives the software device lavapipe, for testing only), or run on the CPU (backend = \"cpu\", the default)",
            self.0
        )
    }
}

impl std::error::Error for NoAdapter {}

impl GpuDevice {
    /// Opens the best Vulkan adapter (high performance first), with the adapter's own limits.
    pub fn open() -> Result<GpuDevice, NoAdapter> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = wgpu::Backends::VULKAN;
        let instance = wgpu::Instance::new(desc);
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            ..Default::default()
        }))
        .map_err(|e| NoAdapter(format!("no Vulkan adapter found ({e})")))?;
        let info = adapter.get_info();
        if info.backend != wgpu::Backend::Vulkan {
            return Err(NoAdapter(format!(
                "the adapter `{}` is not a Vulkan one ({:?})",
                info.name, info.backend
            )));
        }
        let have = adapter.limits().max_storage_buffers_per_shader_stage;
        if have < STORAGE_BUFFERS {
            return Err(NoAdapter(format!(
                "the adapter `{}` binds {have} storage buffers per shader, the GPU path needs {STORAGE_BUFFERS}",
                info.name
            )));
        }
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("fluid-solver"),
            required_features: wgpu::Features::empty(),
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| NoAdapter(format!("the adapter `{}` refused a device ({e})", info.name)))?;
        Ok(GpuDevice { device, queue, info })
    }

    /// Whether the adapter is a CPU emulation (lavapipe, SwiftShader): right answers, no speed.
    pub fn is_software(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }

    /// "name (driver, type)" of the adapter.
    pub fn description(&self) -> String {
        format!(
            "{} ({} {}, {:?})",
            self.info.name, self.info.driver, self.info.driver_info, self.info.device_type
        )
    }

    /// Waits until the queue's work is done.
    pub fn wait(&self) {
        // An error here means the device was lost, which the next map reports.
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
    }
}
