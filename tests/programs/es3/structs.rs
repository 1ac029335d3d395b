//! GLSL ES 3.00 structures in uniforms and in uniform blocks. Uniforms: a structure holding an
//! array, a nested structure, a matrix and a sampler; an array of them; an array of another
//! indexed by a uniform and passed whole to a function. Blocks: structures (nested, in arrays,
//! holding matrices of every layout, booleans and arrays) laid out by std140, their leaves'
//! offsets, strides and matrix layouts as GL reports them, and values placed by those offsets.
//! Drawn as colours, with what the queries answer as marks.

use super::super::multi_draw::mark_all;
use super::super::struct_uniforms::{link_status, mark_active, mark_found, name_hash, unit_texture};
use super::super::*;

const UNIFORM_BUFFER: u32 = 0x8A11;
const UNIFORM_OFFSET: u32 = 0x8A3B;
const UNIFORM_ARRAY_STRIDE: u32 = 0x8A3C;
const UNIFORM_MATRIX_STRIDE: u32 = 0x8A3D;
const UNIFORM_IS_ROW_MAJOR: u32 = 0x8A3E;
const UNIFORM_BLOCK_INDEX: u32 = 0x8A3A;
const UNIFORM_TYPE: u32 = 0x8A37;
const UNIFORM_SIZE: u32 = 0x8A38;
const UNIFORM_BLOCK_DATA_SIZE: u32 = 0x8A40;

const FS: &str = "#version 300 es
    precision highp float;
    struct Inner { float x; vec2 y[2]; bool b; };
    struct S { vec4 a; float arr[3]; Inner inner; sampler2D tex; mat3 m; };
    struct P { vec3 c; float w[2]; };
    uniform S u;
    uniform S v[2];
    uniform P q[2];
    uniform int k;
    in vec2 uv;
    out vec4 frag;
    float sum(P p) { return p.c.x + p.w[0]; }
    void main() {
        int band = int(uv.y * 12.0);
        if (band == 0) frag = u.a;
        else if (band == 1) frag = vec4(u.arr[0], u.arr[1], u.arr[2], 1.0);
        else if (band == 2) frag = vec4(u.inner.x, u.inner.y[1], u.inner.b ? 1.0 : 0.0);
        else if (band == 3) frag = texture(u.tex, uv);
        else if (band == 4) frag = texture(v[1].tex, uv) * texture(v[0].tex, uv.yx) + v[0].a * 0.2;
        else if (band == 5) frag = vec4(u.m * vec3(uv, 1.0), 1.0) * 0.3 + vec4(v[1].m[2], 0.0) * 0.5;
        else if (band == 6) frag = vec4(q[k].c, q[k].w[1]);
        else if (band == 7) frag = vec4(sum(q[0]), v[1].inner.y[0].y, float(v[0].inner.b), 1.0)
            + vec4(v[0].arr[2], v[1].arr[0], v[0].inner.x + v[1].inner.x + v[0].inner.y[1].x, 0.0) * 0.2
            + vec4(v[1].a.x + v[0].m[0][0] + v[1].inner.y[1].y + v[0].inner.y[0].x + v[1].arr[1], v[0].arr[1] + v[1].arr[2] + v[0].arr[0], 0.0, 0.0) * 0.1
            + vec4(float(v[1].inner.b), q[1].c.y, 0.0, 0.0) * 0.05;
        else frag = vec4(0.0, 0.0, 0.0, 1.0);
    }";

/// Values in [0, 1), distinct per `seed`.
fn vals(n: usize, seed: f32) -> Vec<f32> {
    (0..n).map(|k| (k as f32 * 0.29 + seed) % 1.0).collect()
}

/// Structure uniforms set by every name form, drawn; what the queries answer of their leaves.
pub fn struct_uniforms(gl: Gl<'_>, n: &mut Names) -> R {
    unit_texture(gl, n, 2, &[10, 20, 30, 255, 60, 0, 120, 255, 0, 0, 0, 255, 30, 200, 90, 255])?;
    unit_texture(gl, n, 0, &[200, 40, 0, 255, 0, 180, 60, 255, 90, 90, 250, 255, 255, 255, 0, 255])?;
    let p = super::language::screen(gl, n, super::language::VS_SCREEN, FS)?;
    let at = |gl: Gl<'_>, name: &str| gl.glGetUniformLocation(p, Text::borrowed(name));
    for (s, seed) in [("u", 0.1), ("v[0]", 0.4), ("v[1]", 0.7)] {
        let l = at(gl, &format!("{s}.a"))?;
        gl.glUniform4fv(l, Slice::new(&vals(4, seed)))?;
        let l = at(gl, &format!("{s}.arr"))?;
        gl.glUniform1fv(l, Slice::new(&vals(3, seed + 0.05)))?;
        let l = at(gl, &format!("{s}.inner.x"))?;
        gl.glUniform1f(l, seed + 0.1)?;
        let l = at(gl, &format!("{s}.inner.y[0]"))?;
        gl.glUniform2fv(l, Slice::new(&vals(4, seed + 0.15)))?;
        let l = at(gl, &format!("{s}.inner.b"))?;
        gl.glUniform1i(l, i32::from(seed > 0.3))?;
        let l = at(gl, &format!("{s}.m"))?;
        gl.glUniformMatrix3fv(l, false, Slice::new(&vals(9, seed + 0.2)))?;
    }
    // `u.arr[1]` alone, after the whole array.
    let l = at(gl, "u.arr[1]")?;
    gl.glUniform1f(l, 0.9)?;
    let l = at(gl, "u.tex")?;
    gl.glUniform1i(l, 2)?;
    let l = at(gl, "v[0].tex")?;
    gl.glUniform1i(l, 0)?;
    let l = at(gl, "v[1].tex")?;
    gl.glUniform1i(l, 2)?;
    for (s, seed) in [("q[0]", 0.3), ("q[1]", 0.6)] {
        let l = at(gl, &format!("{s}.c"))?;
        gl.glUniform3fv(l, Slice::new(&vals(3, seed)))?;
        let l = at(gl, &format!("{s}.w"))?;
        gl.glUniform1fv(l, Slice::new(&vals(2, seed + 0.1)))?;
    }
    let l = at(gl, "k")?;
    gl.glUniform1i(l, 1)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    let mut marks = Vec::new();
    let leaves =
        ["u.a", "u.arr[0]", "u.inner.y[0]", "u.inner.b", "u.tex", "u.m", "v[1].inner.x", "v[0].tex", "q[1].w[0]"];
    mark_active(gl, p, &leaves, &mut marks)?;
    let forms = ["u.arr", "u.arr[2]", "u.arr[3]", "u.inner", "u", "v[1].a", "v.a", "v[2].a", "q[1].w[1]", "u.inner.y"];
    mark_found(gl, p, &forms, &mut marks)?;
    // glGetUniformIndices on the name forms, and what the index found is named.
    let list = forms.join("\n") + "\n";
    for i in gl.glGetUniformIndices(p, forms.len() as i32, Text::borrowed(&list))? {
        let name = if i == u32::MAX { None } else { gl.glGetActiveUniform(p, i)? };
        marks.push(name.map_or(0xFFFF, |a| name_hash(&a.name)));
    }
    let l = at(gl, "u.arr[1]")?;
    marks.extend(gl.glGetUniformfv(p, l)?.iter().map(|v| (v * 1000.0) as u32));
    let l = at(gl, "v[1].inner.y[1]")?;
    marks.extend(gl.glGetUniformfv(p, l)?.iter().map(|v| (v * 1000.0) as u32));
    let l = at(gl, "v[1].tex")?;
    marks.extend(gl.glGetUniformiv(p, l)?.iter().map(|&v| v as u32));
    let l = at(gl, "v[0].inner.b")?;
    marks.extend(gl.glGetUniformiv(p, l)?.iter().map(|&v| v as u32));
    // Stages declaring a structure alike, with another member type, another member name, a
    // structure of another name.
    let vs = |s: &str| {
        format!("#version 300 es\n{s}\nuniform S s; in vec4 p; void main() {{ gl_Position = p * float(s.a); }}")
    };
    let fs = "#version 300 es\nprecision highp float; struct S { float a; }; uniform S s; out vec4 o; void main() { o = vec4(s.a); }";
    for decl in [
        "struct S { float a; };",
        "struct S { int a; };",
        "struct S { float a; float b; };",
        "struct T { float a; };\n#define S T",
    ] {
        marks.push(link_status(gl, n, &vs(decl), fs)?);
    }
    mark_all(gl, &marks)
}

const BLOCK_FS: &str = "#version 300 es
    precision highp float;
    struct Pair { float x; vec3 y; };
    struct S { mat2 m2; ivec2 i[2]; Pair p; bool b; mat3x2 r; };
    struct T { float t; S s[2]; vec4 after; };
    struct Q { vec2 a; float b[2]; };
    layout(std140) uniform Plain { float head; S s; float tail; } plain;
    layout(std140, row_major) uniform Rows { T t; layout(column_major) S c; mat2x3 last; Q qs[2]; };
    uniform int k;
    in vec2 uv;
    out vec4 frag;
    void main() {
        int band = int(uv.y * 16.0);
        if (band == 0) frag = vec4(plain.head, plain.s.m2[1], plain.tail);
        else if (band == 1) frag = vec4(vec2(plain.s.i[1]) * 0.1, plain.s.p.x, plain.s.b ? 1.0 : 0.0);
        else if (band == 2) frag = vec4(plain.s.p.y, plain.s.r[2].y);
        else if (band == 3) frag = vec4(plain.s.r[0], plain.s.r[1]);
        else if (band == 4) frag = vec4(t.t, t.s[1].m2[0], t.after.w);
        else if (band == 5) frag = vec4(t.s[0].r[1], t.s[1].r[2].x, float(t.s[0].b));
        else if (band == 6) frag = vec4(t.s[1].p.y, vec2(t.s[0].i[0]).y * 0.1);
        else if (band == 7) frag = vec4(c.r[2], c.m2[1]);
        else if (band == 8) frag = vec4(last[1], qs[k].b[1] + qs[0].a.y);
        else frag = vec4(0.0, 0.0, 0.0, 1.0);
    }";

/// The shape of a GL type: (vectors, components per vector) for a column-major matrix, else
/// (1, components); and whether its words are integers (1) or booleans (2).
fn shape(ty: u32) -> (usize, usize, u8) {
    match ty {
        0x8B5A => (2, 2, 0),
        0x8B5B => (3, 3, 0),
        0x8B5C => (4, 4, 0),
        0x8B65 => (2, 3, 0),
        0x8B66 => (2, 4, 0),
        0x8B67 => (3, 2, 0),
        0x8B68 => (3, 4, 0),
        0x8B69 => (4, 2, 0),
        0x8B6A => (4, 3, 0),
        0x8B50..=0x8B52 => (1, (ty - 0x8B4E) as usize, 0),
        0x8B53..=0x8B55 => (1, (ty - 0x8B51) as usize, 1),
        0x8B57..=0x8B59 => (1, (ty - 0x8B55) as usize, 2),
        0x8B56 => (1, 1, 2),
        0x1404 | 0x1405 => (1, 1, 1),
        _ => (1, 1, 0),
    }
}

/// Block structures filled by the offsets GL reports; what it reports of their leaves.
pub fn block_structs(gl: Gl<'_>, n: &mut Names) -> R {
    let p = super::language::screen(gl, n, super::language::VS_SCREEN, BLOCK_FS)?;
    let k = gl.glGetUniformLocation(p, Text::borrowed("k"))?;
    gl.glUniform1i(k, 1)?;
    let mut marks = Vec::new();
    let leaves = [
        "Plain.head",
        "Plain.s.m2",
        "Plain.s.i[0]",
        "Plain.s.p.x",
        "Plain.s.p.y",
        "Plain.s.b",
        "Plain.s.r",
        "Plain.tail",
        "t.t",
        "t.s[0].m2",
        "t.s[0].i[0]",
        "t.s[0].p.y",
        "t.s[0].b",
        "t.s[0].r",
        "t.s[1].m2",
        "t.s[1].i[0]",
        "t.s[1].p.x",
        "t.s[1].p.y",
        "t.s[1].r",
        "t.after",
        "c.m2",
        "c.r",
        "c.i[0]",
        "last",
        "t.s[1].b",
        "c.p.x",
        "t.s",
        "Plain.s",
        "qs[0].a",
        "qs[1].b[0]",
        "qs[0].b",
        "qs[1].a",
    ];
    let blocks =
        [gl.glGetUniformBlockIndex(p, Text::borrowed("Plain"))?, gl.glGetUniformBlockIndex(p, Text::borrowed("Rows"))?];
    let list = leaves.join("\n") + "\n";
    let indices = gl.glGetUniformIndices(p, leaves.len() as i32, Text::borrowed(&list))?;
    // Each block's words: each leaf's from its name's hash, a step per word; an integer leaf's
    // small integers, a boolean's alternately true and false.
    let mut words: [Vec<[u8; 4]>; 2] = [vec![[0; 4]; 256], vec![[0; 4]; 256]];
    for (&i, name) in indices.iter().zip(leaves) {
        if i == u32::MAX {
            marks.push(0xFFFF);
            continue;
        }
        let mut q = |pname| -> Result<i32, ClientError> {
            Ok(gl.glGetActiveUniformsiv(p, Slice::new(&[i]), pname)?.first().copied().unwrap_or(-1))
        };
        let (offset, stride, matrix, row) =
            (q(UNIFORM_OFFSET)?, q(UNIFORM_ARRAY_STRIDE)?, q(UNIFORM_MATRIX_STRIDE)?, q(UNIFORM_IS_ROW_MAJOR)?);
        let (ty, size, block) = (q(UNIFORM_TYPE)? as u32, q(UNIFORM_SIZE)?, q(UNIFORM_BLOCK_INDEX)?);
        let which = blocks.iter().position(|&b| b as i32 == block);
        // Three marks: the offset; the array and matrix strides; the type, size, layout and
        // block.
        marks.extend([offset as u32, (stride as u32 & 0xFF) | (matrix as u32) << 8]);
        let block_bit = which.map_or(3, |w| w as u32);
        marks.push((ty & 0xFFF) | (row as u32 & 1) << 12 | block_bit << 13 | (size as u32 & 1) << 15);
        let Some(words) = which.map(|w| &mut words[w]) else { continue };
        let (vectors, comps, kind) = shape(ty);
        // A row-major matrix's vectors are its rows.
        let (vectors, comps) = if row == 1 { (comps, vectors) } else { (vectors, comps) };
        let base = name_hash(name) as f32 / 65536.0;
        for e in 0..size.max(1) as usize {
            for v in 0..vectors {
                for c in 0..comps {
                    let j = (e * vectors + v) * comps + c;
                    let byte = offset.max(0) as usize + e * stride.max(0) as usize + v * matrix.max(0) as usize + c * 4;
                    if let Some(slot) = words.get_mut(byte / 4) {
                        *slot = match kind {
                            1 => (j as i32 + 1).to_ne_bytes(),
                            2 => i32::from(j % 2 == 0).to_ne_bytes(),
                            _ => ((base + j as f32 * 0.07) % 1.0).to_ne_bytes(),
                        };
                    }
                }
            }
        }
    }
    for (w, (&b, binding)) in blocks.iter().zip([1, 4]).enumerate() {
        let size = gl.glGetActiveUniformBlockiv(p, b, UNIFORM_BLOCK_DATA_SIZE)?.first().copied().unwrap_or(0);
        marks.push(size as u32);
        let bytes: Vec<u8> = words[w].iter().take(size.max(0) as usize / 4).flatten().copied().collect();
        gl.glUniformBlockBinding(p, b, binding)?;
        let buf = buffer(gl, n, UNIFORM_BUFFER, &bytes)?;
        gl.glBindBufferBase(UNIFORM_BUFFER, binding, buf)?;
    }
    gl.glBindBuffer(ARRAY_BUFFER, 0)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    mark_all(gl, &marks)
}
