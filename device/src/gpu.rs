//! A GPU device and its queue: the compositor's, and one per client (each on an instance of its
//! own). Its queue is reached only through [`Gpu::submit`], which names the submission's
//! [`Lane`], and through the methods below for writes: every submission goes through one door.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use crate::lane::Lane;

/// Why no GPU device could be opened.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter matched.
    #[error("no Vulkan adapter found ({0}); on Debian install mesa-vulkan-drivers and libvulkan1")]
    NoAdapter(String),
    /// The adapter refused to open a device.
    #[error("opening the device failed: {0}")]
    Device(#[from] wgpu::RequestDeviceError),
    /// The device could not be opened with a queue global priority.
    #[error("opening the device with a queue global priority failed")]
    Priority,
}

/// Optional device features the executor uses where the adapter has them: linear filtering
/// of RGBA32F (`OES_texture_float_linear`), and BC, ETC2 and ASTC block formats (compressed textures
/// sampled natively instead of decoded on upload), and Depth32FloatStencil8 (`--depth-format
/// 32float` for configs with stencil), timestamps (the composite's own device time), and
/// depth clip control (`EXT_depth_clamp`), and border clamping (`EXT_texture_border_clamp`),
/// and 32-bit float blending and packed float rendering (`EXT_color_buffer_float`).
pub(crate) const OPTIONAL_FEATURES: wgpu::Features = wgpu::Features::FLOAT32_FILTERABLE
    .union(wgpu::Features::TIMESTAMP_QUERY)
    .union(wgpu::Features::DEPTH32FLOAT_STENCIL8)
    .union(wgpu::Features::TEXTURE_COMPRESSION_BC)
    .union(wgpu::Features::TEXTURE_COMPRESSION_ETC2)
    .union(wgpu::Features::TEXTURE_COMPRESSION_ASTC)
    .union(wgpu::Features::DEPTH_CLIP_CONTROL)
    .union(wgpu::Features::DUAL_SOURCE_BLENDING)
    .union(wgpu::Features::ADDRESS_MODE_CLAMP_TO_BORDER)
    // ES 3.0's transform feedback: the vertex stage writes the captured varyings.
    .union(wgpu::Features::VERTEX_WRITABLE_STORAGE)
    // ES 3.0's float colour buffers (EXT_color_buffer_float): blending into 32-bit float ones
    // (EXT_float_blend), and R11F_G11F_B10F rendered in its own format.
    .union(wgpu::Features::FLOAT32_BLENDABLE)
    .union(wgpu::Features::RG11B10UFLOAT_RENDERABLE);

/// What upper layers build once per device and share (their pipelines and fixed images), by type.
type Shared = HashMap<std::any::TypeId, Arc<dyn std::any::Any + Send + Sync>>;

/// A device and its queue: the compositor's, or one client's.
pub struct Gpu {
    /// What upper layers keep once per device ([`Gpu::shared`]).
    pub(crate) shared: Mutex<Shared>,
    /// The optional features the device was opened with.
    pub features: wgpu::Features,
    /// The device.
    pub device: wgpu::Device,
    /// Its queue: submissions go through [`Gpu::submit`], writes through
    /// [`Gpu::write_buffer`] and [`Gpu::write_texture`].
    pub(crate) queue: wgpu::Queue,
    /// The device's own lane: work of the device's owner that no client's lane carries
    /// (reads, depth writes, the compositor's own passes).
    pub lane: Arc<Lane>,
    /// Adapter name, driver and backend, for logs and `GL_RENDERER`.
    pub info: wgpu::AdapterInfo,
    /// The device's limits.
    pub limits: wgpu::Limits,
    /// The instance, for window surfaces.
    pub instance: wgpu::Instance,
    /// The adapter, for window surfaces' capabilities.
    pub adapter: wgpu::Adapter,
    /// The queue's global priority the driver granted (`None`: not offered or not asked).
    pub global_priority: Option<&'static str>,
    /// Set when the device is lost (a fault, a reset, or destroyed): nothing more runs on it.
    pub lost: Arc<std::sync::atomic::AtomicBool>,
    /// Frame completion time the frame waiter measured (for devices that are not CPU
    /// rasterizers), microseconds.
    pub(crate) waited_us: std::sync::atomic::AtomicU64,
    /// The threads the driver started for this device (lavapipe's queue and rasterizer
    /// threads), which inherited the nice value of the thread that opened it.
    pub threads: Vec<i32>,
    /// Polls the device while fence marks are outstanding.
    pub(crate) watch: crate::marks::Watch,
}

impl std::fmt::Debug for Gpu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Gpu").field("adapter", &self.info.name).field("threads", &self.threads).finish()
    }
}

impl Gpu {
    /// What an upper layer keeps once per device, of type `T` (its fixed pipelines and images):
    /// built by `init` on first use, then shared by every user of the device.
    pub fn shared<T: std::any::Any + Send + Sync>(&self, init: impl FnOnce(&Gpu) -> T) -> Arc<T> {
        let key = std::any::TypeId::of::<T>();
        let found = self.shared.lock().unwrap_or_else(|e| e.into_inner()).get(&key).cloned();
        if let Some(any) = found.and_then(|a| a.downcast::<T>().ok()) {
            return any;
        }
        // Built without the lock: `init` may ask for other shared objects.
        let built: Arc<dyn std::any::Any + Send + Sync> = Arc::new(init(self));
        let mut map = self.shared.lock().unwrap_or_else(|e| e.into_inner());
        let kept = map.entry(key).or_insert(built).clone();
        drop(map);
        match kept.downcast::<T>() {
            Ok(t) => t,
            Err(_) => unreachable!("the map holds a T under T's type id"),
        }
    }

    /// Submits `bufs` on the queue as `lane`'s work: the one place any work reaches a queue.
    /// Returns the submission's index.
    pub fn submit(&self, lane: &Lane, bufs: Vec<wgpu::CommandBuffer>) -> wgpu::SubmissionIndex {
        let index = self.queue.submit(bufs);
        lane.submitted(index.clone());
        index
    }

    /// A fence: marks the point after everything submitted on the queue so far, for `lane`.
    /// Returns the mark; nothing waits. The device's watch polls until the mark is reached and
    /// publishes it where the lane publishes its marks ([`Lane::publish_marks`]).
    pub fn mark(&self, lane: &Lane) -> u64 {
        let marks = lane.marks().clone();
        // Handed out before the watch looks (see `marks::Watch::watch`).
        let mark = marks.issued.fetch_add(1, std::sync::atomic::Ordering::AcqRel) + 1;
        let reached = marks.clone();
        self.queue.on_submitted_work_done(move || reached.complete(mark));
        self.watch.watch(&marks, &self.device, &self.lost);
        mark
    }

    /// Writes `data` into `buffer` at `offset` on the queue (before the next submission).
    pub fn write_buffer(&self, buffer: &wgpu::Buffer, offset: u64, data: &[u8]) {
        self.queue.write_buffer(buffer, offset, data);
    }

    /// Writes `data` laid out as `layout` into `size` of `texture` on the queue (before the next
    /// submission).
    pub fn write_texture(
        &self,
        texture: wgpu::TexelCopyTextureInfo<'_>,
        data: &[u8],
        layout: wgpu::TexelCopyBufferLayout,
        size: wgpu::Extent3d,
    ) {
        self.queue.write_texture(texture, data, layout, size);
    }

    /// Nanoseconds per timestamp tick of the queue.
    pub fn timestamp_period(&self) -> f32 {
        self.queue.get_timestamp_period()
    }

    /// Presents a window surface's texture drawn on this device.
    pub fn present(&self, frame: wgpu::SurfaceTexture) {
        self.queue.present(frame);
    }

    /// Counts `busy` as time the device spent on a frame's work (measured by whoever waits for
    /// frames on devices that are not CPU rasterizers; see [`Gpu::busy`]).
    pub fn add_waited(&self, busy: std::time::Duration) {
        let us = busy.as_micros().min(u128::from(u64::MAX)) as u64;
        self.waited_us.fetch_add(us, std::sync::atomic::Ordering::Relaxed);
    }

    /// Whether the device blends with a fragment's second colour (`GL_EXT_blend_func_extended`).
    pub fn dual_source(&self) -> bool {
        self.features.contains(wgpu::Features::DUAL_SOURCE_BLENDING)
    }

    /// Whether the device was lost.
    pub fn is_lost(&self) -> bool {
        self.lost.load(std::sync::atomic::Ordering::Acquire)
    }

    /// How long the device has been busy: on a CPU rasterizer (lavapipe) the CPU time of its
    /// driver threads, which is exactly its work; on a GPU, the time from each frame's last
    /// submission to its completion, as the frame waiter saw it.
    pub fn busy(&self) -> std::time::Duration {
        if self.info.device_type == wgpu::DeviceType::Cpu {
            self.threads_cpu_time()
        } else {
            std::time::Duration::from_micros(self.waited_us.load(std::sync::atomic::Ordering::Relaxed))
        }
    }

    /// Sets the nice value of the driver's threads of this device (a client moved to another
    /// class); raising needs `CAP_SYS_NICE`, without which they stay where they are.
    pub fn renice(&self, nice: i32) {
        for &tid in &self.threads {
            #[cfg(target_os = "linux")]
            // SAFETY: setpriority on one of this process's threads only sets its nice value.
            unsafe {
                libc::setpriority(libc::PRIO_PROCESS, tid as libc::id_t, nice);
            }
        }
    }

    /// CPU time the driver's threads of this device have used (on a CPU rasterizer such as
    /// lavapipe, the time the device was busy), read from `/proc/self/task/*/stat`.
    pub fn threads_cpu_time(&self) -> std::time::Duration {
        // SAFETY: sysconf only reads a constant.
        let ticks = unsafe { libc::sysconf(libc::_SC_CLK_TCK) }.max(1) as f64;
        let total: u64 = self
            .threads
            .iter()
            .filter_map(|t| {
                let stat = std::fs::read_to_string(format!("/proc/self/task/{t}/stat")).ok()?;
                // Fields after the command name (which may hold spaces) start at its ')'.
                let rest = stat.rsplit_once(')')?.1;
                let f: Vec<&str> = rest.split_whitespace().collect();
                Some(f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?)
            })
            .sum();
        std::time::Duration::from_secs_f64(total as f64 / ticks)
    }
}
