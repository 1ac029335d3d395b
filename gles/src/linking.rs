//! Linking programs' stages, and freeing what deleted programs and shaders held once nothing
//! uses them: what program, pipeline and program binary calls share.

use std::collections::HashMap;

use crate::context::{Context, Objects};
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::glsl;
use crate::glsl::types::Stage;
use crate::limits::MAX_ATTRIBS;
use crate::objects::program::{LinkResult, LinkedProgram, LinkedStages, Program, Recipe, ShaderObj};

/// Frees the shaders among `shaders` that were deleted while attached and are now attached
/// to no program.
pub fn release_shaders(objects: &mut Objects, shaders: &[u32]) {
    for s in shaders {
        let still = objects.programs.values().any(|p| p.attached.contains(s));
        if !still && objects.shaders.get(s).is_some_and(|x| x.delete_pending) {
            objects.shaders.remove(s);
            objects.forget_label(SHADER_KHR, *s);
        }
    }
}

/// Removes `program` (deleted, and no longer in use) with its label, freeing the shaders
/// that were deleted while attached to it.
pub fn remove_program(objects: &mut Objects, program: u32) {
    if let Some(p) = objects.programs.remove(&program) {
        objects.forget_label(PROGRAM_KHR, program);
        release_shaders(objects, &p.attached);
    }
}

/// The last successful link of `program`, for the active-variable queries: an unlinked
/// program is `GL_INVALID_VALUE`, a name that is no program the usual error.
pub fn linked_for_query(objects: &Objects, program: u32) -> GlResult<&LinkedProgram> {
    match objects.programs.get(&program) {
        Some(p) => p.linked.as_deref().ok_or(GlError::InvalidValue),
        None => Err(objects.shader_or_program_error(program)),
    }
}

/// Links the program's attached shaders: the program info log on failure. A separable
/// program may have one stage; it is linked against a stand-in for the other.
pub fn link_stages(objects: &Objects, p: &Program) -> Result<LinkResult, String> {
    let find = |stage: Stage| p.attached.iter().filter_map(|s| objects.shaders.get(s)).find(|s| s.stage == stage);
    let compiled = |s: &ShaderObj| match &s.compiled {
        Some(c) if s.compiled_ok => Ok(c.clone()),
        _ => Err("error: an attached shader did not compile".to_string()),
    };
    let vertex = find(Stage::Vertex).map(compiled).transpose()?;
    let fragment = find(Stage::Fragment).map(compiled).transpose()?;
    let (mut info, mut recipe) = link_either(vertex.as_ref(), fragment.as_ref(), &p.bindings, p.separable)?;
    if let Some(v) = &vertex {
        info.capture = glsl::capture::resolve(&p.xfb.0, !p.xfb.1, v)?;
    }
    // A binary of the program captures what it does.
    recipe.xfb = p.xfb.clone();
    Ok((info, recipe, LinkedStages::new(p.separable, vertex, fragment)))
}

/// Links both stages, or one alone where `separable` allows.
pub fn link_either(
    vertex: Option<&glsl::Shader>,
    fragment: Option<&glsl::Shader>,
    bindings: &HashMap<String, u32>,
    separable: bool,
) -> Result<(glsl::Linked, Recipe), String> {
    match (vertex, fragment) {
        (Some(v), Some(f)) => link_shaders(v, f, bindings),
        (Some(one), None) | (None, Some(one)) if separable => link_one(one, bindings),
        _ => Err("error: a program needs one vertex and one fragment shader".to_string()),
    }
}

/// Links one compiled stage alone, as a separable program.
pub fn link_one(s: &glsl::Shader, bindings: &HashMap<String, u32>) -> Result<(glsl::Linked, Recipe), String> {
    let info = glsl::link_alone(s, bindings, MAX_ATTRIBS as u32)?;
    Ok((info, Recipe::new(s, bindings)))
}

/// Links two compiled shaders with attribute `bindings`, with what they were linked from.
pub fn link_shaders(
    v: &glsl::Shader,
    f: &glsl::Shader,
    bindings: &HashMap<String, u32>,
) -> Result<(glsl::Linked, Recipe), String> {
    let info = glsl::link(v, f, bindings, MAX_ATTRIBS as u32)?;
    let mut recipe = Recipe::new(v, bindings);
    recipe.fragment = f.source.clone();
    Ok((info, recipe))
}

/// Frees `program` if it was deleted while in use and nothing uses it now.
pub fn release_if_unused(ctx: &mut Context, program: u32) {
    let objects = &ctx.objects;
    let pending = objects.programs.get(&program).is_some_and(|p| p.delete_pending);
    let used = ctx.bindings.program == program
        || objects.pipelines.values().any(|pl| pl.uses(program))
        || ctx.others_use.contains(&program);
    if pending && !used {
        crate::linking::remove_program(&mut ctx.objects, program);
    }
}
