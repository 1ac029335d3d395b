//! GLSL ES 3.00 uniform blocks (§4.3.7): lifted out of the shader as [`Block`]s, laid out by
//! std140 (`shared` and `packed` take std140's layout, as §4.3.8.3 allows), and declared again in
//! the generated code at their program-wide binding.

use std::collections::HashMap;
use std::fmt::Write as _;

use glsl_lang::ast::{self, TypeQualifierSpecData};

use crate::glsl::consts::Val;
use crate::glsl::linked::LinkedBlock;
use crate::glsl::structs::{elements, FieldTy, Structs, MAX_DEPTH};
use crate::glsl::types::{Block, BlockMember, Shader};

/// `GL_MAX_UNIFORM_BLOCK_SIZE`: the bytes one block may hold (ES 3.0's minimum).
pub const MAX_UNIFORM_BLOCK_SIZE: u32 = 16384;
/// `GL_MAX_VERTEX_UNIFORM_BLOCKS` and `GL_MAX_FRAGMENT_UNIFORM_BLOCKS` (ES 3.0's minimum).
pub const MAX_STAGE_UNIFORM_BLOCKS: usize = 12;
/// `GL_MAX_COMBINED_UNIFORM_BLOCKS` and `GL_MAX_UNIFORM_BUFFER_BINDINGS` (ES 3.0's minimum).
pub const MAX_COMBINED_UNIFORM_BLOCKS: usize = 24;
/// `glGetProgramiv`'s names for a program's blocks.
pub const ACTIVE_UNIFORM_BLOCK_MAX_NAME_LENGTH: u32 = 0x8A35;
/// `GL_ACTIVE_UNIFORM_BLOCKS`.
pub const ACTIVE_UNIFORM_BLOCKS: u32 = 0x8A36;
/// The binding of a program's first block in its bind group, after the default block (0) and
/// the samplers (1 + 3k).
pub const FIRST_BLOCK_BINDING: u32 = 100;

/// One element block of an array of blocks, as `block_arrays` made it.
#[derive(Debug, Clone)]
pub(super) struct Element {
    /// The array's block name (`B`).
    pub(super) base: String,
    /// The element's index.
    pub(super) index: u32,
    /// Whether the shader's code indexes it (`GL_UNIFORM_BLOCK_REFERENCED_BY_*`).
    pub(super) referenced: bool,
}

/// The element blocks `block_arrays` made, by their declared name (`B__k`).
pub(super) type Elements = HashMap<String, Element>;

/// The declared name of element `index` of block or instance `name`.
pub(super) fn element_name(name: &str, index: u32) -> String {
    format!("{name}__{index}")
}

/// The layout qualifiers a block (or `layout(…) uniform;`, or a member) may carry: std140 and
/// its stand-ins, and the matrix layout, which it returns (`Some(true)`: `row_major`, the last
/// one given winning). `shared` reaches here renamed (`preprocess`).
fn check_layout(q: Option<&ast::TypeQualifier>) -> Result<Option<bool>, String> {
    let mut row_major = None;
    for s in q.iter().flat_map(|q| q.qualifiers.iter()) {
        let TypeQualifierSpecData::Layout(l) = &s.content else { continue };
        for id in &l.ids {
            match &id.content {
                ast::LayoutQualifierSpecData::Shared => {}
                ast::LayoutQualifierSpecData::Identifier(name, None)
                    if matches!(name.0.as_str(), "std140" | "packed" | "shar__") => {}
                ast::LayoutQualifierSpecData::Identifier(name, None)
                    if matches!(name.0.as_str(), "row_major" | "column_major") =>
                {
                    row_major = Some(name.0 == "row_major");
                }
                ast::LayoutQualifierSpecData::Identifier(name, _) => {
                    return Err(format!("0: layout qualifier `{}' is not allowed on a uniform block", name.0))
                }
            }
        }
    }
    Ok(row_major)
}

/// Whether `decl` is `layout(…) uniform;`, the default layout of later blocks (checked); a
/// matrix layout it gives becomes `row_major`, the default.
pub(super) fn default_layout(q: &ast::TypeQualifier, row_major: &mut bool) -> Result<bool, String> {
    let uniform = q.qualifiers.iter().any(|s| {
        matches!(&s.content, TypeQualifierSpecData::Storage(st) if st.content == ast::StorageQualifierData::Uniform)
    });
    if uniform {
        if let Some(r) = check_layout(Some(q))? {
            *row_major = r;
        }
    }
    Ok(uniform)
}

/// Lifts a `uniform` block declaration (perhaps an element of an array of blocks, as
/// `block_arrays` made it), its matrices row-major by default where `row_major`; `None` if the
/// block is not a uniform block. A member of structure type is laid out leaf by leaf
/// ([`place`]; `block_structs` rewrites its reads).
pub(super) fn lift(
    b: &ast::Block,
    consts: &HashMap<String, Val>,
    elements: &Elements,
    row_major: bool,
    structs: &Structs,
) -> Result<Option<Block>, String> {
    let uniform = b.qualifier.qualifiers.iter().any(|s| {
        matches!(&s.content, TypeQualifierSpecData::Storage(st) if st.content == ast::StorageQualifierData::Uniform)
    });
    if !uniform {
        return Ok(None);
    }
    let block_major = check_layout(Some(&b.qualifier))?.unwrap_or(row_major);
    let instance = b.identifier.as_ref().map(|id| id.ident.0.to_string());
    let (name, element, referenced) = match elements.get(b.name.0.as_str()) {
        Some(e) => (format!("{}[{}]", e.base, e.index), Some(e.index), e.referenced),
        None => (b.name.0.to_string(), None, true),
    };
    let mut members = Vec::new();
    let mut struct_members = Vec::new();
    let mut cursor = 0u32;
    for f in &b.fields {
        let major = check_layout(f.qualifier.as_ref())?.unwrap_or(block_major);
        for field in crate::glsl::structs::fields(std::slice::from_ref(f), consts)? {
            if let FieldTy::Struct(s) = &field.ty {
                struct_members.push((field.name.clone(), s.clone(), field.array));
            }
            let (fname, ty, array) = (field.name, &field.ty, field.array);
            place(structs, &name, fname, ty, array, major, &mut cursor, &mut members, 0)?;
        }
    }
    let size = cursor.div_ceil(16) * 16;
    Ok(Some(Block { name, instance, element, referenced, members, structs: struct_members, size }))
}

/// std140's rounding of a structure's start and end, and of an array's stride: a `vec4`.
fn round(n: u32) -> u32 {
    n.div_ceil(16) * 16
}

/// Places a member named `name` (relative to its block: `s.x`, `a[1].m`) of type `ty` (an
/// array where `array`), matrices row by row where `row_major`, at or after `cursor`, which it
/// moves past the member; leaves go to `out`. `block` names the block in errors.
#[allow(clippy::too_many_arguments)]
fn place(
    structs: &Structs,
    block: &str,
    name: String,
    ty: &FieldTy,
    array: Option<u32>,
    row_major: bool,
    cursor: &mut u32,
    out: &mut Vec<BlockMember>,
    depth: usize,
) -> Result<(), String> {
    let too_big = || format!("error: uniform block `{block}' needs more than {MAX_UNIFORM_BLOCK_SIZE} bytes");
    match ty {
        FieldTy::Basic(t, _) if t.is_sampler() => Err("0: samplers are not allowed in uniform blocks".into()),
        FieldTy::Basic(t, _) => {
            let mut m =
                BlockMember { name, ty: *t, array, row_major: row_major && t.columns() > 0, offset: 0, stride: 0 };
            // A row-major matrix is laid out as its transpose (one row per 16 bytes).
            let (size, align) = crate::glsl::block_members::storage(&m).std140();
            let (align, stride, total) = match array {
                // An array's elements (and a matrix's columns) are 16 bytes apart at least.
                Some(n) => (16, round(size), round(size).checked_mul(n)),
                None => (align, 0, Some(size)),
            };
            m.offset = cursor.div_ceil(align) * align;
            m.stride = stride;
            *cursor = total
                .and_then(|t| m.offset.checked_add(t))
                .filter(|&o| o <= MAX_UNIFORM_BLOCK_SIZE)
                .ok_or_else(too_big)?;
            out.push(m);
            Ok(())
        }
        FieldTy::Struct(s) => {
            let fields =
                structs.get(s).filter(|_| depth < MAX_DEPTH).ok_or_else(|| format!("0: unknown structure `{s}'"))?;
            for e in elements(&name, array) {
                *cursor = round(*cursor);
                for f in fields {
                    place(
                        structs,
                        block,
                        format!("{e}.{}", f.name),
                        &f.ty,
                        f.array,
                        row_major,
                        cursor,
                        out,
                        depth + 1,
                    )?;
                }
                *cursor = round(*cursor);
                if *cursor > MAX_UNIFORM_BLOCK_SIZE {
                    return Err(too_big());
                }
            }
            Ok(())
        }
        FieldTy::Other(t) => Err(format!("0: uniform block members of type '{t}' are not supported")),
    }
}

/// The generated declaration of `block` at `binding`.
pub(super) fn declaration(block: &Block, binding: u32) -> String {
    // An element of an array of blocks is declared under the name `block_arrays` gave it.
    let ident = match block.element {
        Some(k) => element_name(block.base_name(), k),
        None => block.name.clone(),
    };
    let mut out = format!("layout(std140, set = 0, binding = {binding}) uniform {ident} {{\n");
    // Where a member lies past where std140 would place it after the one before (after a
    // structure's leaves), padding fills the gap.
    let mut end = 0u32;
    for (k, m) in block.members.iter().enumerate() {
        let (size, align) = crate::glsl::block_members::storage(m).std140();
        let natural = if m.array.is_some() { end.div_ceil(16) * 16 } else { end.div_ceil(align) * align };
        for p in 0..m.offset.saturating_sub(natural) / 4 {
            let _ = writeln!(out, "    float strata_pad{k}_{p};");
        }
        let _ = writeln!(out, "    {}", crate::glsl::block_members::declaration(m));
        end = m.offset + m.array.map_or(size, |n| n * m.stride);
    }
    let _ = writeln!(out, "}}{};", block.instance.as_deref().map_or(String::new(), |i| format!(" {i}")));
    out
}

/// The program's uniform blocks: each stage's, one per name (a block both stages declare must
/// be declared alike, §4.3.7), each at its binding, within the limits.
pub(super) fn link_blocks(vs: &Shader, fs: &Shader) -> Result<Vec<LinkedBlock>, String> {
    for (s, stage) in [(vs, "vertex"), (fs, "fragment")] {
        if s.blocks.len() > MAX_STAGE_UNIFORM_BLOCKS {
            return Err(format!("error: the {stage} shader has more than {MAX_STAGE_UNIFORM_BLOCKS} uniform blocks"));
        }
    }
    let mut blocks: Vec<LinkedBlock> = Vec::new();
    for (b, vertex) in vs.blocks.iter().map(|b| (b, true)).chain(fs.blocks.iter().map(|b| (b, false))) {
        match blocks.iter_mut().find(|l| l.block.name == b.name) {
            Some(l) if l.block.members != b.members || l.block.instance.is_some() != b.instance.is_some() => {
                return Err(format!("error: uniform block `{}' is declared differently in the two stages", b.name))
            }
            Some(l) => l.fragment = b.referenced,
            None => blocks.push(LinkedBlock {
                block: b.clone(),
                binding: FIRST_BLOCK_BINDING + blocks.len() as u32,
                vertex: vertex && b.referenced,
                fragment: !vertex && b.referenced,
            }),
        }
    }
    if blocks.len() > MAX_COMBINED_UNIFORM_BLOCKS {
        return Err(format!("error: the program has more than {MAX_COMBINED_UNIFORM_BLOCKS} uniform blocks"));
    }
    Ok(blocks)
}
