//! Opening a device: its own instance (on lavapipe a separate rasterizer), the optional
//! features the executor uses, external memory for shared surfaces, and the queue's global
//! priority (`VK_KHR_global_priority`/`VK_EXT_global_priority`) where the adapter offers it.
//!
//! A device's driver threads (lavapipe's queue and rasterizer threads) inherit the scheduling
//! of the thread that creates the device, so [`Gpu::open_with`] is called on a thread already
//! at the class's nice value ([`crate::nice_for`], [`crate::set_thread_nice`]).

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use ash::vk;
use strata_protocol::control::Priority;
use tracing::{debug, error, info};
use wgpu::hal::api::Vulkan;

use crate::gpu::{Gpu, GpuError, OPTIONAL_FEATURES};
use crate::lane::Lane;
use crate::process::{EnvOverride, RASTERIZER_THREADS};
use crate::threads::{ours, set_thread_idle, set_thread_slice, slice_for, task_ids};

/// What a device is opened for.
#[derive(Clone)]
pub struct DeviceOptions {
    /// The queue's class: its global priority where the adapter offers one.
    pub priority: Priority,
    /// Ask for a global priority at all (`--no-global-priority` turns it off to compare).
    pub global_priority: bool,
    /// The device's label in logs and validation messages.
    pub label: &'static str,
    /// Rasterizer threads of a CPU rasterizer's device (llvmpipe's `LP_NUM_THREADS`, read
    /// when the instance is created; `None`: the driver's default, one per core).
    pub rasterizer_threads: Option<u32>,
}

impl Default for DeviceOptions {
    fn default() -> Self {
        DeviceOptions { priority: Priority::Normal, global_priority: true, label: "stratad", rasterizer_threads: None }
    }
}

/// The queue global priority a class asks for.
fn global_priority(class: Priority) -> vk::QueueGlobalPriorityKHR {
    match class {
        Priority::High => vk::QueueGlobalPriorityKHR::HIGH,
        Priority::Normal => vk::QueueGlobalPriorityKHR::MEDIUM,
        Priority::Low => vk::QueueGlobalPriorityKHR::LOW,
    }
}

/// The name of a granted global priority, for logs and `ctl stats`.
pub fn priority_name(p: vk::QueueGlobalPriorityKHR) -> &'static str {
    match p {
        vk::QueueGlobalPriorityKHR::LOW => "low",
        vk::QueueGlobalPriorityKHR::MEDIUM => "medium",
        vk::QueueGlobalPriorityKHR::HIGH => "high",
        vk::QueueGlobalPriorityKHR::REALTIME => "realtime",
        _ => "unknown",
    }
}

/// Held while a device opens.
static OPENING: Mutex<()> = Mutex::new(());

/// Whether the adapter offers a queue global priority, and the extension to enable for it.
fn global_priority_extension(adapter: &wgpu::Adapter) -> Option<&'static std::ffi::CStr> {
    // SAFETY: only enumerates the physical device's extensions.
    unsafe {
        let hal = adapter.as_hal::<Vulkan>()?;
        let instance = hal.shared_instance().raw_instance();
        let exts = instance.enumerate_device_extension_properties(hal.raw_physical_device()).ok()?;
        let has = |name: &std::ffi::CStr| exts.iter().any(|e| e.extension_name_as_c_str() == Ok(name));
        if has(ash::khr::global_priority::NAME) {
            Some(ash::khr::global_priority::NAME)
        } else if has(ash::ext::global_priority::NAME) {
            Some(ash::ext::global_priority::NAME)
        } else {
            None
        }
    }
}

/// Opens a device on `adapter` with the queue at `priority` (`None`: the driver's default).
fn open_device(
    adapter: &wgpu::Adapter,
    desc: &wgpu::DeviceDescriptor<'_>,
    priority: Option<(&'static std::ffi::CStr, vk::QueueGlobalPriorityKHR)>,
) -> Result<(wgpu::Device, wgpu::Queue), GpuError> {
    let Some((ext, level)) = priority else {
        return Ok(pollster::block_on(adapter.request_device(desc))?);
    };
    // SAFETY: the callback only adds an extension the adapter offers and chains the queue's
    // priority, which that extension defines; the device is handed to wgpu from this adapter.
    unsafe {
        let hal = adapter.as_hal::<Vulkan>().ok_or(GpuError::Priority)?;
        let mut prio = vk::DeviceQueueGlobalPriorityCreateInfoKHR::default().global_priority(level);
        let prio_ref = &mut prio;
        let callback: Box<wgpu::hal::vulkan::CreateDeviceCallback<'_>> = Box::new(move |args| {
            if !args.extensions.contains(&ext) {
                args.extensions.push(ext);
            }
            if let Some(q) = args.queue_create_infos.first_mut() {
                *q = q.push_next(prio_ref);
            }
        });
        let open = hal
            .open_with_callback(desc.required_features, &desc.required_limits, &desc.memory_hints, Some(callback))
            .map_err(|_| GpuError::Priority)?;
        drop(hal);
        Ok(adapter.create_device_from_hal(open, desc)?)
    }
}

impl Gpu {
    /// Opens the first Vulkan adapter (lavapipe on machines without a GPU) with default
    /// options.
    pub fn open() -> Result<Arc<Gpu>, GpuError> {
        Gpu::open_with(DeviceOptions::default())
    }

    /// Opens a device of its own: a new instance, the first Vulkan adapter, and a queue at the
    /// global priority of `opts.priority` where the adapter offers one (falling back to lower
    /// ones, then none, when the driver refuses). The uncaptured error handler only logs:
    /// errors are charged to clients through error scopes.
    pub fn open_with(opts: DeviceOptions) -> Result<Arc<Gpu>, GpuError> {
        // On a thread of its own, which inherits the caller's nice value and hands it, and its
        // name, to the threads the driver starts.
        let name = format!("gpu-{}", opts.label);
        std::thread::scope(|s| {
            std::thread::Builder::new()
                .name(name)
                .spawn_scoped(s, || Gpu::open_here(opts))
                .map_err(|e| GpuError::NoAdapter(format!("starting the thread that opens the device: {e}")))?
                .join()
                .unwrap_or_else(|_| Err(GpuError::NoAdapter("opening the device panicked".into())))
        })
    }

    /// [`Gpu::open_with`] on the calling thread.
    fn open_here(opts: DeviceOptions) -> Result<Arc<Gpu>, GpuError> {
        // A low-priority device's driver threads run only on what the others leave (idle
        // class), inherited from this thread, which exists only to open the device.
        if opts.priority == Priority::Low {
            set_thread_idle(0, true);
        }
        // Devices open one at a time, so that the threads that appear meanwhile are this
        // device's (its driver's queue and rasterizer threads).
        let _one = OPENING.lock().unwrap_or_else(|e| e.into_inner());
        let before = task_ids();
        let _threads = opts.rasterizer_threads.map(|n| EnvOverride::set(RASTERIZER_THREADS, &n.to_string()));
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
        let features = adapter.features() & OPTIONAL_FEATURES;
        let desc = wgpu::DeviceDescriptor {
            label: Some(opts.label),
            required_features: features,
            required_limits: limits.clone(),
            experimental_features: Default::default(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        };
        let ext = if opts.global_priority { global_priority_extension(&adapter) } else { None };
        let wanted = global_priority(opts.priority);
        let mut granted = None;
        let mut opened = None;
        if let Some(ext) = ext {
            let mut level = wanted;
            loop {
                match open_device(&adapter, &desc, Some((ext, level))) {
                    Ok(d) => {
                        granted = Some(level);
                        opened = Some(d);
                        break;
                    }
                    // Raising priority may need a privilege (VK_ERROR_NOT_PERMITTED): ask lower.
                    Err(_) if level.as_raw() > vk::QueueGlobalPriorityKHR::LOW.as_raw() => {
                        level = vk::QueueGlobalPriorityKHR::from_raw(level.as_raw() / 2);
                    }
                    Err(_) => break,
                }
            }
        }
        let (device, queue) = match opened {
            Some(d) => d,
            None => open_device(&adapter, &desc, None)?,
        };
        device.on_uncaptured_error(Arc::new(|e: wgpu::Error| error!("uncaptured GPU error: {e}")));
        let lost = Arc::new(std::sync::atomic::AtomicBool::new(false));
        let flag = lost.clone();
        let label = opts.label;
        device.set_device_lost_callback(move |reason, message| {
            flag.store(true, std::sync::atomic::Ordering::Release);
            error!(device = label, ?reason, "GPU device lost: {message}");
        });
        let threads: Vec<i32> = task_ids().difference(&before).copied().filter(|&t| !ours(t)).collect();
        // The class's slice on the driver's threads (an idle-class thread keeps its own).
        if let Some(slice) = slice_for(opts.priority) {
            for &t in &threads {
                set_thread_slice(t, Some(slice));
            }
        }
        let asked = ext.map(|_| priority_name(wanted));
        let got = granted.map(priority_name);
        if granted.is_some() && granted != Some(wanted) {
            info!(
                asked = asked.unwrap_or("-"),
                granted = got.unwrap_or("-"),
                "queue global priority lowered by the driver"
            );
        }
        debug!(label = opts.label, adapter = %info.name, driver = %info.driver, features = ?features,
            global_priority = got.unwrap_or("not offered"), "GPU device opened");
        Ok(Arc::new(Gpu {
            shared: Mutex::new(HashMap::new()),
            lane: Lane::new(opts.priority),
            features,
            device,
            queue,
            info,
            limits,
            instance,
            adapter,
            global_priority: got,
            lost,
            waited_us: Default::default(),
            threads,
            watch: Default::default(),
        }))
    }
}
