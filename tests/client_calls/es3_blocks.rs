//! ES 3.0's active uniforms with uniform blocks, in an ES 3.0 context: the default block's
//! uniforms and two std140 blocks' members (one block with an instance name, one without; an
//! array, a matrix) listed by `glGetActiveUniform`, found by `glGetUniformIndices`, described by
//! `glGetActiveUniformsiv` and listed per block; and the errors. Indices are each
//! implementation's own, so uniforms are compared by name.

use std::ffi::CString;

use super::*;

const ACTIVE_UNIFORMS: u32 = 0x8B86;
const ACTIVE_UNIFORM_MAX_LENGTH: u32 = 0x8B87;
const UNIFORM_BLOCK_ACTIVE_UNIFORMS: u32 = 0x8A42;
const UNIFORM_BLOCK_ACTIVE_UNIFORM_INDICES: u32 = 0x8A43;
/// `glGetActiveUniformsiv`'s names, `GL_UNIFORM_TYPE` … `GL_UNIFORM_IS_ROW_MAJOR`.
const PROPERTIES: std::ops::RangeInclusive<u32> = 0x8A37..=0x8A3E;

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    uniform vec4 tint;
    uniform float weights[3];
    layout(std140) uniform Camera { mat4 view; vec2 jitter; float scale[2]; } camera;
    layout(std140) uniform Light { vec3 direction; int count; };
    out vec4 c;
    void main() {
        c = tint * weights[2] * camera.scale[1] + vec4(direction, float(count)) + vec4(camera.jitter, 0.0, 0.0);
        gl_Position = camera.view * pos;
    }";
const FS: &str = "#version 300 es
    precision mediump float; in vec4 c; out vec4 o; void main() { o = c; }";
/// Members laid out otherwise than naga would: booleans, two-row and row-major matrices.
const VS_TYPES: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    layout(std140, row_major) uniform Mixed {
        bool flag; bvec3 flags; layout(column_major) mat3x2 a; mat2x3 b; mat4x3 c; mat2 d[2]; bool e[3]; mat3 f;
    } mixed;
    out vec4 c;
    void main() {
        c = vec4(float(mixed.flag) + float(mixed.flags.x) + float(mixed.e[2]), mixed.a[1], 1.0)
            + vec4(mixed.b[1] + mixed.c[3] + mixed.f[2], mixed.d[1][0].x);
        gl_Position = pos;
    }";
/// An array of blocks, its elements indexed in one stage or the other.
const VS_ARRAY: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    uniform Light { vec4 color; float k[2]; } lights[3];
    out vec4 c;
    void main() { c = lights[0].color * lights[2].k[1]; gl_Position = pos; }";
const FS_ARRAY: &str = "#version 300 es
    precision mediump float;
    uniform Light { vec4 color; float k[2]; } lights[3];
    in vec4 c; out vec4 o;
    void main() { o = c + lights[1].color; }";

/// The name of active uniform `i` of `p`, with its type and size.
fn active(r: &Run, p: u32, i: u32) -> String {
    let (mut len, mut size, mut ty, mut name) = (0, 0, 0u32, [0i8; 64]);
    // SAFETY: a context is current; the out-pointers have room.
    unsafe {
        (r.gl.get_active_uniform)(p, i, 64, &mut len, &mut size, &mut ty, name.as_mut_ptr());
        let n = std::ffi::CStr::from_ptr(name.as_ptr()).to_string_lossy().into_owned();
        format!("{n} {ty:#x} {size}")
    }
}

/// The active uniforms sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    let p = r.program(VS, FS);
    // SAFETY: GL calls with a current context; every pointer holds what the call reads or writes.
    unsafe {
        let mut n = -1;
        (gl.get_programiv)(p, ACTIVE_UNIFORMS, &mut n);
        let mut max = -1;
        (gl.get_programiv)(p, ACTIVE_UNIFORM_MAX_LENGTH, &mut max);
        r.note(&format!("active uniforms {n}, longest name {max}"));
        let mut listed: Vec<String> = (0..n.max(0) as u32).map(|i| active(r, p, i)).collect();
        listed.sort();
        r.note(&format!("listed: {listed:?}"));
        let names = [
            "tint",
            "weights",
            "weights[0]",
            "Camera.view",
            "Camera.jitter",
            "Camera.scale[0]",
            "direction",
            "count",
            "camera.view",
            "nothing",
        ];
        let owned: Vec<CString> = names.iter().map(|s| CString::new(*s).expect("name")).collect();
        let ptrs: Vec<*const i8> = owned.iter().map(|c| c.as_ptr()).collect();
        let mut indices = vec![0xDEAD_u32; names.len()];
        (gl.get_uniform_indices)(p, names.len() as i32, ptrs.as_ptr(), indices.as_mut_ptr());
        r.note("glGetUniformIndices");
        let found: Vec<(usize, u32)> = indices.iter().copied().enumerate().filter(|&(_, i)| i != u32::MAX).collect();
        r.note(&format!(
            "names not found: {:?}",
            names.iter().zip(&indices).filter(|(_, &i)| i == u32::MAX).map(|(n, _)| *n).collect::<Vec<_>>()
        ));
        let list: Vec<u32> = found.iter().map(|f| f.1).collect();
        for pname in PROPERTIES {
            let mut v = vec![-7i32; list.len()];
            (gl.get_active_uniformsiv)(p, list.len() as i32, list.as_ptr(), pname, v.as_mut_ptr());
            let by_name: Vec<String> = found.iter().zip(&v).map(|((k, _), x)| format!("{}={x}", names[*k])).collect();
            r.note(&format!("property {pname:#x}: {by_name:?}"));
        }
        for block in 0..2u32 {
            let mut count = -1;
            (gl.get_active_uniform_blockiv)(p, block, UNIFORM_BLOCK_ACTIVE_UNIFORMS, &mut count);
            let mut members = vec![-7i32; count.max(0) as usize];
            (gl.get_active_uniform_blockiv)(p, block, UNIFORM_BLOCK_ACTIVE_UNIFORM_INDICES, members.as_mut_ptr());
            let mut named: Vec<String> = members.iter().map(|&i| active(r, p, i as u32)).collect();
            named.sort();
            r.note(&format!("block {block}: {count} members {named:?}"));
        }
        // The errors.
        let bad = [list[0], 1000];
        let mut v = [-7i32; 2];
        (gl.get_active_uniformsiv)(p, 2, bad.as_ptr(), 0x8A37, v.as_mut_ptr());
        r.note(&format!("an index past the last: {v:?}"));
        (gl.get_active_uniformsiv)(p, 1, bad.as_ptr(), 0x1234, v.as_mut_ptr());
        r.note("a name no property has");
        (gl.get_active_uniformsiv)(p, -1, bad.as_ptr(), 0x8A37, v.as_mut_ptr());
        r.note("a count of -1");
        (gl.get_uniform_indices)(0xBEEF, 1, ptrs.as_ptr(), indices.as_mut_ptr());
        r.note("glGetUniformIndices of no program");
        let mut v1 = -7;
        (gl.get_active_uniformsiv)(0xBEEF, 1, bad.as_ptr(), 0x8A37, &mut v1);
        r.note("glGetActiveUniformsiv of no program");

        // Booleans and matrices: each member's type, size, offset, strides and layout.
        let t = r.program(VS_TYPES, FS);
        (gl.get_programiv)(t, ACTIVE_UNIFORMS, &mut n);
        let all: Vec<u32> = (0..n.max(0) as u32).collect();
        let mut described = Vec::new();
        for &i in &all {
            let mut props = Vec::new();
            for pname in PROPERTIES {
                let mut v = -7i32;
                (gl.get_active_uniformsiv)(t, 1, &i, pname, &mut v);
                props.push(v);
            }
            described.push(format!("{} {props:?}", active(r, t, i)));
        }
        described.sort();
        r.note(&format!("booleans and matrices: {described:?}"));

        // An array of blocks: its members' names, and each element's.
        let q = r.program(VS_ARRAY, FS_ARRAY);
        (gl.get_programiv)(q, ACTIVE_UNIFORMS, &mut n);
        let mut listed: Vec<String> = (0..n.max(0) as u32).map(|i| active(r, q, i)).collect();
        listed.sort();
        r.note(&format!("an array of blocks: {n} active uniforms {listed:?}"));
        for block in 0..3u32 {
            let mut count = -1;
            (gl.get_active_uniform_blockiv)(q, block, UNIFORM_BLOCK_ACTIVE_UNIFORMS, &mut count);
            let mut members = vec![-7i32; count.max(0) as usize];
            (gl.get_active_uniform_blockiv)(q, block, UNIFORM_BLOCK_ACTIVE_UNIFORM_INDICES, members.as_mut_ptr());
            let mut named: Vec<String> = members.iter().map(|&i| active(r, q, i as u32)).collect();
            named.sort();
            r.note(&format!("element {block}: {count} members {named:?}"));
        }
    }
}
