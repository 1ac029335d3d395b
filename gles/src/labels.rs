//! Object labels (`GL_KHR_debug`): `glObjectLabelKHR` and `glGetObjectLabelKHR` on the object
//! kinds an ES 2.0 context has, and the pointer variants, which name sync objects (ES 2.0 has
//! none, so every pointer is invalid).
//!
//! `GL_EXT_debug_label`'s `glLabelObjectEXT` and `glGetObjectLabelEXT` label the same objects
//! under their own type names (Mesa also takes `GL_KHR_debug`'s), with their own rules: an
//! object that does not exist is `GL_INVALID_OPERATION`, a negative length
//! `GL_INVALID_VALUE`, and a length of 0 a NUL-terminated label.
//!
//! Labels live beside the objects, in `Objects::labels`, keyed by the label namespace and the
//! name; deleting an object forgets its label, so a name that is used again starts unlabelled.

use crate::context::Context;
use strata_protocol::commands::MAX_LABEL_LENGTH;
use strata_protocol::{Blob, Bytes};

use crate::context::Objects;
use crate::debug::message_text;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::GlesExecutor;

/// Checks that `identifier` is a label namespace of this context (`GL_INVALID_ENUM`) and that
/// `name` is an object in it (`GL_INVALID_VALUE`).
fn check_object(objects: &Objects, current_vao: u32, identifier: u32, name: u32) -> GlResult {
    let exists = match identifier {
        BUFFER_KHR => name != 0 && objects.buffers.contains_key(&name),
        SHADER_KHR => objects.shaders.contains_key(&name),
        PROGRAM_KHR => objects.programs.contains_key(&name),
        VERTEX_ARRAY_KHR => name != 0 && (name == current_vao || objects.vertex_arrays.contains_key(&name)),
        TEXTURE => name != 0 && objects.textures.contains_key(&name),
        RENDERBUFFER => name != 0 && objects.renderbuffers.contains_key(&name),
        FRAMEBUFFER => name != 0 && objects.framebuffers.contains_key(&name),
        _ => return Err(GlError::InvalidEnum),
    };
    if exists {
        Ok(())
    } else {
        Err(GlError::InvalidValue)
    }
}

/// The `GL_KHR_debug` namespace a `GL_EXT_debug_label` object type names: `GL_INVALID_ENUM`
/// for no type, `GL_INVALID_OPERATION` for queries and program pipelines, which an ES 2.0
/// context here has none of.
fn ext_namespace(object_type: u32) -> GlResult<u32> {
    Ok(match object_type {
        BUFFER_OBJECT_EXT | BUFFER_KHR => BUFFER_KHR,
        SHADER_OBJECT_EXT | SHADER_KHR => SHADER_KHR,
        PROGRAM_OBJECT_EXT | PROGRAM_KHR => PROGRAM_KHR,
        VERTEX_ARRAY_OBJECT_EXT | VERTEX_ARRAY_KHR => VERTEX_ARRAY_KHR,
        TEXTURE | RENDERBUFFER | FRAMEBUFFER => object_type,
        QUERY_OBJECT_EXT | PROGRAM_PIPELINE_OBJECT_EXT => return Err(GlError::InvalidOperation),
        _ => return Err(GlError::InvalidEnum),
    })
}

/// The namespace of a `GL_EXT_debug_label` object that exists (`GL_INVALID_OPERATION` if not).
fn ext_object(ctx: &Context, object_type: u32, object: u32) -> GlResult<u32> {
    let namespace = ext_namespace(object_type)?;
    check_object(&ctx.objects, ctx.bindings.vertex_array, namespace, object).map_err(|e| match e {
        GlError::InvalidValue => GlError::InvalidOperation,
        e => e,
    })?;
    Ok(namespace)
}

impl Objects {
    /// Forgets the label of the object `name` in namespace `identifier` (it was deleted).
    pub fn forget_label(&mut self, identifier: u32, name: u32) {
        if !self.labels.is_empty() {
            self.labels.remove(&(identifier, name));
        }
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glObjectLabelKHR(
        &mut self,
        ctx: &mut Context,
        identifier: u32,
        name: u32,
        length: i32,
        label: Option<Blob<'_>>,
    ) -> GlResult {
        check_object(&ctx.objects, ctx.bindings.vertex_array, identifier, name)?;
        match label {
            None => {
                ctx.objects.labels.remove(&(identifier, name));
            }
            Some(label) => {
                let text = message_text(length, &label, MAX_LABEL_LENGTH)?;
                if text.is_empty() {
                    ctx.objects.labels.remove(&(identifier, name));
                } else {
                    ctx.objects.labels.insert((identifier, name), text);
                }
            }
        }
        Ok(())
    }

    pub(super) fn glGetObjectLabelKHR(
        &mut self,
        ctx: &mut Context,
        identifier: u32,
        name: u32,
        buf_size: i32,
    ) -> Option<Bytes> {
        let checked = if buf_size < 0 {
            Err(GlError::InvalidValue)
        } else {
            check_object(&ctx.objects, ctx.bindings.vertex_array, identifier, name)
        };
        match checked {
            Ok(()) => Some(Bytes(ctx.objects.labels.get(&(identifier, name)).cloned().unwrap_or_default())),
            Err(e) => {
                ctx.record(e);
                None
            }
        }
    }

    pub(super) fn glLabelObjectEXT(
        &mut self,
        ctx: &mut Context,
        object_type: u32,
        object: u32,
        length: i32,
        label: Option<Blob<'_>>,
    ) -> GlResult {
        if length < 0 {
            return Err(GlError::InvalidValue);
        }
        let namespace = ext_object(ctx, object_type, object)?;
        // A length of 0 is GL_KHR_debug's negative one: the whole NUL-terminated label.
        self.glObjectLabelKHR(ctx, namespace, object, if length == 0 { -1 } else { length }, label)
    }

    pub(super) fn glGetObjectLabelEXT(
        &mut self,
        ctx: &mut Context,
        object_type: u32,
        object: u32,
        buf_size: i32,
    ) -> Option<Bytes> {
        let checked = if buf_size < 0 { Err(GlError::InvalidValue) } else { ext_object(ctx, object_type, object) };
        match checked {
            Ok(namespace) => Some(Bytes(ctx.objects.labels.get(&(namespace, object)).cloned().unwrap_or_default())),
            Err(e) => {
                ctx.record(e);
                None
            }
        }
    }

    /// ES 2.0 has no sync objects, so no pointer names one.
    pub(super) fn glObjectPtrLabelKHR(
        &mut self,
        _ctx: &mut Context,
        _ptr: u64,
        _length: i32,
        _label: Option<Blob<'_>>,
    ) -> GlResult {
        Err(GlError::InvalidValue)
    }

    /// ES 2.0 has no sync objects, so no pointer names one.
    pub(super) fn glGetObjectPtrLabelKHR(&mut self, ctx: &mut Context, _ptr: u64, _buf_size: i32) -> Option<Bytes> {
        ctx.record(GlError::InvalidValue);
        None
    }
}
