//! Images shared between devices: a client's device allocates a surface's colour and depth in
//! memory it can export as an opaque file descriptor (`VK_KHR_external_memory_fd`), and the
//! compositor's device imports that memory into an image of its own. Both images are created
//! with identical parameters, so the two devices read and write the same bytes; nothing is
//! copied. Where a device cannot export or import an image of the format, [`Gpu::exportable`]
//! says so and the caller copies frames through host memory instead (`strata_scene::transfer::Transfer`).

use std::os::fd::{FromRawFd, IntoRawFd, OwnedFd};

use ash::vk;
use wgpu::hal::api::Vulkan;
use wgpu::hal::vulkan as hv;

use crate::gpu::Gpu;

/// Why an image could not be exported or imported.
#[derive(Debug, thiserror::Error)]
pub enum ShareError {
    /// The device is not a Vulkan device (no external memory).
    #[error("the device is not a Vulkan device")]
    NotVulkan,
    /// The device lacks `VK_KHR_external_memory_fd`.
    #[error("the device lacks VK_KHR_external_memory_fd")]
    NoExtension,
    /// The two devices are different physical devices or drivers.
    #[error("the devices are different physical devices or drivers")]
    OtherDevice,
    /// The driver cannot export or import images of this format as opaque fds.
    #[error("the driver cannot share {0:?} images through opaque fds")]
    Format(wgpu::TextureFormat),
    /// No memory type fits.
    #[error("no device-local memory type can hold the image")]
    NoMemoryType,
    /// A Vulkan call failed.
    #[error("{call} failed: {result}")]
    Vulkan {
        /// The call.
        call: &'static str,
        /// Its result.
        result: vk::Result,
    },
}

fn vkr(call: &'static str) -> impl FnOnce(vk::Result) -> ShareError {
    move |result| ShareError::Vulkan { call, result }
}

/// The memory behind an exported image, as another device imports it.
#[derive(Debug)]
pub struct Exported {
    /// The memory's file descriptor (one reference to the memory; importing consumes it).
    pub fd: OwnedFd,
    /// The allocation's size.
    pub size: u64,
    /// The memory type index it was allocated from.
    pub memory_type: u32,
}

impl Exported {
    /// Another reference to the same memory (a duplicate descriptor), for a second device to
    /// import.
    pub fn try_clone(&self) -> std::io::Result<Exported> {
        Ok(Exported { fd: self.fd.try_clone()?, size: self.size, memory_type: self.memory_type })
    }
}

/// What identifies a physical device and its driver across instances.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DeviceIdentity {
    /// `VkPhysicalDeviceIDProperties::deviceUUID`.
    pub device: [u8; 16],
    /// `VkPhysicalDeviceIDProperties::driverUUID`.
    pub driver: [u8; 16],
}

/// The Vulkan image usage every shared image of `format` has, on both sides: a render
/// attachment that is sampled, and colour is also copied (reads, uploads).
fn vk_usage(format: wgpu::TextureFormat) -> vk::ImageUsageFlags {
    if format.is_depth_stencil_format() {
        // Transfers out: glReadPixels of stencil (GL_NV_read_stencil) copies that aspect.
        vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_SRC
    } else {
        vk::ImageUsageFlags::COLOR_ATTACHMENT
            | vk::ImageUsageFlags::SAMPLED
            | vk::ImageUsageFlags::TRANSFER_SRC
            | vk::ImageUsageFlags::TRANSFER_DST
    }
}

/// The wgpu usage matching [`vk_usage`].
pub fn shared_usage(format: wgpu::TextureFormat) -> wgpu::TextureUsages {
    use wgpu::TextureUsages as U;
    if format.is_depth_stencil_format() {
        U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC
    } else {
        U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC | U::COPY_DST
    }
}

fn hal_usage(format: wgpu::TextureFormat) -> wgpu::wgt::TextureUses {
    use wgpu::wgt::TextureUses as U;
    if format.is_depth_stencil_format() {
        U::DEPTH_STENCIL_READ | U::DEPTH_STENCIL_WRITE | U::RESOURCE | U::COPY_SRC
    } else {
        U::COLOR_TARGET | U::RESOURCE | U::COPY_SRC | U::COPY_DST
    }
}

/// A 2D, single-level, single-sample image of `format` and `size` shared through opaque fds.
fn image_info<'a>(
    vk_format: vk::Format,
    format: wgpu::TextureFormat,
    (width, height): (u32, u32),
    external: &'a mut vk::ExternalMemoryImageCreateInfo<'_>,
) -> vk::ImageCreateInfo<'a> {
    vk::ImageCreateInfo::default()
        .flags(create_flags(format))
        .image_type(vk::ImageType::TYPE_2D)
        .format(vk_format)
        .extent(vk::Extent3D { width, height, depth: 1 })
        .mip_levels(1)
        .array_layers(1)
        .samples(vk::SampleCountFlags::TYPE_1)
        .tiling(vk::ImageTiling::OPTIMAL)
        .usage(vk_usage(format))
        .sharing_mode(vk::SharingMode::EXCLUSIVE)
        .initial_layout(vk::ImageLayout::UNDEFINED)
        .push_next(external)
}

/// The view formats a shared image of `format` is made for: an sRGB view of colour images,
/// which `EGL_KHR_gl_colorspace` surfaces draw through.
fn view_formats(format: wgpu::TextureFormat) -> &'static [wgpu::TextureFormat] {
    if format == wgpu::TextureFormat::Rgba8Unorm {
        &crate::passes::SRGB_VIEW
    } else {
        &[]
    }
}

/// The Vulkan image flags matching [`view_formats`]: views of another format are allowed.
fn create_flags(format: wgpu::TextureFormat) -> vk::ImageCreateFlags {
    if view_formats(format).is_empty() {
        vk::ImageCreateFlags::empty()
    } else {
        vk::ImageCreateFlags::MUTABLE_FORMAT
    }
}

fn descriptor(label: &'static str, format: wgpu::TextureFormat, size: (u32, u32)) -> wgpu::TextureDescriptor<'static> {
    let desc = crate::passes::descriptor_2d(label, format, size, shared_usage(format));
    wgpu::TextureDescriptor { view_formats: view_formats(format), ..desc }
}

const HANDLE: vk::ExternalMemoryHandleTypeFlags = vk::ExternalMemoryHandleTypeFlags::OPAQUE_FD;

impl Gpu {
    /// The physical device and driver this device runs on, if it is a Vulkan device.
    pub fn identity(&self) -> Option<DeviceIdentity> {
        // SAFETY: only reads properties of the adapter's physical device.
        unsafe {
            let adapter = self.adapter.as_hal::<Vulkan>()?;
            let instance = adapter.shared_instance().raw_instance();
            let mut id = vk::PhysicalDeviceIDProperties::default();
            let mut props = vk::PhysicalDeviceProperties2::default().push_next(&mut id);
            instance.get_physical_device_properties2(adapter.raw_physical_device(), &mut props);
            Some(DeviceIdentity { device: id.device_uuid, driver: id.driver_uuid })
        }
    }

    /// Whether images of `format` can be exported from this device and imported into
    /// `other` (the same physical device and driver, both with `VK_KHR_external_memory_fd`,
    /// and the format exportable and importable as an opaque fd).
    pub fn exportable(&self, other: &Gpu, format: wgpu::TextureFormat) -> Result<(), ShareError> {
        if self.identity().ok_or(ShareError::NotVulkan)? != other.identity().ok_or(ShareError::NotVulkan)? {
            return Err(ShareError::OtherDevice);
        }
        for gpu in [self, other] {
            // SAFETY: only reads the device's enabled extensions.
            let has = unsafe { gpu.device.as_hal::<Vulkan>() }
                .ok_or(ShareError::NotVulkan)?
                .enabled_device_extensions()
                .contains(&ash::khr::external_memory_fd::NAME);
            if !has {
                return Err(ShareError::NoExtension);
            }
        }
        // SAFETY: only queries the physical device's image format properties.
        unsafe {
            let adapter = self.adapter.as_hal::<Vulkan>().ok_or(ShareError::NotVulkan)?;
            let instance = adapter.shared_instance().raw_instance();
            let vk_format = adapter.texture_format_as_raw(format);
            let mut ext_info = vk::PhysicalDeviceExternalImageFormatInfo::default().handle_type(HANDLE);
            let info = vk::PhysicalDeviceImageFormatInfo2::default()
                .flags(create_flags(format))
                .format(vk_format)
                .ty(vk::ImageType::TYPE_2D)
                .tiling(vk::ImageTiling::OPTIMAL)
                .usage(vk_usage(format))
                .push_next(&mut ext_info);
            let mut ext_props = vk::ExternalImageFormatProperties::default();
            let mut props = vk::ImageFormatProperties2::default().push_next(&mut ext_props);
            instance
                .get_physical_device_image_format_properties2(adapter.raw_physical_device(), &info, &mut props)
                .map_err(|_| ShareError::Format(format))?;
            let features = ext_props.external_memory_properties.external_memory_features;
            let need = vk::ExternalMemoryFeatureFlags::EXPORTABLE | vk::ExternalMemoryFeatureFlags::IMPORTABLE;
            if !features.contains(need) {
                return Err(ShareError::Format(format));
            }
        }
        Ok(())
    }

    /// A new `width`×`height` image of `format` on this device whose memory can be exported:
    /// the texture, and the memory as another device imports it ([`Gpu::import`]).
    pub fn create_exported(
        &self,
        label: &'static str,
        format: wgpu::TextureFormat,
        size: (u32, u32),
    ) -> Result<(wgpu::Texture, Exported), ShareError> {
        // SAFETY: the image and memory are created, bound and handed to wgpu-hal here, with
        // the parameters `descriptor` gives wgpu; every failure path destroys what it made.
        unsafe {
            let adapter = self.adapter.as_hal::<Vulkan>().ok_or(ShareError::NotVulkan)?;
            let vk_format = adapter.texture_format_as_raw(format);
            let instance = adapter.shared_instance().raw_instance().clone();
            let hal = self.device.as_hal::<Vulkan>().ok_or(ShareError::NotVulkan)?;
            let dev = hal.raw_device();
            let mut external = vk::ExternalMemoryImageCreateInfo::default().handle_types(HANDLE);
            let info = image_info(vk_format, format, size, &mut external);
            let image = dev.create_image(&info, None).map_err(vkr("vkCreateImage"))?;
            let req = dev.get_image_memory_requirements(image);
            let Some(memory_type) = memory_type(&instance, hal.raw_physical_device(), req.memory_type_bits) else {
                dev.destroy_image(image, None);
                return Err(ShareError::NoMemoryType);
            };
            let mut export = vk::ExportMemoryAllocateInfo::default().handle_types(HANDLE);
            let mut dedicated = vk::MemoryDedicatedAllocateInfo::default().image(image);
            let alloc = vk::MemoryAllocateInfo::default()
                .allocation_size(req.size)
                .memory_type_index(memory_type)
                .push_next(&mut export)
                .push_next(&mut dedicated);
            let memory = match dev.allocate_memory(&alloc, None) {
                Ok(m) => m,
                Err(e) => {
                    dev.destroy_image(image, None);
                    return Err(vkr("vkAllocateMemory")(e));
                }
            };
            let fd_fn = ash::khr::external_memory_fd::Device::new(&instance, dev);
            let got = dev.bind_image_memory(image, memory, 0).map_err(vkr("vkBindImageMemory")).and_then(|()| {
                let get = vk::MemoryGetFdInfoKHR::default().memory(memory).handle_type(HANDLE);
                fd_fn.get_memory_fd(&get).map_err(vkr("vkGetMemoryFdKHR"))
            });
            let fd = match got {
                Ok(fd) => OwnedFd::from_raw_fd(fd),
                Err(e) => {
                    dev.destroy_image(image, None);
                    dev.free_memory(memory, None);
                    return Err(e);
                }
            };
            let desc = descriptor(label, format, size);
            let texture = self.wrap(&hal, image, &desc, hv::TextureMemory::Dedicated(memory));
            Ok((texture, Exported { fd, size: req.size, memory_type }))
        }
    }

    /// Imports memory another device exported ([`Gpu::create_exported`] with the same format
    /// and size) as a `width`×`height` image of `format` on this device.
    pub fn import(
        &self,
        label: &'static str,
        format: wgpu::TextureFormat,
        size: (u32, u32),
        memory: Exported,
    ) -> Result<wgpu::Texture, ShareError> {
        // SAFETY: as in `create_exported`; the fd is handed to the driver only on success.
        unsafe {
            let adapter = self.adapter.as_hal::<Vulkan>().ok_or(ShareError::NotVulkan)?;
            let vk_format = adapter.texture_format_as_raw(format);
            let hal = self.device.as_hal::<Vulkan>().ok_or(ShareError::NotVulkan)?;
            let dev = hal.raw_device();
            let mut external = vk::ExternalMemoryImageCreateInfo::default().handle_types(HANDLE);
            let info = image_info(vk_format, format, size, &mut external);
            let image = dev.create_image(&info, None).map_err(vkr("vkCreateImage"))?;
            let req = dev.get_image_memory_requirements(image);
            if req.size > memory.size || req.memory_type_bits & (1 << memory.memory_type) == 0 {
                dev.destroy_image(image, None);
                return Err(ShareError::NoMemoryType);
            }
            let raw_fd = memory.fd.into_raw_fd();
            let mut import = vk::ImportMemoryFdInfoKHR::default().handle_type(HANDLE).fd(raw_fd);
            let mut dedicated = vk::MemoryDedicatedAllocateInfo::default().image(image);
            let alloc = vk::MemoryAllocateInfo::default()
                .allocation_size(memory.size)
                .memory_type_index(memory.memory_type)
                .push_next(&mut import)
                .push_next(&mut dedicated);
            let mem = match dev.allocate_memory(&alloc, None) {
                Ok(m) => m,
                Err(e) => {
                    // Not consumed by the driver: ours to close.
                    drop(OwnedFd::from_raw_fd(raw_fd));
                    dev.destroy_image(image, None);
                    return Err(vkr("vkAllocateMemory (import)")(e));
                }
            };
            if let Err(e) = dev.bind_image_memory(image, mem, 0) {
                dev.destroy_image(image, None);
                dev.free_memory(mem, None);
                return Err(vkr("vkBindImageMemory")(e));
            }
            let desc = descriptor(label, format, size);
            Ok(self.wrap(&hal, image, &desc, hv::TextureMemory::Dedicated(mem)))
        }
    }

    /// Hands a bound image to wgpu, which then owns it and its memory.
    ///
    /// # Safety
    /// `image` must be created as `desc` describes, bound to `memory`, on this device.
    unsafe fn wrap(
        &self,
        hal: &hv::Device,
        image: vk::Image,
        desc: &wgpu::TextureDescriptor<'_>,
        memory: hv::TextureMemory,
    ) -> wgpu::Texture {
        let hal_desc = wgpu::hal::TextureDescriptor {
            label: desc.label,
            size: desc.size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: desc.format,
            usage: hal_usage(desc.format),
            memory_flags: wgpu::hal::MemoryFlags::empty(),
            view_formats: desc.view_formats.to_vec(),
        };
        // SAFETY: the caller's contract; wgpu-hal takes ownership of image and memory.
        unsafe {
            let texture = hal.texture_from_raw(image, &hal_desc, None, memory);
            self.device.create_texture_from_hal::<Vulkan>(texture, desc, wgpu::wgt::TextureUses::UNINITIALIZED)
        }
    }
}

/// The first device-local memory type among `bits`, else any of them.
fn memory_type(instance: &ash::Instance, phd: vk::PhysicalDevice, bits: u32) -> Option<u32> {
    // SAFETY: reads the physical device's memory properties.
    let props = unsafe { instance.get_physical_device_memory_properties(phd) };
    let types = props.memory_types_as_slice();
    let allowed = |i: usize| bits & (1 << i) != 0;
    let local = vk::MemoryPropertyFlags::DEVICE_LOCAL;
    (0..types.len())
        .find(|&i| allowed(i) && types[i].property_flags.contains(local))
        .or_else(|| (0..types.len()).find(|&i| allowed(i)))
        .map(|i| i as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Clears `tex` (colour, or depth when `depth` is given) on `gpu` and waits.
    fn clear(gpu: &Gpu, tex: &wgpu::Texture, color: wgpu::Color, depth: Option<f32>) {
        let view = tex.create_view(&Default::default());
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        let ops = wgpu::Operations { load: wgpu::LoadOp::Clear(color), store: wgpu::StoreOp::Store };
        let color_att =
            [Some(wgpu::RenderPassColorAttachment { view: &view, depth_slice: None, resolve_target: None, ops })];
        drop(enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: None,
            color_attachments: if depth.is_none() { &color_att } else { &[] },
            depth_stencil_attachment: depth.map(|d| wgpu::RenderPassDepthStencilAttachment {
                view: &view,
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(d), store: wgpu::StoreOp::Store }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        }));
        let index = gpu.submit(&gpu.lane, vec![enc.finish()]);
        gpu.device.poll(wgpu::PollType::Wait { submission_index: Some(index), timeout: None }).expect("poll");
    }

    /// The depth values of `tex` (a `Depth32Float` image) as `gpu` reads them.
    fn read_depth(gpu: &Gpu, tex: &wgpu::Texture, (w, h): (u32, u32)) -> Vec<f32> {
        let bytes = gpu
            .read_texels(&gpu.lane, tex, (0, 0), [0, 0, w, h], wgpu::TextureAspect::DepthOnly, 4)
            .expect("read back");
        bytemuck::cast_slice::<u8, f32>(&bytes).to_vec()
    }

    #[test]
    fn what_one_device_draws_another_device_reads() {
        // Two instances, as two clients' devices are; no Vulkan device: nothing to test.
        let (Ok(a), Ok(b)) = (Gpu::open(), Gpu::open()) else { return };
        let size = (64, 48);
        let color = wgpu::TextureFormat::Rgba8Unorm;
        let depth = wgpu::TextureFormat::Depth32Float;
        a.exportable(&b, color).expect("lavapipe shares RGBA8 images");
        a.exportable(&b, depth).expect("lavapipe shares depth images");
        let (ca, mem) = a.create_exported("colour", color, size).expect("export colour");
        let cb = b.import("colour", color, size, mem).expect("import colour");
        let (da, mem) = a.create_exported("depth", depth, size).expect("export depth");
        let db = b.import("depth", depth, size, mem).expect("import depth");
        for (rgba, d) in [([10u8, 20, 30, 255], 0.25f32), ([200, 100, 50, 128], 0.75)] {
            let c = wgpu::Color {
                r: f64::from(rgba[0]) / 255.0,
                g: f64::from(rgba[1]) / 255.0,
                b: f64::from(rgba[2]) / 255.0,
                a: f64::from(rgba[3]) / 255.0,
            };
            clear(&a, &ca, c, None);
            clear(&a, &da, wgpu::Color::BLACK, Some(d));
            let px = b.read_rgba8(&cb, [0, 0, size.0, size.1]).expect("read on the other device");
            assert!(px.chunks(4).all(|p| p == rgba), "colour drawn on one device reads {:?} on the other", &px[..4]);
            let depths = read_depth(&b, &db, size);
            assert!(depths.iter().all(|v| *v == d), "depth {d} reads {} on the other device", depths[0]);
        }
    }
}
