//! GLSL ES 1.00 uniforms of structure types: an array of structures read in the vertex stage,
//! structures holding samplers (an array of them, declared with the uniform), structures
//! nested in structures and an array of them passed whole to a function; drawn as colours, with
//! what the active-uniform queries report of each leaf (`m[1].tint`, `o.q[0].b`), where
//! `glGetUniformLocation` finds one (every name form, and names that are no uniform), the values
//! read back, and links whose stages declare a structure differently.

use super::multi_draw::mark_all;
use super::*;

const ACTIVE_UNIFORMS: u32 = 0x8B86;
const LINK_STATUS: u32 = 0x8B82;
const VERTEX_SHADER: u32 = 0x8B31;
const FRAGMENT_SHADER: u32 = 0x8B30;

const VS: &str = "attribute vec2 pos;
    struct Light { vec3 c; float w[2]; };
    uniform Light lights[2];
    varying vec2 uv;
    varying vec3 lit;
    void main() {
        uv = pos * 0.5 + 0.5;
        lit = lights[0].c * lights[0].w[1] + lights[1].c * lights[1].w[0];
        gl_Position = vec4(pos, 0.0, 1.0);
    }";

const FS: &str = "precision mediump float;
    uniform struct Material { sampler2D t; vec4 tint; bool on; } m[2];
    struct Pair { float a; vec2 b; };
    struct Outer { Pair p; Pair q[2]; };
    uniform Outer o;
    varying vec2 uv;
    varying vec3 lit;
    float sum(Pair p) { return p.a + p.b.y; }
    void main() {
        int band = int(uv.y * 6.0);
        if (band == 0) gl_FragColor = texture2D(m[0].t, uv) * m[0].tint;
        else if (band == 1) gl_FragColor = texture2D(m[1].t, uv) + (m[1].on ? m[1].tint : vec4(0.0));
        else if (band == 2) gl_FragColor = vec4(o.p.a, o.q[1].b, o.q[0].a);
        else if (band == 3) gl_FragColor = vec4(lit, sum(o.q[1]) * 0.5 + o.p.b.x);
        else gl_FragColor = vec4(0.0, 0.0, 0.0, 1.0);
    }";

/// A name as a number a mark can show (its bytes hashed into 16 bits).
pub(super) fn name_hash(name: &str) -> u32 {
    name.bytes().fold(7u32, |h, b| h.wrapping_mul(31).wrapping_add(u32::from(b))) & 0xFFFF
}

/// Marks, for each of `names`, what the active uniform of that name reports (its name, size
/// and type; 0xFFFF where none is), found among all `program`'s active uniforms, in any order.
pub(super) fn mark_active(gl: Gl<'_>, program: u32, names: &[&str], marks: &mut Vec<u32>) -> R {
    let count = gl.glGetProgramiv(program, ACTIVE_UNIFORMS)?;
    marks.push(count as u32);
    let mut listed = Vec::new();
    for i in 0..count.max(0) as u32 {
        if let Some(a) = gl.glGetActiveUniform(program, i)? {
            listed.push(a);
        }
    }
    for name in names {
        match listed.iter().find(|a| a.name == *name) {
            Some(a) => marks.extend([name_hash(&a.name), a.size as u32, a.ty]),
            None => marks.push(0xFFFF),
        }
    }
    Ok(())
}

/// Marks whether `glGetUniformLocation` finds each of `names`.
pub(super) fn mark_found(gl: Gl<'_>, program: u32, names: &[&str], marks: &mut Vec<u32>) -> R {
    for name in names {
        marks.push(u32::from(gl.glGetUniformLocation(program, Text::borrowed(name))? != -1));
    }
    Ok(())
}

/// The link status of `vs` with `fs`.
pub(super) fn link_status(gl: Gl<'_>, n: &mut Names, vs: &str, fs: &str) -> Result<u32, ClientError> {
    let (p, v, f) = (n.next(), n.next(), n.next());
    gl.glCreateProgram(p)?;
    for (s, ty, src) in [(v, VERTEX_SHADER, vs), (f, FRAGMENT_SHADER, fs)] {
        gl.glCreateShader(ty, s)?;
        gl.glShaderSource(s, Text::borrowed(src))?;
        gl.glCompileShader(s)?;
        gl.glAttachShader(p, s)?;
    }
    gl.glLinkProgram(p)?;
    Ok(gl.glGetProgramiv(p, LINK_STATUS)? as u32)
}

/// A 2×2 texture of `px` on unit `unit` (made on unit 0, which it is left bound to as well:
/// unit 0's comes last).
pub(super) fn unit_texture(gl: Gl<'_>, n: &mut Names, unit: u32, px: &[u8; 16]) -> R {
    let t = texture(gl, n, 2, 2, RGBA, UNSIGNED_BYTE, px, NEAREST, CLAMP_TO_EDGE)?;
    gl.glActiveTexture(TEXTURE0 + unit)?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glActiveTexture(TEXTURE0)
}

fn struct_uniforms(gl: Gl<'_>, n: &mut Names) -> R {
    unit_texture(gl, n, 1, &[10, 20, 30, 255, 60, 0, 120, 255, 0, 0, 0, 255, 30, 200, 90, 255])?;
    unit_texture(gl, n, 0, &[200, 40, 0, 255, 0, 180, 60, 255, 90, 90, 250, 255, 255, 255, 0, 255])?;
    let p = program(gl, n, VS, FS, &["pos"])?;
    buffer(gl, n, ARRAY_BUFFER, &f32s(&[-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0]))?;
    attrib(gl, 0, 2, FLOAT, false, 0, 0)?;
    let at = |gl: Gl<'_>, name: &str| gl.glGetUniformLocation(p, Text::borrowed(name));
    let l = at(gl, "lights[0].c")?;
    gl.glUniform3f(l, 0.2, 0.4, 0.6)?;
    let l = at(gl, "lights[0].w")?;
    gl.glUniform1fv(l, Slice::new(&[0.1, 0.9]))?;
    let l = at(gl, "lights[1].c")?;
    gl.glUniform3f(l, 0.5, 0.1, 0.3)?;
    let l = at(gl, "lights[1].w[0]")?;
    gl.glUniform1f(l, 0.6)?;
    let l = at(gl, "m[0].t")?;
    gl.glUniform1i(l, 1)?;
    let l = at(gl, "m[1].t")?;
    gl.glUniform1i(l, 0)?;
    let l = at(gl, "m[0].tint")?;
    gl.glUniform4f(l, 0.9, 0.5, 1.0, 1.0)?;
    let l = at(gl, "m[1].tint")?;
    gl.glUniform4f(l, 0.1, 0.3, 0.0, 0.5)?;
    let l = at(gl, "m[1].on")?;
    gl.glUniform1i(l, 1)?;
    let l = at(gl, "o.p.a")?;
    gl.glUniform1f(l, 0.7)?;
    let l = at(gl, "o.p.b")?;
    gl.glUniform2f(l, 0.25, 0.5)?;
    let l = at(gl, "o.q[0].a")?;
    gl.glUniform1f(l, 0.35)?;
    let l = at(gl, "o.q[1].b")?;
    gl.glUniform2f(l, 0.15, 0.45)?;
    let l = at(gl, "o.q[1].a")?;
    gl.glUniform1f(l, 0.2)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    let mut marks = Vec::new();
    let leaves = [
        "lights[0].c",
        "lights[0].w[0]",
        "lights[1].w[0]",
        "m[0].t",
        "m[1].tint",
        "m[1].on",
        "o.p.a",
        "o.p.b",
        "o.q[0].a",
        "o.q[1].b",
        "lights[0].w",
        "o.q[1]",
        "o",
    ];
    mark_active(gl, p, &leaves, &mut marks)?;
    let forms = ["lights[1].w", "lights[1].w[1]", "lights[1].w[2]", "lights[2].c", "lights.c", "m[1]", "o.q[1].b[0]"];
    mark_found(gl, p, &forms, &mut marks)?;
    let l = at(gl, "lights[0].w[1]")?;
    marks.extend(gl.glGetUniformfv(p, l)?.iter().map(|v| (v * 1000.0) as u32));
    let l = at(gl, "o.q[1].b")?;
    marks.extend(gl.glGetUniformfv(p, l)?.iter().map(|v| (v * 1000.0) as u32));
    let l = at(gl, "m[0].t")?;
    marks.extend(gl.glGetUniformiv(p, l)?.iter().map(|&v| v as u32));
    let l = at(gl, "m[1].on")?;
    marks.extend(gl.glGetUniformiv(p, l)?.iter().map(|&v| v as u32));
    // A structure's sampler takes only glUniform1i.
    let l = at(gl, "m[0].t")?;
    gl.glUniform1f(l, 1.0)?;
    marks.push(gl.glGetError()?);
    // Stages declaring a structure alike, with another member type, another member name.
    let vs = |s: &str| {
        format!("struct S {{ {s}; }}; uniform S s; attribute vec4 p; void main() {{ gl_Position = p * float(s.a); }}")
    };
    let fs = "precision highp float; struct S { float a; }; uniform S s; void main() { gl_FragColor = vec4(s.a); }";
    for member in ["float a", "int a", "float b"] {
        let vs = vs(member).replace("s.a", if member.ends_with('b') { "s.b" } else { "s.a" });
        marks.push(link_status(gl, n, &vs, fs)?);
    }
    mark_all(gl, &marks)
}

pub fn all() -> Vec<Case> {
    vec![Case { name: "struct_uniforms", run: struct_uniforms, tol: DEFAULT, expects_error: false }]
}
