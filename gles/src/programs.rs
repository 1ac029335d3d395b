//! Program objects: creation, attachment, attribute bindings, linking (through `glsl`, then
//! wgpu shader modules and layouts), use, deletion and queries.
//!
//! `GL_OES_get_program_binary`. A program's binary holds what it was linked from: both
//! stages' sources and the attribute bindings in force, framed by a magic number, a format
//! version and a CRC-32. Loading one compiles and links those again, so a binary stays good
//! across daemon builds until the format changes. A binary that is corrupt, truncated, of
//! another format version or another implementation fails the link with a log that says
//! why; it never reaches the GPU unchecked, since its contents are validated as
//! `glShaderSource` and `glBindAttribLocation` validate theirs.

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::glsl;
use crate::glsl::types::Stage;
use crate::limits::MAX_ATTRIBS;
use crate::linking::link_either;
use crate::linking::{link_stages, linked_for_query, release_shaders};
use crate::objects::program::Recipe;
use crate::objects::program::{create_gpu_program, Program};
use crate::objects::program::{LinkResult, LinkedStages};
use crate::GlesExecutor;
use std::collections::HashMap;
use strata_protocol::{ActiveVariable, Text};
use strata_protocol::{Blob, Bytes};

/// `f` of program `name`, or `default` after recording the error GL gives for a bad name.
fn with_program<T>(ctx: &mut Context, name: u32, default: T, f: impl FnOnce(&Program) -> T) -> T {
    match ctx.objects.programs.get(&name) {
        Some(p) => f(p),
        None => {
            let e = ctx.objects.shader_or_program_error(name);
            ctx.record(e);
            default
        }
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glCreateProgram(&mut self, ctx: &mut Context, name: u32) -> GlResult {
        let objects = &mut ctx.objects;
        if name == 0 || objects.shaders.contains_key(&name) || objects.programs.contains_key(&name) {
            return Err(GlError::InvalidValue);
        }
        self.admit(ctx, strata_device::account::Kind::Program, 1)?;
        ctx.objects.programs.insert(name, Program::default());
        Ok(())
    }

    pub(super) fn glDeleteProgram(&mut self, ctx: &mut Context, program: u32) -> GlResult {
        if program == 0 {
            return Ok(());
        }
        let objects = &mut ctx.objects;
        if !objects.programs.contains_key(&program) {
            return Err(objects.shader_or_program_error(program));
        }
        if let Some(p) = objects.programs.get_mut(&program) {
            p.delete_pending = true;
        }
        crate::linking::release_if_unused(ctx, program);
        Ok(())
    }

    pub(super) fn glAttachShader(&mut self, ctx: &mut Context, program: u32, shader: u32) -> GlResult {
        let objects = &mut ctx.objects;
        let Some(p) = objects.programs.get(&program) else { return Err(objects.shader_or_program_error(program)) };
        let Some(stage) = objects.shaders.get(&shader).map(|s| s.stage) else {
            return Err(objects.shader_or_program_error(shader));
        };
        let same_stage = p.attached.iter().any(|s| objects.shaders.get(s).is_some_and(|x| x.stage == stage));
        if p.attached.contains(&shader) || same_stage {
            return Err(GlError::InvalidOperation);
        }
        if let Some(p) = objects.programs.get_mut(&program) {
            p.attached.push(shader);
        }
        Ok(())
    }

    pub(super) fn glDetachShader(&mut self, ctx: &mut Context, program: u32, shader: u32) -> GlResult {
        let objects = &mut ctx.objects;
        if !objects.programs.contains_key(&program) {
            return Err(objects.shader_or_program_error(program));
        }
        if !objects.shaders.contains_key(&shader) {
            return Err(objects.shader_or_program_error(shader));
        }
        let Some(p) = objects.programs.get_mut(&program) else { return Ok(()) };
        let i = p.attached.iter().position(|&s| s == shader).ok_or(GlError::InvalidOperation)?;
        p.attached.remove(i);
        release_shaders(objects, &[shader]);
        Ok(())
    }

    pub(super) fn glBindAttribLocation(
        &mut self,
        ctx: &mut Context,
        program: u32,
        index: u32,
        name: Text<'_>,
    ) -> GlResult {
        if index as usize >= MAX_ATTRIBS {
            return Err(GlError::InvalidValue);
        }
        if name.as_str().starts_with("gl_") {
            return Err(GlError::InvalidOperation);
        }
        let objects = &mut ctx.objects;
        match objects.programs.get_mut(&program) {
            Some(p) => {
                p.bindings.insert(name.as_str().to_string(), index);
                Ok(())
            }
            None => Err(objects.shader_or_program_error(program)),
        }
    }

    pub(super) fn glLinkProgram(&mut self, ctx: &mut Context, program: u32) -> GlResult {
        let id = self.next_uid();
        let gpu = &self.gpu;
        let objects = &mut ctx.objects;
        let Some(p) = objects.programs.get(&program) else { return Err(objects.shader_or_program_error(program)) };
        // Not the program an active transform feedback captures from.
        let capturing = ctx.xfb.active().map(|c| c.program.id);
        if capturing.is_some() && p.linked.as_ref().map(|l| l.id) == capturing {
            return Err(GlError::InvalidOperation);
        }
        let result = link_stages(objects, p).and_then(|linked| create_gpu_program(gpu, linked, id));
        if let Some(p) = objects.programs.get_mut(&program) {
            p.install(result);
        }
        Ok(())
    }

    pub(super) fn glUseProgram(&mut self, ctx: &mut Context, program: u32) -> GlResult {
        if ctx.xfb.capturing().is_some() {
            return Err(GlError::InvalidOperation);
        }
        let objects = &mut ctx.objects;
        if program != 0 && !objects.programs.get(&program).is_some_and(|p| p.link_ok) {
            return Err(objects.shader_or_program_error(program));
        }
        let old = std::mem::replace(&mut ctx.bindings.program, program);
        crate::linking::release_if_unused(ctx, old);
        Ok(())
    }

    pub(super) fn glValidateProgram(&mut self, ctx: &mut Context, program: u32) -> GlResult {
        let objects = &mut ctx.objects;
        match objects.programs.get_mut(&program) {
            Some(p) => {
                p.validated = p.link_ok;
                Ok(())
            }
            None => Err(objects.shader_or_program_error(program)),
        }
    }

    pub(super) fn glIsProgram(&mut self, ctx: &mut Context, name: u32) -> bool {
        ctx.objects.programs.contains_key(&name)
    }

    pub(super) fn glGetProgramiv(&mut self, ctx: &mut Context, program: u32, pname: u32) -> i32 {
        let v = match ctx.objects.programs.get(&program) {
            Some(p) => {
                let linked = p.linked.as_ref();
                match pname {
                    LINK_STATUS => Ok(i32::from(p.link_ok)),
                    // Linking completes within glLinkProgram.
                    COMPLETION_STATUS_KHR => Ok(1),
                    DELETE_STATUS => Ok(i32::from(p.delete_pending)),
                    PROGRAM_SEPARABLE_EXT => Ok(i32::from(p.separable)),
                    VALIDATE_STATUS => Ok(i32::from(p.validated)),
                    INFO_LOG_LENGTH => Ok(if p.log.is_empty() { 0 } else { p.log.len() as i32 + 1 }),
                    ATTACHED_SHADERS => Ok(p.attached.len() as i32),
                    PROGRAM_BINARY_LENGTH_OES => Ok(crate::programs::length(p)),
                    ACTIVE_ATTRIBUTES => Ok(linked.map_or(0, |l| l.info.attributes.len() as i32)),
                    ACTIVE_UNIFORMS => Ok(linked.map_or(0, |l| crate::active_uniforms::active(&l.info).len() as i32)),
                    ACTIVE_ATTRIBUTE_MAX_LENGTH => Ok(linked
                        .map_or(0, |l| l.info.attributes.iter().map(|a| a.0.name.len() as i32 + 1).max().unwrap_or(0))),
                    _ if ctx.es3() && crate::transform_feedback::program_state(p, pname).is_some() => {
                        Ok(crate::transform_feedback::program_state(p, pname).unwrap_or(0))
                    }
                    crate::glsl::blocks::ACTIVE_UNIFORM_BLOCKS if ctx.es3() => {
                        Ok(linked.map_or(0, |l| l.info.blocks.len() as i32))
                    }
                    crate::glsl::blocks::ACTIVE_UNIFORM_BLOCK_MAX_NAME_LENGTH if ctx.es3() => Ok(linked
                        .map_or(0, |l| l.info.blocks.iter().map(|b| b.block.name.len() as i32 + 1).max().unwrap_or(0))),
                    ACTIVE_UNIFORM_MAX_LENGTH => Ok(linked.map_or(0, |l| {
                        let list = crate::active_uniforms::active(&l.info);
                        list.iter().map(|a| a.name.len() as i32 + 1).max().unwrap_or(0)
                    })),
                    _ => Err(GlError::InvalidEnum),
                }
            }
            None => Err(ctx.objects.shader_or_program_error(program)),
        };
        v.unwrap_or_else(|e| {
            ctx.record(e);
            0
        })
    }

    pub(super) fn glGetProgramInfoLog(&mut self, ctx: &mut Context, program: u32) -> String {
        with_program(ctx, program, String::new(), |p| p.log.clone())
    }

    pub(super) fn glGetAttachedShaders(&mut self, ctx: &mut Context, program: u32) -> Vec<u32> {
        with_program(ctx, program, vec![], |p| p.attached.clone())
    }

    pub(super) fn glGetAttribLocation(&mut self, ctx: &mut Context, program: u32, name: Text<'_>) -> i32 {
        let v = match ctx.objects.programs.get(&program) {
            Some(p) => match &p.linked {
                Some(l) => Ok(l.info.attributes.iter().find(|a| a.0.name == name.as_str()).map_or(-1, |a| a.1 as i32)),
                None => Err(GlError::InvalidOperation),
            },
            None => Err(ctx.objects.shader_or_program_error(program)),
        };
        v.unwrap_or_else(|e| {
            ctx.record(e);
            -1
        })
    }

    pub(super) fn glGetFragDataLocation(&mut self, ctx: &mut Context, program: u32, name: Text<'_>) -> i32 {
        let v = match ctx.objects.programs.get(&program) {
            Some(p) => match &p.linked {
                Some(l) => Ok(l.info.outputs.iter().find(|o| o.0 == name.as_str()).map_or(-1, |o| o.1 as i32)),
                None => Err(GlError::InvalidOperation),
            },
            None => Err(ctx.objects.shader_or_program_error(program)),
        };
        v.unwrap_or_else(|e| {
            ctx.record(e);
            -1
        })
    }

    pub(super) fn glGetActiveAttrib(&mut self, ctx: &mut Context, program: u32, index: u32) -> Option<ActiveVariable> {
        let v = linked_for_query(&ctx.objects, program).and_then(|l| {
            let (a, _) = l.info.attributes.get(index as usize).ok_or(GlError::InvalidValue)?;
            Ok(ActiveVariable { size: 1, ty: a.ty.gl_enum(), name: a.name.clone() })
        });
        v.map_err(|e| ctx.record(e)).ok()
    }
}

/// `GL_PROGRAM_BINARY_FORMATS_OES`' one entry: Strata's program binary format.
pub const PROGRAM_BINARY_FORMAT: u32 = 0x5354_5241;
/// The first bytes of every binary.
const MAGIC: &[u8; 8] = b"STRATApb";
/// The layout of what follows the header; a binary of another version is refused.
const VERSION: u32 = 2;
/// Magic, version and CRC-32.
const HEADER: usize = 16;
/// The most a binary's payload may claim to hold.
const LIMIT: usize = 64 << 20;

/// Why a binary was refused.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum BinaryError {
    /// Too short to hold a header, or not begun by Strata's magic number.
    #[error("the binary is not a Strata program binary")]
    Foreign,
    /// Made by a build whose binary format differs.
    #[error("the binary's format version is {0}, and this daemon reads version {VERSION}: link the program from its sources")]
    Version(u32),
    /// The checksum does not match the contents.
    #[error("the binary is corrupt: its checksum does not match its contents")]
    Checksum,
    /// The contents do not decode, or hold what the GL calls would refuse.
    #[error("the binary is malformed: {0}")]
    Malformed(String),
}

/// `recipe`'s binary.
pub fn encode(recipe: &Recipe) -> Vec<u8> {
    let payload = bincode::serde::encode_to_vec(recipe, bincode::config::standard()).unwrap_or_default();
    let mut out = Vec::with_capacity(HEADER + payload.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&crc32fast::hash(&payload).to_le_bytes());
    out.extend_from_slice(&payload);
    out
}

/// The recipe `bytes` holds, checked as the GL calls that make one check their input.
pub fn decode(bytes: &[u8]) -> Result<Recipe, BinaryError> {
    if bytes.len() < HEADER || &bytes[..8] != MAGIC {
        return Err(BinaryError::Foreign);
    }
    let word = |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    if word(8) != VERSION {
        return Err(BinaryError::Version(word(8)));
    }
    let payload = &bytes[HEADER..];
    if crc32fast::hash(payload) != word(12) {
        return Err(BinaryError::Checksum);
    }
    let config = bincode::config::standard().with_limit::<LIMIT>();
    let (recipe, used): (Recipe, usize) =
        bincode::serde::decode_from_slice(payload, config).map_err(|e| BinaryError::Malformed(e.to_string()))?;
    if used != payload.len() {
        return Err(BinaryError::Malformed(format!("{} bytes follow the program", payload.len() - used)));
    }
    for (name, index) in &recipe.bindings {
        if *index as usize >= MAX_ATTRIBS || name.starts_with("gl_") {
            return Err(BinaryError::Malformed(format!("attribute `{name}` is bound to {index}")));
        }
    }
    Ok(recipe)
}

/// The length of `p`'s binary (`GL_PROGRAM_BINARY_LENGTH_OES`): 0 unless its last link succeeded.
pub fn length(p: &Program) -> i32 {
    match (&p.linked, p.link_ok) {
        (Some(l), true) => encode(&l.recipe).len() as i32,
        _ => 0,
    }
}

/// Compiles and links what `bytes` holds (a one-stage binary as a separable program's
/// stage, which `separable` must allow): the program info log on failure.
fn relink(bytes: &[u8], separable: bool) -> Result<LinkResult, String> {
    let recipe = decode(bytes).map_err(|e| format!("error: {e}"))?;
    let compile = |stage: Stage, source: &str, what: &str| {
        if source.is_empty() {
            return Ok(None);
        }
        glsl::compile(stage, source)
            .map(Some)
            .map_err(|log| format!("error: the binary's {what} shader does not compile:\n{log}"))
    };
    let vertex = compile(Stage::Vertex, &recipe.vertex, "vertex")?;
    let fragment = compile(Stage::Fragment, &recipe.fragment, "fragment")?;
    let bindings: HashMap<String, u32> = recipe.bindings.iter().cloned().collect();
    let xfb = recipe.xfb.clone();
    let (mut info, mut recipe) = link_either(vertex.as_ref(), fragment.as_ref(), &bindings, separable)?;
    if let Some(v) = &vertex {
        info.capture = glsl::capture::resolve(&xfb.0, !xfb.1, v)?;
    }
    recipe.xfb = xfb;
    Ok((info, recipe, LinkedStages::new(separable, vertex, fragment)))
}

#[allow(non_snake_case)]
impl GlesExecutor {
    /// Links `program` from a binary. As on Mesa, the program's link status is false from
    /// the start, so a length or format error leaves it unlinked too.
    pub(super) fn glProgramBinaryOES(
        &mut self,
        ctx: &mut Context,
        program: u32,
        binary_format: u32,
        length: i32,
        binary: Blob<'_>,
    ) -> GlResult {
        let id = self.next_uid();
        let objects = &mut ctx.objects;
        let Some(p) = objects.programs.get_mut(&program) else { return Err(objects.shader_or_program_error(program)) };
        p.link_ok = false;
        p.log.clear();
        if length < 0 {
            return Err(GlError::InvalidValue);
        }
        if binary_format != PROGRAM_BINARY_FORMAT {
            return Err(GlError::InvalidEnum);
        }
        let bytes = binary.as_bytes();
        let bytes = &bytes[..bytes.len().min(length as usize)];
        let result = relink(bytes, p.separable).and_then(|linked| create_gpu_program(&self.gpu, linked, id));
        // The program's varyings for transform feedback become the binary's.
        if let Ok(l) = &result {
            p.xfb = l.recipe.xfb.clone();
        }
        p.install(result);
        Ok(())
    }

    /// The binary of `program`'s last link; see the command's reply.
    pub(super) fn glGetProgramBinaryOES(
        &mut self,
        ctx: &mut Context,
        program: u32,
        buf_size: i32,
    ) -> Option<Option<(u32, Bytes)>> {
        let Some(p) = ctx.objects.programs.get(&program) else {
            let e = ctx.objects.shader_or_program_error(program);
            ctx.record(e);
            return None;
        };
        if buf_size < 0 {
            ctx.record(GlError::InvalidValue);
            return None;
        }
        let binary = p.linked.as_ref().filter(|_| p.link_ok).map(|l| encode(&l.recipe));
        match binary {
            Some(b) if b.len() <= buf_size as usize => Some(Some((PROGRAM_BINARY_FORMAT, Bytes(b)))),
            _ => {
                ctx.record(GlError::InvalidOperation);
                Some(None)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn recipe() -> Recipe {
        Recipe {
            vertex: "attribute vec4 p; void main() { gl_Position = p; }".into(),
            fragment: "void main() { gl_FragColor = vec4(1.0); }".into(),
            bindings: vec![("p".into(), 3)],
            xfb: (Vec::new(), false),
        }
    }

    /// `bytes` with the checksum recomputed over what follows the header.
    fn resealed(mut bytes: Vec<u8>) -> Vec<u8> {
        let crc = crc32fast::hash(&bytes[HEADER..]).to_le_bytes();
        bytes[12..16].copy_from_slice(&crc);
        bytes
    }

    #[test]
    fn a_binary_decodes_to_what_it_was_made_from() {
        assert_eq!(decode(&encode(&recipe())), Ok(recipe()));
    }

    #[test]
    fn every_damaged_binary_is_refused_with_its_reason() {
        let good = encode(&recipe());
        assert_eq!(decode(&good[..HEADER - 1]), Err(BinaryError::Foreign));
        assert_eq!(decode(b"MESA binary, whatever it holds"), Err(BinaryError::Foreign));
        let mut other = good.clone();
        other[8] = 1;
        assert_eq!(decode(&other), Err(BinaryError::Version(1)), "a binary of the layout before");
        for at in [HEADER, good.len() / 2, good.len() - 1] {
            let mut flipped = good.clone();
            flipped[at] ^= 0x10;
            assert_eq!(decode(&flipped), Err(BinaryError::Checksum), "byte {at} flipped");
        }
        assert_eq!(decode(&good[..good.len() - 3]), Err(BinaryError::Checksum));
        // Well sealed, yet not what the GL calls accept.
        let mut trailing = good.clone();
        trailing.push(0);
        assert!(matches!(decode(&resealed(trailing)), Err(BinaryError::Malformed(_))));
        for (name, index) in [("p", MAX_ATTRIBS as u32), ("gl_Vertex", 0)] {
            let bad = Recipe { bindings: vec![(name.into(), index)], ..recipe() };
            assert!(matches!(decode(&encode(&bad)), Err(BinaryError::Malformed(_))), "{name} at {index}");
        }
        // A length prefix that claims more than the limit allows fails without allocating it.
        let mut huge = good[..HEADER].to_vec();
        huge.extend_from_slice(&[0xFD, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x7F]);
        assert!(matches!(decode(&resealed(huge)), Err(BinaryError::Malformed(_))));
    }

    proptest::proptest! {
        /// Any payload behind a good header is decoded or refused, never a panic, and what
        /// decodes links or fails with a log.
        #[test]
        fn any_sealed_payload_is_decoded_or_refused(payload in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..400)) {
            let mut bytes = encode(&recipe())[..HEADER].to_vec();
            bytes.extend_from_slice(&payload);
            let bytes = resealed(bytes);
            if decode(&bytes).is_ok() {
                let _ = relink(&bytes, false);
            }
        }

        /// Recipes with arbitrary sources and bindings survive the round trip.
        #[test]
        fn any_recipe_round_trips(vertex in ".*", fragment in ".*", index in 0..MAX_ATTRIBS as u32) {
            let r = Recipe { vertex, fragment, bindings: vec![("a".into(), index)], xfb: (Vec::new(), false) };
            proptest::prop_assert_eq!(decode(&encode(&r)), Ok(r));
        }
    }

    #[test]
    fn a_binary_whose_sources_fail_fails_the_link_with_the_compile_log() {
        let bad = Recipe { fragment: "void main() { gl_FragColor = oops; }".into(), ..recipe() };
        let log = relink(&encode(&bad), false).err().unwrap_or_default();
        assert!(log.contains("fragment shader does not compile"), "{log}");
        assert!(relink(&encode(&recipe()), false).is_ok());
    }
}
