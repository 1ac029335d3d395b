//! What this client holds, checked against its quota: object counts come from the contexts'
//! name tables and surfaces; GPU memory is reserved when an image or buffer is allocated and
//! given back when it is dropped. A refusal is `GL_OUT_OF_MEMORY` (or `EGL_BAD_ALLOC`) for this
//! client alone; see [`crate::quota`].

use super::context::Context;
use strata_device::account::{Kind, Reservation};

use super::error::{GlError, GlResult};
use super::formats::Storage;
use super::GlesExecutor;

impl GlesExecutor {
    /// Objects of `kind` this client has now, over all its contexts: those in the table and
    /// `current`, the current context while a handler holds it.
    pub(super) fn have(&self, kind: Kind, current: Option<&Context>) -> u64 {
        let tables = |f: fn(&super::context::Objects) -> usize| -> u64 {
            self.contexts.values().chain(current).map(|c| f(&c.objects) as u64).sum()
        };
        match kind {
            Kind::Buffer => tables(|o| o.buffers.len()),
            Kind::Texture => tables(|o| o.textures.len()),
            Kind::Renderbuffer => tables(|o| o.renderbuffers.len()),
            Kind::Framebuffer => tables(|o| o.framebuffers.len()),
            Kind::Shader => tables(|o| o.shaders.len()),
            Kind::Program => tables(|o| o.programs.len()),
            Kind::VertexArray => tables(|o| o.vertex_arrays.len()),
            Kind::Context => (self.contexts.len() + usize::from(current.is_some())) as u64,
            Kind::Surface => self.surfaces.len() as u64,
        }
    }

    /// Whether `more` new objects of `kind` fit this client's quota (`ctx`: the current
    /// context, held by the handler asking).
    pub(super) fn admit(&self, ctx: &Context, kind: Kind, more: u64) -> GlResult {
        if more == 0 {
            return Ok(());
        }
        self.account.admit(kind, self.have(kind, Some(ctx)), more).map_err(|_| GlError::OutOfMemory)
    }

    /// Reserves `bytes` of GPU memory for an object this client allocates.
    pub(super) fn reserve(&self, bytes: u64) -> GlResult<Reservation> {
        self.account.reserve(bytes).map_err(|_| GlError::OutOfMemory)
    }

    /// Publishes the object counts for `ctl stats`.
    pub(super) fn publish_usage(&self) {
        for kind in Kind::ALL {
            self.account.set_count(kind, self.have(kind, None));
        }
    }
}

/// Bytes of a texture image of `width`×`height` with `layers` faces and `mips` levels.
pub fn image_bytes(width: u32, height: u32, layers: u32, mips: u32, storage: Storage) -> u64 {
    (0..mips)
        .map(|l| {
            let (w, h) = ((width >> l).max(1) as u64, (height >> l).max(1) as u64);
            match storage {
                // Native blocks are kept on the device and, for decoding later, in the daemon.
                Storage::Native(c) => 2 * c.image_size(w as u32, h as u32) as u64,
                s => w * h * u64::from(s.texel_bytes()),
            }
        })
        .sum::<u64>()
        * u64::from(layers)
}

/// The bytes a 3D image of `width`×`height`×`depth` with `mips` levels holds (each level
/// halves the depth too).
pub fn volume_bytes(width: u32, height: u32, depth: u32, mips: u32, storage: Storage) -> u64 {
    (0..mips).map(|l| image_bytes(width >> l, height >> l, (depth >> l).max(1), 1, storage)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn image_bytes_count_every_level_and_face() {
        assert_eq!(image_bytes(4, 4, 1, 1, Storage::Rgba8), 64);
        assert_eq!(image_bytes(4, 4, 1, 3, Storage::Rgba8), 64 + 16 + 4);
        assert_eq!(image_bytes(4, 4, 6, 1, Storage::Float), 6 * 16 * 16);
        assert_eq!(volume_bytes(4, 4, 2, 3, Storage::Rgba8), 4 * (32 + 4 + 1));
    }
}
