//! The one GPU device the daemon owns, shared by every client's executor.

use std::sync::Arc;

use tracing::{error, info};

/// Why no GPU device could be opened.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter matched.
    #[error("no Vulkan adapter found ({0}); on Debian install mesa-vulkan-drivers and libvulkan1")]
    NoAdapter(String),
    /// The adapter refused to open a device.
    #[error("opening the device failed: {0}")]
    Device(#[from] wgpu::RequestDeviceError),
}

/// The device and queue every executor draws with.
pub struct Gpu {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Adapter name, driver and backend, for logs and `GL_RENDERER`.
    pub info: wgpu::AdapterInfo,
    /// The device's limits.
    pub limits: wgpu::Limits,
}

impl Gpu {
    /// Opens the first Vulkan adapter (lavapipe on machines without a GPU). The uncaptured
    /// error handler only logs: errors are charged to clients through error scopes.
    pub fn open() -> Result<Arc<Gpu>, GpuError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN,
            flags: wgpu::InstanceFlags::empty(),
            memory_budget_thresholds: Default::default(),
            backend_options: Default::default(),
            display: None,
        });
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        }))
        .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        let info = adapter.get_info();
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("stratad"),
            required_features: wgpu::Features::empty(),
            required_limits: limits.clone(),
            experimental_features: Default::default(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))?;
        device.on_uncaptured_error(Arc::new(|e: wgpu::Error| error!("uncaptured GPU error: {e}")));
        info!(adapter = %info.name, driver = %info.driver, "GPU opened");
        Ok(Arc::new(Gpu { device, queue, info, limits }))
    }
}
