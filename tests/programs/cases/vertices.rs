//! Programs of vertex input: indexed draws of each index type, strips, fans and lines, and
//! attributes of every component type, normalised or not, and constant.

use super::*;

pub(super) fn indexed(gl: Gl<'_>, n: &mut Names, ty: u32) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.3, 0.6, 0.9, 1.0])?;
    let verts = [-0.9f32, -0.9, 0.0, 0.9, -0.9, 0.0, 0.9, 0.9, 0.0, -0.9, 0.9, 0.0, 0.0, 0.0, 0.0];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&verts))?;
    attrib(gl, 0, 3, FLOAT, false, 0, 0)?;
    let idx = [0u32, 1, 4, 2, 3, 4];
    let bytes: Vec<u8> = match ty {
        UNSIGNED_BYTE => idx.iter().map(|&i| i as u8).collect(),
        UNSIGNED_SHORT => idx.iter().flat_map(|&i| (i as u16).to_ne_bytes()).collect(),
        _ => idx.iter().flat_map(|&i| i.to_ne_bytes()).collect(),
    };
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &bytes)?;
    gl.glDrawElements(TRIANGLES, 6, ty, 0)
}

pub(super) fn elements_ubyte(gl: Gl<'_>, n: &mut Names) -> R {
    indexed(gl, n, UNSIGNED_BYTE)
}
pub(super) fn elements_ushort(gl: Gl<'_>, n: &mut Names) -> R {
    indexed(gl, n, UNSIGNED_SHORT)
}
/// 32-bit indices (`GL_OES_element_index_uint`).
pub(super) fn elements_uint(gl: Gl<'_>, n: &mut Names) -> R {
    indexed(gl, n, UNSIGNED_INT)
}

pub(super) fn strip_and_fan(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.9, 0.8, 0.1, 1.0])?;
    draw_positions(
        gl,
        n,
        &[-0.9, -0.9, 0.0, -0.9, -0.1, 0.0, -0.5, -0.9, 0.0, -0.3, -0.2, 0.0, -0.1, -0.8, 0.0],
        TRIANGLE_STRIP,
    )?;
    color(gl, p, [0.1, 0.8, 0.9, 1.0])?;
    draw_positions(
        gl,
        n,
        &[0.5, 0.5, 0.0, 0.9, 0.5, 0.0, 0.8, 0.8, 0.0, 0.5, 0.95, 0.0, 0.2, 0.8, 0.0, 0.1, 0.5, 0.0],
        TRIANGLE_FAN,
    )
}

pub(super) fn fan_indexed(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.6, 0.2, 0.9, 1.0])?;
    let verts = [0.0f32, 0.0, 0.0, 0.9, 0.0, 0.0, 0.6, 0.6, 0.0, 0.0, 0.9, 0.0, -0.6, 0.6, 0.0, -0.9, 0.0, 0.0];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&verts))?;
    attrib(gl, 0, 3, FLOAT, false, 0, 0)?;
    let idx: Vec<u8> = [0u16, 1, 2, 3, 4, 5].iter().flat_map(|i| i.to_ne_bytes()).collect();
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &idx)?;
    gl.glDrawElements(TRIANGLE_FAN, 6, UNSIGNED_SHORT, 0)
}

pub(super) fn lines(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 1.0, 1.0, 1.0])?;
    // Axis-aligned lines through pixel centres rasterise identically under GL and Vulkan rules.
    let c = |px: f32| (px + 0.5) / 32.0 - 1.0;
    draw_positions(
        gl,
        n,
        &[c(4.0), c(10.0), 0.0, c(60.0), c(10.0), 0.0, c(20.0), c(2.0), 0.0, c(20.0), c(50.0), 0.0],
        LINES,
    )?;
    color(gl, p, [1.0, 0.0, 0.5, 1.0])?;
    draw_positions(
        gl,
        n,
        &[c(30.0), c(30.0), 0.0, c(50.0), c(30.0), 0.0, c(50.0), c(55.0), 0.0, c(30.0), c(55.0), 0.0],
        LINE_LOOP,
    )?;
    color(gl, p, [0.0, 1.0, 1.0, 1.0])?;
    draw_positions(gl, n, &[c(5.0), c(40.0), 0.0, c(15.0), c(40.0), 0.0, c(15.0), c(60.0), 0.0], LINE_STRIP)
}

pub(super) fn attrib_formats(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    // Positions as FIXED 16.16, colours as normalised unsigned bytes (size 3: converted).
    let one = 65536i32;
    let pos: Vec<u8> = [-one * 9 / 10, -one * 9 / 10, 0, one * 9 / 10, -one * 9 / 10, 0, 0, one * 9 / 10, 0]
        .iter()
        .flat_map(|v| v.to_ne_bytes())
        .collect();
    buffer(gl, n, ARRAY_BUFFER, &pos)?;
    attrib(gl, 0, 3, FIXED, false, 0, 0)?;
    buffer(gl, n, ARRAY_BUFFER, &[255, 0, 0, 0, 255, 0, 0, 0, 255])?;
    attrib(gl, 1, 3, UNSIGNED_BYTE, true, 0, 0)?;
    gl.glVertexAttrib4f(1, 0.0, 0.0, 0.0, 1.0)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

/// Normalised shorts for positions and `GL_OES_vertex_half_float`'s half floats for colours.
pub(super) fn attrib_short_half(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    let pos: Vec<u8> = [-30000i16, -30000, 30000, -30000, 0, 30000].iter().flat_map(|v| v.to_ne_bytes()).collect();
    buffer(gl, n, ARRAY_BUFFER, &pos)?;
    attrib(gl, 0, 2, SHORT, true, 0, 0)?;
    let h = |x: f32| half::f16::from_f32(x).to_bits().to_ne_bytes();
    let col: Vec<u8> =
        [1.0, 0.5, 0.0, 1.0, 0.0, 1.0, 0.5, 1.0, 0.5, 0.0, 1.0, 1.0].iter().flat_map(|&x| h(x)).collect();
    buffer(gl, n, ARRAY_BUFFER, &col)?;
    attrib(gl, 1, 4, HALF_FLOAT_OES, false, 0, 0)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

pub(super) fn attrib_unnormalized_bytes(gl: Gl<'_>, n: &mut Names) -> R {
    let vs = "attribute vec4 pos; attribute vec4 col; varying vec4 v; void main() { v = col / 255.0; gl_Position = vec4(pos.xy / 100.0, 0.0, 1.0); }";
    program(gl, n, vs, FS_VARY, &["pos", "col"])?;
    let pos: Vec<u8> = [-90i8, -90, 90, -90, 0, 90].iter().map(|&v| v as u8).collect();
    buffer(gl, n, ARRAY_BUFFER, &pos)?;
    attrib(gl, 0, 2, BYTE, false, 0, 0)?;
    buffer(gl, n, ARRAY_BUFFER, &[200, 10, 10, 255, 10, 200, 10, 255, 10, 10, 200, 255])?;
    attrib(gl, 1, 4, UNSIGNED_BYTE, false, 0, 0)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

pub(super) fn constant_attrib(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    gl.glVertexAttrib4f(1, 0.25, 0.5, 0.75, 1.0)?;
    draw_positions(gl, n, &quad(-0.5, -0.5, 0.5, 0.5, 0.0), TRIANGLES)
}
