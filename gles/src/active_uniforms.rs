//! A program's active uniforms as ES 3.0 lists them: the default block's, then each uniform
//! block's members (named `Block.member` where the block has an instance name, `member` where
//! not, arrays as `name[0]`), with `glGetActiveUniform`, `glGetUniformIndices`,
//! `glGetActiveUniformsiv` and `GL_UNIFORM_BLOCK_ACTIVE_UNIFORM_INDICES` on that list, checked in
//! Mesa's order.

use strata_protocol::{ActiveVariable, Slice, Text};

use crate::context::Context;
use crate::error::GlError;
use crate::glsl::{Linked, Ty};
use crate::GlesExecutor;

/// `glGetActiveUniformsiv`'s names.
const UNIFORM_TYPE: u32 = 0x8A37;
const UNIFORM_SIZE: u32 = 0x8A38;
const UNIFORM_NAME_LENGTH: u32 = 0x8A39;
const UNIFORM_BLOCK_INDEX: u32 = 0x8A3A;
const UNIFORM_OFFSET: u32 = 0x8A3B;
const UNIFORM_ARRAY_STRIDE: u32 = 0x8A3C;
const UNIFORM_MATRIX_STRIDE: u32 = 0x8A3D;
const UNIFORM_IS_ROW_MAJOR: u32 = 0x8A3E;
/// What `glGetUniformIndices` answers for a name no active uniform has.
const INVALID_INDEX: u32 = u32::MAX;

/// One active uniform.
pub(crate) struct Active {
    /// Its name as GL reports it (`[0]` after an array's).
    pub(crate) name: String,
    /// Its type.
    pub(crate) ty: Ty,
    /// Its array length (1 for one value).
    pub(crate) size: u32,
    /// Its uniform block, and its offset and array stride there (`None` in the default block,
    /// whose layout is Strata's own).
    pub(crate) block: Option<(u32, u32, u32)>,
    /// A matrix in a block laid out row by row.
    pub(crate) row_major: bool,
}

/// `info`'s active uniforms, in the order their indices count.
pub(crate) fn active(info: &Linked) -> Vec<Active> {
    let mut out: Vec<Active> = info
        .uniforms
        .iter()
        .map(|u| Active {
            name: if u.is_array { format!("{}[0]", u.gl_name) } else { u.gl_name.clone() },
            ty: u.ty,
            size: u.len,
            block: None,
            row_major: false,
        })
        .collect();
    for (b, lb) in info.blocks.iter().enumerate() {
        // The members of an array of blocks are listed once, under the block's name without
        // an index, as its first element's (as on Mesa).
        if listed_block(info, b as u32) != b as u32 {
            continue;
        }
        let block_name = lb.block.base_name();
        for m in &lb.block.members {
            let name = match &lb.block.instance {
                Some(_) => format!("{block_name}.{}", m.name),
                None => m.name.clone(),
            };
            out.push(Active {
                name: if m.array.is_some() { format!("{name}[0]") } else { name },
                ty: m.ty,
                size: m.array.unwrap_or(1),
                block: Some((b as u32, m.offset, m.stride)),
                row_major: m.row_major,
            });
        }
    }
    out
}

/// The active uniform `name` names: its GL name, or an array's without `[0]` or with another
/// element's index (whatever the index, as Mesa finds it).
fn index_of(list: &[Active], name: &str) -> u32 {
    let element_of = |base: &str| {
        name.strip_prefix(base)
            .and_then(|rest| rest.strip_prefix('['))
            .and_then(|rest| rest.strip_suffix(']'))
            .is_some_and(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()))
    };
    list.iter()
        .position(|a| a.name == name || a.name.strip_suffix("[0]").is_some_and(|base| base == name || element_of(base)))
        .map_or(INVALID_INDEX, |i| i as u32)
}

/// What `glGetActiveUniformsiv` answers of `a` for `pname` (`None`: not one of its names).
fn property(a: &Active, pname: u32) -> Option<i32> {
    let in_block = a.block;
    Some(match pname {
        UNIFORM_TYPE => a.ty.gl_enum() as i32,
        UNIFORM_SIZE => a.size as i32,
        UNIFORM_NAME_LENGTH => a.name.len() as i32 + 1,
        UNIFORM_BLOCK_INDEX => in_block.map_or(-1, |b| b.0 as i32),
        UNIFORM_OFFSET => in_block.map_or(-1, |b| b.1 as i32),
        UNIFORM_ARRAY_STRIDE => in_block.map_or(-1, |b| b.2 as i32),
        // std140 lays a matrix's columns (rows, row-major) out 16 bytes apart.
        UNIFORM_MATRIX_STRIDE => match in_block {
            Some(_) if a.ty.columns() > 0 => 16,
            Some(_) => 0,
            None => -1,
        },
        UNIFORM_IS_ROW_MAJOR => i32::from(a.row_major),
        _ => return None,
    })
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glGetActiveUniform(&mut self, ctx: &mut Context, program: u32, index: u32) -> Option<ActiveVariable> {
        let v = crate::linking::linked_for_query(&ctx.objects, program).and_then(|l| {
            let list = active(&l.info);
            let a = list.get(index as usize).ok_or(GlError::InvalidValue)?;
            Ok(ActiveVariable { size: a.size as i32, ty: a.ty.gl_enum(), name: a.name.clone() })
        });
        v.map_err(|e| ctx.record(e)).ok()
    }

    /// `names`: the `count` names, each ended by a newline.
    pub(super) fn glGetUniformIndices(
        &mut self,
        ctx: &mut Context,
        program: u32,
        count: i32,
        names: Text<'_>,
    ) -> Vec<u32> {
        if count < 0 {
            ctx.record(GlError::InvalidValue);
            return Vec::new();
        }
        let names: Vec<&str> = names.as_str().lines().take(count as usize).collect();
        match ctx.objects.programs.get(&program) {
            Some(p) => {
                let list = p.linked.as_ref().map(|l| active(&l.info)).unwrap_or_default();
                names.iter().map(|n| index_of(&list, n)).collect()
            }
            None => {
                let e = ctx.objects.shader_or_program_error(program);
                ctx.record(e);
                Vec::new()
            }
        }
    }

    pub(super) fn glGetActiveUniformsiv(
        &mut self,
        ctx: &mut Context,
        program: u32,
        indices: Slice<'_, u32>,
        pname: u32,
    ) -> Vec<i32> {
        let Some(p) = ctx.objects.programs.get(&program) else {
            let e = ctx.objects.shader_or_program_error(program);
            ctx.record(e);
            return Vec::new();
        };
        let list = p.linked.as_ref().map(|l| active(&l.info)).unwrap_or_default();
        // Every index first: a bad one leaves nothing written.
        if indices.iter().any(|i| i as usize >= list.len()) {
            ctx.record(GlError::InvalidValue);
            return Vec::new();
        }
        let mut out = Vec::new();
        for i in indices.iter() {
            match property(&list[i as usize], pname) {
                Some(v) => out.push(v),
                None => {
                    ctx.record(GlError::InvalidEnum);
                    return Vec::new();
                }
            }
        }
        out
    }
}

/// The indices of block `block`'s members in `info`'s active uniforms
/// (`GL_UNIFORM_BLOCK_ACTIVE_UNIFORM_INDICES`).
pub(crate) fn block_members(info: &Linked, block: u32) -> Vec<i32> {
    let listed = listed_block(info, block);
    active(info)
        .iter()
        .enumerate()
        .filter(|(_, a)| a.block.is_some_and(|b| b.0 == listed))
        .map(|(i, _)| i as i32)
        .collect()
}

/// The block whose members stand for `block`'s in the active uniforms: the first element of
/// an array of blocks (the program's first block of that array), else `block` itself.
fn listed_block(info: &Linked, block: u32) -> u32 {
    let Some(b) = info.blocks.get(block as usize) else { return block };
    if b.block.element.is_none() {
        return block;
    }
    let first =
        info.blocks.iter().position(|o| o.block.element.is_some() && o.block.base_name() == b.block.base_name());
    first.map_or(block, |i| i as u32)
}
