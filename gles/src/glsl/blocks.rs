//! GLSL ES 3.00 uniform blocks (§4.3.7): lifted out of the shader as [`Block`]s, laid out by
//! std140 (`shared` and `packed` take std140's layout, as §4.3.8.3 allows), and declared again in
//! the generated code at their program-wide binding.

use std::collections::HashMap;
use std::fmt::Write as _;

use glsl_lang::ast::{self, TypeQualifierSpecData};

use crate::glsl::consts::Val;
use crate::glsl::linked::LinkedBlock;
use crate::glsl::types::{Block, BlockMember, Shader, Ty};

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
/// block is not a uniform block.
pub(super) fn lift(
    b: &ast::Block,
    consts: &HashMap<String, Val>,
    elements: &Elements,
    row_major: bool,
) -> Result<Option<Block>, String> {
    let uniform = b.qualifier.qualifiers.iter().any(|s| {
        matches!(&s.content, TypeQualifierSpecData::Storage(st) if st.content == ast::StorageQualifierData::Uniform)
    });
    if !uniform {
        return Ok(None);
    }
    let block_major = check_layout(Some(&b.qualifier))?.unwrap_or(row_major);
    let instance = b.identifier.as_ref().map(|id| id.ident.0.to_string());
    let mut members = Vec::new();
    for f in &b.fields {
        let major = check_layout(f.qualifier.as_ref())?.unwrap_or(block_major);
        let ty = Ty::from_spec(&f.ty.ty).filter(|t| !t.is_sampler()).ok_or_else(|| {
            "0: uniform block members of this type (structures, samplers) are not supported yet".to_string()
        })?;
        for id in &f.identifiers {
            let spec = id.array_spec.as_ref().or(f.ty.array_specifier.as_ref());
            let array = crate::glsl::consts::array_len(spec, consts)?;
            let row_major = major && ty.columns() > 0;
            members.push(BlockMember { name: id.ident.0.to_string(), ty, array, row_major, offset: 0, stride: 0 });
        }
    }
    let (name, element, referenced) = match elements.get(b.name.0.as_str()) {
        Some(e) => (format!("{}[{}]", e.base, e.index), Some(e.index), e.referenced),
        None => (b.name.0.to_string(), None, true),
    };
    let mut block = Block { name, instance, element, referenced, members, size: 0 };
    lay_out(&mut block)?;
    Ok(Some(block))
}

/// std140 (§2.12.6.4 of ES 3.0): each member's offset and array stride, and the block's size.
fn lay_out(block: &mut Block) -> Result<(), String> {
    let mut offset = 0u32;
    for m in &mut block.members {
        // A row-major matrix is laid out as its transpose (one row per 16 bytes).
        let (size, align) = crate::glsl::block_members::storage(m).std140();
        let (align, stride, total) = match m.array {
            // An array's elements (and a matrix's columns) are 16 bytes apart at least.
            Some(n) => {
                let stride = size.div_ceil(16) * 16;
                (16, stride, stride.checked_mul(n))
            }
            None => (align, 0, Some(size)),
        };
        offset = offset.div_ceil(align) * align;
        m.offset = offset;
        m.stride = stride;
        offset =
            total.and_then(|t| offset.checked_add(t)).filter(|&o| o <= MAX_UNIFORM_BLOCK_SIZE).ok_or_else(|| {
                format!("error: uniform block `{}' needs more than {MAX_UNIFORM_BLOCK_SIZE} bytes", block.name)
            })?;
    }
    block.size = offset.div_ceil(16) * 16;
    Ok(())
}

/// The generated declaration of `block` at `binding`.
pub(super) fn declaration(block: &Block, binding: u32) -> String {
    // An element of an array of blocks is declared under the name `block_arrays` gave it.
    let ident = match block.element {
        Some(k) => element_name(block.base_name(), k),
        None => block.name.clone(),
    };
    let mut out = format!("layout(std140, set = 0, binding = {binding}) uniform {ident} {{\n");
    for m in &block.members {
        let _ = writeln!(out, "    {}", crate::glsl::block_members::declaration(m));
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
