//! ES 3.0's uniform blocks: a named block and an anonymous one across both stages, read from
//! ranges of one buffer and the whole of another through `glBindBufferRange`/`Base` and
//! `glUniformBlockBinding`, updated between draws by `glBufferSubData`; and what the block
//! queries answer (indices, std140 sizes, bindings, name lengths, member counts, the stages
//! that declare each, the indexed bindings' state) and the errors, as colours.

use super::super::multi_draw::mark_all;
use super::super::*;

const UNIFORM_BUFFER: u32 = 0x8A11;
const UNIFORM_BUFFER_OFFSET_ALIGNMENT: u32 = 0x8A34;
const UNIFORM_BUFFER_BINDING: u32 = 0x8A28;
const UNIFORM_BUFFER_START: u32 = 0x8A29;
const UNIFORM_BUFFER_SIZE: u32 = 0x8A2A;
const MAX_UNIFORM_BUFFER_BINDINGS: u32 = 0x8A2F;
const BLOCK_PNAMES: [u32; 6] = [0x8A3F, 0x8A40, 0x8A41, 0x8A42, 0x8A44, 0x8A46];
const DYNAMIC_DRAW: u32 = 0x88E8;
const ACTIVE_UNIFORM_BLOCKS: u32 = 0x8A36;
const VERTEX_SHADER: u32 = 0x8B31;

const VS: &str = "#version 300 es
    layout(location = 0) in vec2 pos;
    layout(std140) uniform Placement { vec4 scale_offset; float lift[3]; } place;
    uniform Common { vec4 tint; ivec2 mode; mat3 mix3; };
    out vec3 c;
    void main() {
        c = mix3 * vec3(pos * 0.5 + 0.5, 1.0) * 0.3;
        vec2 p = pos * place.scale_offset.xy + place.scale_offset.zw;
        gl_Position = vec4(p.x, p.y + place.lift[mode.x], 0.0, 1.0);
    }";
const FS: &str = "#version 300 es
    precision highp float;
    precision highp int;
    uniform Common { vec4 tint; ivec2 mode; mat3 mix3; };
    in vec3 c;
    out vec4 frag;
    void main() { frag = vec4(c + tint.rgb * float(mode.y), 1.0); }";

/// Floats and ints as the bytes a block holds.
fn words(v: &[f32]) -> Vec<u8> {
    f32s(v)
}

/// The `Placement` block's bytes: scale and offset, then `lift` at a 16-byte stride.
fn placement(scale: f32, x: f32, y: f32, lifts: [f32; 3]) -> Vec<u8> {
    let mut v = vec![scale, scale, x, y];
    for l in lifts {
        v.extend([l, 0.0, 0.0, 0.0]);
    }
    words(&v)
}

/// The `Common` block's bytes: tint, mode (two ints), then the mat3 as three padded columns.
fn common(tint: [f32; 4], mode: [i32; 2], m: [[f32; 3]; 3]) -> Vec<u8> {
    let mut b = words(&tint);
    b.extend(mode.iter().flat_map(|i| i.to_ne_bytes()));
    b.extend([0u8; 8]);
    for col in m {
        b.extend(words(&[col[0], col[1], col[2], 0.0]));
    }
    b
}

/// Two blocks from two buffers, drawn three times with updates between; then the queries.
pub fn uniform_blocks(gl: Gl<'_>, n: &mut Names) -> R {
    let p = super::language::screen(gl, n, VS, FS)?;
    let mut marks = Vec::new();
    let place = gl.glGetUniformBlockIndex(p, Text::borrowed("Placement"))?;
    let common_index = gl.glGetUniformBlockIndex(p, Text::borrowed("Common"))?;
    marks.extend([place, common_index, gl.glGetUniformBlockIndex(p, Text::borrowed("place"))?]);
    gl.glUniformBlockBinding(p, place, 2)?;
    gl.glUniformBlockBinding(p, common_index, 5)?;
    // Placement from a range 256 bytes in (a multiple of any alignment the two allow).
    let align = gl.glGetIntegerv(UNIFORM_BUFFER_OFFSET_ALIGNMENT)?.first().copied().unwrap_or(0);
    marks.push(u32::from(align > 0 && 256 % align == 0));
    let mut bytes = vec![0u8; 256];
    bytes.extend(placement(0.3, -0.6, -0.5, [0.0, 0.4, 0.8]));
    let a = buffer(gl, n, UNIFORM_BUFFER, &bytes)?;
    gl.glBindBufferRange(UNIFORM_BUFFER, 2, a, 256, 64)?;
    let m = [[1.0, 0.2, 0.0], [0.0, 1.0, 0.3], [0.5, 0.0, 1.0]];
    let b = n.next();
    gl.glGenBuffers(Slice::new(&[b]))?;
    gl.glBindBufferBase(UNIFORM_BUFFER, 5, b)?;
    let first = common([0.5, 0.1, 0.0, 1.0], [0, 1], m);
    gl.glBufferData(UNIFORM_BUFFER, first.len() as i64, Some(Blob::borrowed(&first)), DYNAMIC_DRAW)?;
    gl.glBindBuffer(ARRAY_BUFFER, 0)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    // The lift index and the tint change between draws; then the placement moves.
    let second = common([0.0, 0.3, 0.6, 1.0], [1, 1], m);
    gl.glBufferSubData(UNIFORM_BUFFER, 0, Blob::borrowed(&second))?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    gl.glBindBuffer(UNIFORM_BUFFER, a)?;
    gl.glBufferSubData(UNIFORM_BUFFER, 256, Blob::borrowed(&placement(0.25, 0.5, -0.6, [0.0, 0.0, 0.9])))?;
    gl.glBindBuffer(UNIFORM_BUFFER, b)?;
    gl.glBufferSubData(
        UNIFORM_BUFFER,
        16,
        Blob::borrowed(&[2i32, 2].iter().flat_map(|i| i.to_ne_bytes()).collect::<Vec<_>>()),
    )?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    // What the queries answer.
    for index in [place, common_index] {
        for pname in BLOCK_PNAMES {
            marks.extend(gl.glGetActiveUniformBlockiv(p, index, pname)?.iter().map(|&v| v as u32));
        }
        let name = gl.glGetActiveUniformBlockName(p, index)?.unwrap_or_default();
        marks.push(name.len() as u32);
    }
    for pname in [UNIFORM_BUFFER_BINDING, UNIFORM_BUFFER_START, UNIFORM_BUFFER_SIZE] {
        marks.extend(gl.glGetIntegeri_v(pname, 2)?.iter().map(|&v| v as u32));
        marks.extend(gl.glGetInteger64i_v(pname, 5)?.iter().map(|&v| v as u32));
    }
    marks.extend(gl.glGetIntegerv(UNIFORM_BUFFER_BINDING)?.iter().map(|&v| (v as u32 == b) as u32));
    let max = gl.glGetIntegerv(MAX_UNIFORM_BUFFER_BINDINGS)?.first().copied().unwrap_or(0) as u32;
    marks.push(u32::from(max >= 24));
    // The errors: a binding past the last, a misaligned offset, a size of 0, a block index
    // past the last, a binding past the last for a block, another target.
    gl.glBindBufferBase(UNIFORM_BUFFER, max, a)?;
    marks.push(gl.glGetError()?);
    gl.glBindBufferRange(UNIFORM_BUFFER, 1, a, 3, 16)?;
    marks.push(gl.glGetError()?);
    gl.glBindBufferRange(UNIFORM_BUFFER, 1, a, 0, 0)?;
    marks.push(gl.glGetError()?);
    gl.glUniformBlockBinding(p, 2, 0)?;
    marks.push(gl.glGetError()?);
    gl.glUniformBlockBinding(p, 0, max)?;
    marks.push(gl.glGetError()?);
    gl.glBindBufferBase(ARRAY_BUFFER, 0, a)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}

const VS_ARRAY: &str = "#version 300 es
    layout(location = 0) in vec2 pos;
    const int LAST = 2;
    uniform Light { vec4 color; vec2 shift; } lights[LAST + 1];
    out vec4 c;
    void main() {
        c = lights[0].color * 0.5 + lights[LAST].color * 0.5;
        gl_Position = vec4(pos * 0.4 + lights[1].shift, 0.0, 1.0);
    }";
const FS_ARRAY: &str = "#version 300 es
    precision mediump float;
    uniform Light { vec4 color; vec2 shift; } lights[3];
    in vec4 c; out vec4 o;
    void main() { o = c + lights[1].color; }";

/// An array of three uniform blocks, each element bound to its own binding: drawn twice,
/// re-bound between; what `glGetUniformBlockIndex` finds (`Light[k]`, `Light` for the first,
/// not past the end or by the instance name), each element's name, size, binding and the
/// stages that index it; and indexing that is not constant, or out of bounds, failing to
/// compile.
pub fn uniform_block_arrays(gl: Gl<'_>, n: &mut Names) -> R {
    let p = super::language::screen(gl, n, VS_ARRAY, FS_ARRAY)?;
    let mut marks = Vec::new();
    let mut index = Vec::new();
    for name in ["Light[0]", "Light[1]", "Light[2]", "Light", "Light[3]", "lights[0]"] {
        index.push(gl.glGetUniformBlockIndex(p, Text::borrowed(name))?);
    }
    marks.extend(index.iter().map(|&i| u32::from(i != u32::MAX)));
    // Elements 0, 1 and 2 at bindings 4, 1 and 7, from three ranges of one buffer 256 apart.
    let element = |color: [f32; 4], shift: [f32; 2]| words(&[&color[..], &shift[..], &[0.0, 0.0]].concat());
    let mut bytes = Vec::new();
    for (color, shift) in
        [([0.8, 0.0, 0.0, 1.0], [-0.5, -0.4]), ([0.0, 0.3, 0.0, 0.0], [0.45, 0.5]), ([0.0, 0.0, 0.6, 1.0], [0.0, 0.0])]
    {
        bytes.extend(element(color, shift));
        bytes.resize(bytes.len().next_multiple_of(256), 0);
    }
    let b = buffer(gl, n, UNIFORM_BUFFER, &bytes)?;
    for (k, binding) in [4u32, 1, 7].into_iter().enumerate() {
        gl.glUniformBlockBinding(p, index[k], binding)?;
        gl.glBindBufferRange(UNIFORM_BUFFER, binding, b, 256 * k as i64, 32)?;
    }
    gl.glBindBuffer(ARRAY_BUFFER, 0)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    // Elements 0 and 2 swap bindings: the colours swap, the position stays.
    gl.glUniformBlockBinding(p, index[0], 7)?;
    gl.glUniformBlockBinding(p, index[2], 4)?;
    gl.glBindBufferRange(UNIFORM_BUFFER, 1, b, 0, 32)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    marks.push(gl.glGetProgramiv(p, ACTIVE_UNIFORM_BLOCKS)? as u32);
    for &i in &index[..3] {
        for pname in BLOCK_PNAMES {
            marks.extend(gl.glGetActiveUniformBlockiv(p, i, pname)?.iter().map(|&v| v as u32));
        }
        let name = gl.glGetActiveUniformBlockName(p, i)?.unwrap_or_default();
        marks.push(u32::from(index.iter().position(|&j| j == i).is_some_and(|k| name == format!("Light[{k}]"))));
    }
    // Indexing by a uniform, and past the end.
    let by_uniform = "#version 300 es
        uniform int k; uniform Light { vec4 color; vec2 shift; } lights[3];
        void main() { gl_Position = lights[k].color; }";
    let past = "#version 300 es
        uniform Light { vec4 color; vec2 shift; } lights[3];
        void main() { gl_Position = lights[3].color; }";
    for vs in [by_uniform, past] {
        marks.push(super::super::draw_buffers::compiles(gl, n, VERTEX_SHADER, vs)?);
    }
    mark_all(gl, &marks)
}

/// Members std140 lays out as naga would not: booleans, two-row and row-major matrices, arrays
/// of them, the default layout changed by `layout(row_major) uniform;` and a member's own.
const BLOCK_TYPES_FS: &str = "#version 300 es
    precision highp float;
    layout(std140, row_major) uniform Mixed {
        bool flag;
        bvec3 flags;
        layout(column_major) mat3x2 a;
        mat2x3 b;
        mat4x3 c;
        mat2 d[2];
        bool e[3];
        mat3 f;
    } mixed;
    layout(row_major) uniform;
    uniform Plain { mat3x2 p; bvec2 q; };
    out vec4 o;
    void main() {
        int k = int(gl_FragCoord.x) / 7;
        if (k == 0) o = vec4(float(mixed.flag), float(mixed.flags.y), float(mixed.flags.z), 1.0);
        else if (k == 1) o = vec4(mixed.a[1], mixed.a[2].x, 1.0);
        else if (k == 2) o = vec4(mixed.b[1], 1.0);
        else if (k == 3) o = vec4(mixed.c[3], 1.0);
        else if (k == 4) o = vec4(mixed.d[1][0], mixed.d[0][1]);
        else if (k == 5) o = vec4(float(mixed.e[0]), float(mixed.e[1]), float(mixed.e[2]), 1.0);
        else if (k == 6) o = vec4(p[2], float(q.x), float(q.y));
        else if (k == 7) o = vec4(mixed.f[0].yz, mixed.f[2].x, 1.0);
        else o = vec4((mixed.c * vec4(0.25)) * 0.5 + (vec3(0.3) * mixed.b).xyx * 0.5, 1.0);
    }";

/// Words of a block: fractions in [0, 1], every fifth word zero (a false boolean).
fn block_words(n: usize) -> Vec<u8> {
    let w: Vec<f32> = (0..n).map(|i| if i % 5 == 3 { 0.0 } else { (i * 7 % 23) as f32 / 23.0 }).collect();
    words(&w)
}

/// Each kind of member read in a strip of its own, from buffers of known words; the layouts
/// are the specification's, so Mesa's image is the same only where the offsets are.
pub fn uniform_block_types(gl: Gl<'_>, n: &mut Names) -> R {
    let p = super::language::screen(gl, n, super::language::VS_SCREEN, BLOCK_TYPES_FS)?;
    let mixed = gl.glGetUniformBlockIndex(p, Text::borrowed("Mixed"))?;
    let plain = gl.glGetUniformBlockIndex(p, Text::borrowed("Plain"))?;
    gl.glUniformBlockBinding(p, mixed, 3)?;
    gl.glUniformBlockBinding(p, plain, 6)?;
    let a = buffer(gl, n, UNIFORM_BUFFER, &block_words(84))?;
    gl.glBindBufferBase(UNIFORM_BUFFER, 3, a)?;
    let b = buffer(gl, n, UNIFORM_BUFFER, &block_words(12))?;
    gl.glBindBufferBase(UNIFORM_BUFFER, 6, b)?;
    gl.glBindBuffer(ARRAY_BUFFER, 0)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    let mut marks = Vec::new();
    for index in [mixed, plain] {
        marks.extend(gl.glGetActiveUniformBlockiv(p, index, 0x8A40)?.iter().map(|&v| v as u32));
    }
    mark_all(gl, &marks)
}
