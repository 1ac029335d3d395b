//! What this client holds, checked against its quota: object counts come from the contexts'
//! name tables and surfaces; GPU memory is reserved when an image or buffer is allocated and
//! given back when it is dropped. A refusal is `GL_OUT_OF_MEMORY` (or `EGL_BAD_ALLOC`) for this
//! client alone; see `strata_device::account`.

use crate::context::Context;
use strata_device::account::{Kind, Reservation};

use crate::error::{GlError, GlResult};
use crate::GlesExecutor;

impl GlesExecutor {
    /// Objects of `kind` this client has now, over all its contexts: those in the table and
    /// `current`, the current context while a handler holds it.
    pub(super) fn have(&self, kind: Kind, current: Option<&Context>) -> u64 {
        let tables = |f: fn(&crate::context::Objects) -> usize| -> u64 {
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
