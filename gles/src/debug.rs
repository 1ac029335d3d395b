//! Debug output (`GL_KHR_debug`): the messages a context generates (GL errors, messages the
//! application inserts, debug groups), the volume control that filters them, the debug group
//! stack, and the message log.
//!
//! **Where messages go.** While the application has no debug callback, enabled messages enter
//! the context's log (at most [`MAX_LOGGED`]; later ones are dropped until it is read). The
//! callback lives in the client library, so while it has one (`strataDebugCallback`), enabled
//! messages wait in a second queue instead, which the library drains with
//! `strataDebugMessages`: after every call when `DEBUG_OUTPUT_SYNCHRONOUS` is enabled, as the
//! extension requires, and otherwise only at points where it waits for the daemon anyway (see
//! the client library's `debug` module). Nothing is generated while `DEBUG_OUTPUT` is disabled,
//! its initial state in a context created without the debug flag.
//!
//! **Volume control.** Each debug group holds the `glDebugMessageControlKHR` rules made while it
//! was on top, in order, starting from a copy of its parent's; a message is enabled unless its
//! severity is `LOW`, and then as the last rule that matches it says. A rule that matches a
//! superset of an older rule's messages replaces it, which keeps the list short.
//!
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
use crate::context::Objects;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::limits::MAX_GROUP_DEPTH;
use crate::objects::debug::{Group, Rule};
use crate::GlesExecutor;
use strata_protocol::commands::MAX_LABEL_LENGTH;
use strata_protocol::commands::{DebugMessage, MAX_DEBUG_MESSAGE_LENGTH};
use strata_protocol::Bytes;
use strata_protocol::{Blob, Slice};

/// Whether `s` is a message source (`GL_DEBUG_SOURCE_*_KHR`).
fn is_source(s: u32) -> bool {
    (DEBUG_SOURCE_API..=DEBUG_SOURCE_OTHER).contains(&s)
}

/// Whether `t` is a message type an application may insert.
fn is_insert_type(t: u32) -> bool {
    (DEBUG_TYPE_ERROR..=DEBUG_TYPE_OTHER).contains(&t) || t == DEBUG_TYPE_MARKER
}

/// Whether `s` is a severity.
fn is_severity(s: u32) -> bool {
    matches!(s, DEBUG_SEVERITY_HIGH | DEBUG_SEVERITY_MEDIUM | DEBUG_SEVERITY_LOW | DEBUG_SEVERITY_NOTIFICATION)
}

/// `None` for `GL_DONT_CARE`, else `v` if `valid`, else `GL_INVALID_ENUM`.
fn dont_care_or(v: u32, valid: bool) -> GlResult<Option<u32>> {
    match v {
        DONT_CARE => Ok(None),
        _ if valid => Ok(Some(v)),
        _ => Err(GlError::InvalidEnum),
    }
}

/// The text of an inserted message or group: `length` bytes, or with a negative `length` the
/// NUL-terminated text the client sent; `GL_INVALID_VALUE` if it is not shorter than the limit.
pub fn message_text(length: i32, text: &Blob<'_>, max: i32) -> GlResult<Vec<u8>> {
    let len = if length < 0 { text.len() } else { length as usize };
    if len >= max as usize || text.len() < len {
        return Err(GlError::InvalidValue);
    }
    Ok(text.as_bytes()[..len].to_vec())
}

#[allow(non_snake_case)]
impl GlesExecutor {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn glDebugMessageControlKHR(
        &mut self,
        ctx: &mut Context,
        source: u32,
        ty: u32,
        severity: u32,
        count: i32,
        ids: Slice<'_, u32>,
        enabled: bool,
    ) -> GlResult {
        if count < 0 {
            return Err(GlError::InvalidValue);
        }
        let source = dont_care_or(source, is_source(source))?;
        let ty = dont_care_or(ty, is_insert_type(ty) || matches!(ty, DEBUG_TYPE_PUSH_GROUP | DEBUG_TYPE_POP_GROUP))?;
        let severity = dont_care_or(severity, is_severity(severity))?;
        if count > 0 && (source.is_none() || ty.is_none() || severity.is_some()) {
            return Err(GlError::InvalidOperation);
        }
        let ids: Vec<u32> = ids.iter().take(count as usize).collect();
        if count > 0 && ids.is_empty() {
            // Ids that were not sent (a null array) select nothing.
            return Ok(());
        }
        ctx.debug.control(Rule { source, ty, severity, ids, enabled })
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glDebugMessageInsertKHR(
        &mut self,
        ctx: &mut Context,
        source: u32,
        ty: u32,
        id: u32,
        severity: u32,
        length: i32,
        text: Blob<'_>,
    ) -> GlResult {
        if !matches!(source, DEBUG_SOURCE_APPLICATION | DEBUG_SOURCE_THIRD_PARTY)
            || !is_insert_type(ty)
            || !is_severity(severity)
        {
            return Err(GlError::InvalidEnum);
        }
        let text = message_text(length, &text, MAX_DEBUG_MESSAGE_LENGTH)?;
        ctx.debug.emit(source, ty, id, severity, text);
        Ok(())
    }

    pub(super) fn glPushDebugGroupKHR(
        &mut self,
        ctx: &mut Context,
        source: u32,
        id: u32,
        length: i32,
        text: Blob<'_>,
    ) -> GlResult {
        if !matches!(source, DEBUG_SOURCE_APPLICATION | DEBUG_SOURCE_THIRD_PARTY) {
            return Err(GlError::InvalidEnum);
        }
        let text = message_text(length, &text, MAX_DEBUG_MESSAGE_LENGTH)?;
        let debug = &mut ctx.debug;
        if debug.groups.len() >= MAX_GROUP_DEPTH {
            return Err(GlError::StackOverflow);
        }
        debug.emit(source, DEBUG_TYPE_PUSH_GROUP, id, DEBUG_SEVERITY_NOTIFICATION, text.clone());
        let rules = debug.groups.last().map(|g| g.rules.clone()).unwrap_or_default();
        debug.groups.push(Group { source, id, text, rules });
        Ok(())
    }

    pub(super) fn glPopDebugGroupKHR(&mut self, ctx: &mut Context) -> GlResult {
        let debug = &mut ctx.debug;
        if debug.groups.len() <= 1 {
            return Err(GlError::StackUnderflow);
        }
        let Some(g) = debug.groups.pop() else { return Err(GlError::StackUnderflow) };
        // The message is filtered by the parent's volume control, which is active again.
        debug.emit(g.source, DEBUG_TYPE_POP_GROUP, g.id, DEBUG_SEVERITY_NOTIFICATION, g.text);
        Ok(())
    }

    pub(super) fn strataDebugCallback(&mut self, ctx: &mut Context, installed: bool) -> GlResult {
        let debug = &mut ctx.debug;
        debug.callback = installed;
        if !installed {
            // Messages not yet delivered are lost with the callback, as a driver's would be.
            debug.pending.clear();
        }
        Ok(())
    }

    pub(super) fn strataDebugMessages(&mut self, ctx: &mut Context) -> Vec<DebugMessage> {
        ctx.debug.pending.drain(..).collect()
    }

    pub(super) fn glGetDebugMessageLogKHR(
        &mut self,
        ctx: &mut Context,
        count: u32,
        buf_size: i32,
        log: bool,
    ) -> Vec<DebugMessage> {
        if log && buf_size < 0 {
            ctx.record(GlError::InvalidValue);
            return Vec::new();
        }
        let debug = &mut ctx.debug;
        let mut room = if log { buf_size as usize } else { usize::MAX };
        let mut out = Vec::new();
        while out.len() < count as usize {
            let Some(m) = debug.log.front() else { break };
            let need = m.text.0.len() + 1;
            if need > room {
                break;
            }
            room -= need;
            out.extend(debug.log.pop_front());
        }
        out
    }
}

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
        SAMPLER => name != 0 && objects.samplers.contains_key(&name),
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
