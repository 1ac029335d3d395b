//! Framebuffer and renderbuffer objects: what each attachment point holds, the draw and read
//! buffers, and a renderbuffer's image.

use crate::channels::is_half_renderbuffer;
use crate::enums::*;
use crate::error::GlError;
use crate::limits::MAX_DRAW_BUFFERS;

/// Where one attachment of a framebuffer object comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Attachment {
    /// Nothing attached.
    #[default]
    None,
    /// A texture level (cube maps: face 0..6).
    Texture {
        /// Texture name.
        name: u32,
        /// Mip level.
        level: u32,
        /// Cube face, 0 for 2D.
        face: u32,
    },
    /// A renderbuffer.
    Renderbuffer(u32),
}

/// A framebuffer object.
#[derive(Clone)]
pub struct Framebuffer {
    /// `COLOR_ATTACHMENT0` … `COLOR_ATTACHMENT7` (`GL_NV_fbo_color_attachments`).
    pub colors: [Attachment; MAX_DRAW_BUFFERS],
    /// `DEPTH_ATTACHMENT`.
    pub depth: Attachment,
    /// `STENCIL_ATTACHMENT`.
    pub stencil: Attachment,
    /// `glDrawBuffersEXT`: per fragment output, `GL_NONE` or the colour attachment it writes.
    pub draw_buffers: [u32; MAX_DRAW_BUFFERS],
    /// `glReadBufferNV`: the colour attachment reads use, or `GL_NONE`.
    pub read: u32,
}

impl Default for Framebuffer {
    fn default() -> Self {
        let mut draw_buffers = [NONE; MAX_DRAW_BUFFERS];
        draw_buffers[0] = COLOR_ATTACHMENT0;
        Framebuffer {
            colors: Default::default(),
            depth: Attachment::None,
            stencil: Attachment::None,
            draw_buffers,
            read: COLOR_ATTACHMENT0,
        }
    }
}

/// The colour attachment `attachment` names among the first `named` (the enums a call knows):
/// `None` for another enum, `Err` for one past the attachments Strata has.
pub fn color_slot(attachment: u32, named: u32) -> Option<Result<usize, GlError>> {
    let i = attachment.checked_sub(COLOR_ATTACHMENT0).filter(|i| *i < named)?;
    Some(if (i as usize) < MAX_DRAW_BUFFERS { Ok(i as usize) } else { Err(GlError::InvalidOperation) })
}

/// What a target is resolved for: draws and clears write the draw buffers, reads and copies
/// read the read buffer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Purpose {
    /// The draw buffers.
    Draw,
    /// The read buffer.
    Read,
}

/// A renderbuffer.
#[derive(Default)]
pub struct Renderbuffer {
    /// Internal format enum, 0 until storage is allocated.
    pub format: u32,
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// The GPU image.
    pub gpu: Option<(wgpu::Texture, wgpu::TextureView)>,
    /// Unique id for caches.
    pub uid: u64,
    /// The image's memory, held against the client's quota (shared with the EGLImages made
    /// from it and their siblings).
    pub reserved: Option<std::sync::Arc<strata_device::account::Reservation>>,
    /// The level and layer of the texture the view shows: (0, 0) but for an EGLImage sibling.
    pub at: crate::objects::image::Subresource,
}

impl Renderbuffer {
    /// `GL_RENDERBUFFER_SAMPLES`: the image's samples, 0 for a single-sample image.
    pub fn samples(&self) -> u32 {
        self.gpu.as_ref().map(|(t, _)| t.sample_count()).filter(|&n| n > 1).unwrap_or(0)
    }

    /// Whether it holds colour: a colour format of its own, or an EGLImage's colour image.
    pub fn is_color(&self) -> bool {
        matches!(self.format, RGBA4 | RGB5_A1 | RGB565 | RGBA8_OES | RGB8_OES | R8_EXT | RG8_EXT | SRGB8_ALPHA8)
            || is_half_renderbuffer(self.format)
            || crate::channels::is_float_renderbuffer(self.format)
            || self.format == RGB10_A2_EXT
            || crate::integer::IntFormat::from_gl(self.format).is_some()
            || (crate::formats::is_color_format(self.format) && self.gpu.is_some())
    }
}
