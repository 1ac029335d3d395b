//! Opening a device: its own instance (on lavapipe a separate rasterizer), the optional
//! features the executor uses, external memory for shared surfaces, and the queue's global
//! priority (`VK_KHR_global_priority`/`VK_EXT_global_priority`) where the adapter offers it.
//!
//! A device's driver threads (lavapipe's queue and rasterizer threads) inherit the scheduling
//! of the thread that creates the device, so [`Gpu::open_with`] is called on a thread already
//! at the class's nice value ([`nice_for`], [`set_thread_nice`]).

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use ash::vk;
use strata_protocol::control::Priority;
use tracing::{debug, error, info};
use wgpu::hal::api::Vulkan;

use super::{Gpu, GpuError, OPTIONAL_FEATURES};

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

/// The nice value the threads of a class's device run at on a CPU rasterizer: high-priority
/// clients and the compositor 0 (or better where the daemon may raise itself), low-priority
/// clients 19, so that on a machine short of cores they take only what the others leave.
pub fn nice_for(class: Priority) -> i32 {
    match class {
        Priority::High => -5,
        Priority::Normal => 0,
        Priority::Low => 19,
    }
}

/// Sets the calling thread's nice value (threads it creates inherit it). Raising priority
/// (a negative value) needs `CAP_SYS_NICE`; without it the thread stays where it is, and this
/// returns the value in force.
pub fn set_thread_nice(nice: i32) -> i32 {
    #[cfg(target_os = "linux")]
    // SAFETY: gettid, setpriority and getpriority on the calling thread only.
    unsafe {
        let tid = libc::gettid() as libc::id_t;
        if libc::setpriority(libc::PRIO_PROCESS, tid, nice) != 0 {
            debug!(nice, "could not set the thread's nice value: {}", std::io::Error::last_os_error());
        }
        *libc::__errno_location() = 0;
        libc::getpriority(libc::PRIO_PROCESS, tid)
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = nice;
        0
    }
}

/// The slice the high class's threads ask the scheduler for (EEVDF's request size; the
/// kernel's default is 0.75 ms times 1 + log2 of the cores, up to 3 ms). A thread with a
/// shorter slice gets an earlier deadline when it wakes, and so preempts a thread with a longer
/// one sooner (Linux 6.12's `PREEMPT_SHORT`): each hop on the instrument cluster's path (the
/// compositor's refresh, the session's reply, the client's next frame) waits less behind work
/// of the same or a lower class that is running. Needs no privilege.
pub const HIGH_SLICE: std::time::Duration = std::time::Duration::from_micros(300);

/// The slice `class`'s threads ask for ([`HIGH_SLICE`] for the high class; the kernel's
/// default otherwise).
pub fn slice_for(class: Priority) -> Option<std::time::Duration> {
    (class == Priority::High).then_some(HIGH_SLICE)
}

/// Sets thread `tid`'s (0: the calling thread) scheduler slice to `slice`, or back to the
/// kernel's default with `None`, keeping its nice value; for threads in `SCHED_OTHER` only.
/// Returns whether the kernel took it (Linux 6.12 or later).
pub fn set_thread_slice(tid: i32, slice: Option<std::time::Duration>) -> bool {
    #[cfg(target_os = "linux")]
    {
        /// `struct sched_attr` as of its first version (48 bytes).
        #[repr(C)]
        struct SchedAttr {
            size: u32,
            policy: u32,
            flags: u64,
            nice: i32,
            priority: u32,
            runtime: u64,
            deadline: u64,
            period: u64,
        }
        // SAFETY: sched_getscheduler, getpriority and sched_setattr on one of this process's
        // threads, with a sched_attr of the size the call is told.
        unsafe {
            let id = if tid == 0 { libc::gettid() } else { tid };
            if libc::sched_getscheduler(id) != libc::SCHED_OTHER {
                return false;
            }
            *libc::__errno_location() = 0;
            let nice = libc::getpriority(libc::PRIO_PROCESS, id as libc::id_t);
            let attr = SchedAttr {
                size: std::mem::size_of::<SchedAttr>() as u32,
                policy: libc::SCHED_OTHER as u32,
                flags: 0,
                nice,
                priority: 0,
                runtime: slice.map_or(0, |s| s.as_nanos().min(u128::from(u64::MAX)) as u64),
                deadline: 0,
                period: 0,
            };
            libc::syscall(libc::SYS_sched_setattr, id, &attr as *const SchedAttr, 0u32) == 0
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = (tid, slice);
        false
    }
}

/// Puts the calling thread at `class`'s CPU priority: its nice value ([`nice_for`]) and slice
/// ([`slice_for`]). Returns the nice value in force (see [`set_thread_nice`]).
pub fn set_thread_class(class: Priority) -> i32 {
    let nice = set_thread_nice(nice_for(class));
    set_thread_slice(0, slice_for(class));
    nice
}

/// Puts the calling thread in the real-time class (`SCHED_FIFO`) at `priority` (1–99), so
/// that it runs as soon as it wakes, ahead of every ordinary thread (threads it creates
/// inherit it). Needs `CAP_SYS_NICE` or an `RLIMIT_RTPRIO` of at least `priority`; the error
/// says why it was refused, and the thread then stays where it is.
pub fn set_thread_realtime(priority: i32) -> std::io::Result<()> {
    #[cfg(target_os = "linux")]
    // SAFETY: sched_setscheduler on the calling thread with a valid sched_param.
    unsafe {
        let param = libc::sched_param { sched_priority: priority };
        if libc::sched_setscheduler(0, libc::SCHED_FIFO, &param) != 0 {
            return Err(std::io::Error::last_os_error());
        }
        Ok(())
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = priority;
        Err(std::io::Error::from(std::io::ErrorKind::Unsupported))
    }
}

/// The variable llvmpipe (lavapipe's rasterizer) reads its thread count from when an instance
/// enumerates its devices.
pub const RASTERIZER_THREADS: &str = "LP_NUM_THREADS";

/// An environment variable set while a device opens, and restored after.
///
/// `stratad` sets the variable once at start-up, before it starts any thread, so that setting
/// it here only replaces a value and never grows the environment that other threads may read.
struct EnvOverride {
    name: &'static str,
    old: Option<std::ffi::OsString>,
}

impl EnvOverride {
    fn set(name: &'static str, value: &str) -> EnvOverride {
        let old = std::env::var_os(name);
        std::env::set_var(name, value);
        EnvOverride { name, old }
    }
}

impl Drop for EnvOverride {
    fn drop(&mut self) {
        match &self.old {
            Some(v) => std::env::set_var(self.name, v),
            None => std::env::remove_var(self.name),
        }
    }
}

/// Gives [`RASTERIZER_THREADS`] its default value (one thread per core) if the environment
/// does not set it, and keeps the C allocator from returning memory on every free (see
/// [`keep_freed_memory`]). Call it before starting any thread: later devices then only replace
/// its value.
pub fn settle_environment() {
    if std::env::var_os(RASTERIZER_THREADS).is_none() {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        std::env::set_var(RASTERIZER_THREADS, cores.to_string());
    }
    keep_freed_memory();
}

/// Above this much free memory at the top of one of the C allocator's heaps, it is returned
/// to the system (glibc's `M_TRIM_THRESHOLD`; glibc's heaps are at most 64 MiB).
pub const TRIM_THRESHOLD: i32 = 64 << 20;

/// Allocations above this size get a mapping of their own (`M_MMAP_THRESHOLD`, glibc's most).
pub const MMAP_THRESHOLD: i32 = 32 << 20;

/// Sets glibc's trim and mapping thresholds ([`TRIM_THRESHOLD`], [`MMAP_THRESHOLD`]) unless
/// `GLIBC_TUNABLES` sets malloc's own; returns whether it set them. lavapipe allocates and
/// frees its vertex and binning memory on its own threads every draw. With glibc's defaults
/// each free of a thread's heap top gives the pages back, and the next draw faults them in
/// again (zeroed): glmark2's bunny drew at 17 fps through the daemon against 62 with these
/// thresholds (docs/architecture.md, "Devices and frames"). The cost is that the daemon's
/// resident memory stays at its high-water mark per heap rather than shrinking after a peak.
pub fn keep_freed_memory() -> bool {
    let tuned = std::env::var("GLIBC_TUNABLES").is_ok_and(|t| t.contains("glibc.malloc."));
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    if !tuned {
        // SAFETY: mallopt with documented parameters; it only changes allocator settings.
        return unsafe {
            libc::mallopt(libc::M_TRIM_THRESHOLD, TRIM_THRESHOLD) == 1
                && libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD) == 1
        };
    }
    let _ = tuned;
    false
}

/// Held while a device opens.
static OPENING: Mutex<()> = Mutex::new(());

/// The ids of this process's threads.
pub(crate) fn task_ids() -> std::collections::HashSet<i32> {
    std::fs::read_dir("/proc/self/task")
        .map(|d| d.filter_map(|e| e.ok()?.file_name().to_str()?.parse().ok()).collect())
        .unwrap_or_default()
}

/// Whether thread `tid` is one of the daemon's own (sessions, frame waiters, the runtime's),
/// which may start while a device opens but are not the device's.
fn ours(tid: i32) -> bool {
    let comm = std::fs::read_to_string(format!("/proc/self/task/{tid}/comm")).unwrap_or_default();
    let comm = comm.trim_end();
    comm == "compositor" || ["session-", "frames-", "tokio"].iter().any(|p| comm.starts_with(p))
}

/// Moves thread `tid` (0: the calling thread) to `SCHED_IDLE` when `idle` (Linux): it runs
/// only when no other thread wants the core, and threads it creates inherit that; otherwise
/// back to `SCHED_OTHER`. Needs no privilege within the thread's nice limit.
pub fn set_thread_idle(tid: i32, idle: bool) -> bool {
    #[cfg(target_os = "linux")]
    // SAFETY: sched_setscheduler on one of this process's threads with a valid parameter.
    unsafe {
        let param = libc::sched_param { sched_priority: 0 };
        libc::sched_setscheduler(tid, if idle { libc::SCHED_IDLE } else { libc::SCHED_OTHER }, &param) == 0
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = (tid, idle);
        false
    }
}

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
            depth_writers: Mutex::new(HashMap::new()),
            features,
            device,
            queue,
            info,
            limits,
            instance,
            adapter,
            gles: std::sync::OnceLock::new(),
            global_priority: got,
            lost,
            waited_us: Default::default(),
            depth_reader: std::sync::OnceLock::new(),
            threads,
        }))
    }
}
