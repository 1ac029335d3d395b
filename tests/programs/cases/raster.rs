//! Programs of rasterisation and per-fragment state: clears, triangles and varyings, the
//! viewport, depth tests and ranges, culling and winding, `gl_FrontFacing` and
//! `gl_FragCoord`, blending, stencil and polygon offset.

use super::*;

pub(super) fn clear_color(gl: Gl<'_>, _: &mut Names) -> R {
    gl.glClearColor(0.2, 0.4, 0.6, 0.8)?;
    gl.glClear(COLOR_BUFFER_BIT)
}

pub(super) fn scissor_clear(gl: Gl<'_>, _: &mut Names) -> R {
    gl.glClearColor(0.0, 0.0, 1.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glEnable(SCISSOR_TEST)?;
    gl.glScissor(10, 5, 30, 20)?;
    gl.glClearColor(1.0, 0.5, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)
}

pub(super) fn color_mask_clear(gl: Gl<'_>, _: &mut Names) -> R {
    gl.glClearColor(0.1, 0.2, 0.3, 0.4)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glColorMask(false, true, false, true)?;
    gl.glClearColor(0.9, 0.9, 0.9, 0.9)?;
    gl.glClear(COLOR_BUFFER_BIT)
}

pub(super) fn triangle_flat(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 0.25, 0.0, 1.0])?;
    draw_positions(gl, n, &[-0.8, -0.7, 0.0, 0.9, -0.5, 0.0, 0.1, 0.85, 0.0], TRIANGLES)
}

pub(super) fn triangle_varying(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    let v =
        [-0.9f32, -0.9, 0.0, 1.0, 0.0, 0.0, 1.0, 0.9, -0.9, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.9, 0.0, 0.0, 0.0, 1.0, 0.5];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 3, FLOAT, false, 28, 0)?;
    attrib(gl, 1, 4, FLOAT, false, 28, 12)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

pub(super) fn viewport_sub(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glViewport(8, 16, 40, 24)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.0, 1.0, 0.5, 1.0])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 0.5, 1.0, 0.0), TRIANGLES)
}

pub(super) fn depth_less(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 0.0, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.8, -0.8, 0.4, 0.4, 0.2), TRIANGLES)?;
    color(gl, p, [0.0, 1.0, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.4, -0.4, 0.8, 0.8, 0.5), TRIANGLES)?;
    color(gl, p, [0.0, 0.0, 1.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.2, -0.9, 0.2, 0.9, -0.3), TRIANGLES)
}

pub(super) fn depth_greater_cleared_zero(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glEnable(DEPTH_TEST)?;
    gl.glDepthFunc(0x0204)?;
    gl.glClearDepthf(0.0)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 1.0, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.8, -0.8, 0.4, 0.4, 0.5), TRIANGLES)?;
    color(gl, p, [0.0, 1.0, 1.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.4, -0.4, 0.8, 0.8, 0.2), TRIANGLES)
}

pub(super) fn depth_range(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    gl.glDepthRangef(0.5, 1.0)?;
    color(gl, p, [1.0, 0.0, 1.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.8, -0.8, 0.4, 0.4, -0.9), TRIANGLES)?;
    gl.glDepthRangef(0.0, 0.5)?;
    color(gl, p, [0.0, 0.5, 1.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.4, -0.4, 0.8, 0.8, 0.9), TRIANGLES)
}

pub(super) fn cull_back(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glEnable(CULL_FACE)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 1.0, 1.0, 1.0])?;
    // Counter-clockwise (front) on the left, clockwise (back) on the right.
    draw_positions(
        gl,
        n,
        &[-0.9, -0.5, 0.0, -0.1, -0.5, 0.0, -0.5, 0.5, 0.0, 0.1, -0.5, 0.0, 0.5, 0.5, 0.0, 0.9, -0.5, 0.0],
        TRIANGLES,
    )
}

pub(super) fn front_face_cw(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glEnable(CULL_FACE)?;
    gl.glFrontFace(0x0900)?;
    gl.glCullFace(0x0405)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.5, 1.0, 0.5, 1.0])?;
    draw_positions(
        gl,
        n,
        &[-0.9, -0.5, 0.0, -0.1, -0.5, 0.0, -0.5, 0.5, 0.0, 0.1, -0.5, 0.0, 0.5, 0.5, 0.0, 0.9, -0.5, 0.0],
        TRIANGLES,
    )
}

pub(super) fn gl_front_facing(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "precision mediump float; void main() { gl_FragColor = gl_FrontFacing ? vec4(0.0, 1.0, 0.0, 1.0) : vec4(1.0, 0.0, 0.0, 1.0); }";
    program(gl, n, VS_POS, fs, &["pos"])?;
    draw_positions(
        gl,
        n,
        &[-0.9, -0.5, 0.0, -0.1, -0.5, 0.0, -0.5, 0.5, 0.0, 0.1, -0.5, 0.0, 0.5, 0.5, 0.0, 0.9, -0.5, 0.0],
        TRIANGLES,
    )
}

pub(super) fn frag_coord(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "precision highp float; void main() { gl_FragColor = vec4(gl_FragCoord.x / 64.0, gl_FragCoord.y / 64.0, gl_FragCoord.z, 1.0); }";
    program(gl, n, VS_POS, fs, &["pos"])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.25), TRIANGLES)
}

pub(super) fn blend_alpha(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.0, 0.0, 1.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glEnable(BLEND)?;
    gl.glBlendFunc(0x0302, 0x0303)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 0.0, 0.0, 0.25])?;
    draw_positions(gl, n, &quad(-0.8, -0.8, 0.5, 0.5, 0.0), TRIANGLES)?;
    color(gl, p, [0.0, 1.0, 0.0, 0.5])?;
    draw_positions(gl, n, &quad(-0.5, -0.5, 0.8, 0.8, 0.0), TRIANGLES)
}

pub(super) fn blend_separate_subtract(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.8, 0.6, 0.4, 0.5)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glEnable(BLEND)?;
    gl.glBlendFuncSeparate(1, 1, 0x0302, 0)?;
    gl.glBlendEquationSeparate(0x800B, 0x800A)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.3, 0.2, 0.1, 0.4])?;
    draw_positions(gl, n, &quad(-0.7, -0.7, 0.7, 0.7, 0.0), TRIANGLES)
}

pub(super) fn blend_constant(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.2, 0.2, 0.2, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glEnable(BLEND)?;
    gl.glBlendColor(0.5, 0.25, 1.0, 1.0)?;
    gl.glBlendFunc(0x8001, 0x8002)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 1.0, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.7, -0.7, 0.7, 0.7, 0.0), TRIANGLES)?;
    // The constant's alpha as the colour factor (CONSTANT_ALPHA, ONE_MINUS_CONSTANT_ALPHA),
    // then beside the constant colour, whose alpha the alpha factor reads.
    gl.glBlendColor(0.2, 0.4, 0.6, 0.8)?;
    gl.glBlendFunc(0x8003, 0x8004)?;
    color(gl, p, [0.0, 1.0, 1.0, 0.5])?;
    draw_positions(gl, n, &quad(-0.9, -0.9, 0.0, 0.0, 0.0), TRIANGLES)?;
    gl.glBlendFuncSeparate(0x8003, 0x8004, 0x8001, 0)?;
    draw_positions(gl, n, &quad(0.0, 0.0, 0.9, 0.9, 0.0), TRIANGLES)
}

pub(super) fn stencil_mask(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearStencil(0)?;
    gl.glClear(COLOR_BUFFER_BIT | STENCIL_BUFFER_BIT)?;
    gl.glEnable(STENCIL_TEST)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    gl.glStencilFunc(0x0207, 1, 0xff)?;
    gl.glStencilOp(0x1E00, 0x1E00, 0x1E01)?;
    gl.glColorMask(false, false, false, false)?;
    color(gl, p, [1.0, 1.0, 1.0, 1.0])?;
    draw_positions(gl, n, &[-0.9, -0.9, 0.0, 0.9, -0.9, 0.0, 0.0, 0.9, 0.0], TRIANGLES)?;
    gl.glColorMask(true, true, true, true)?;
    gl.glStencilFunc(0x0205, 1, 0xff)?;
    gl.glStencilOp(0x1E00, 0x1E00, 0x1E00)?;
    color(gl, p, [1.0, 0.5, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)
}

pub(super) fn polygon_offset(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glEnable(DEPTH_TEST)?;
    gl.glDepthFunc(0x0203)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 0.0, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.8, -0.8, 0.8, 0.8, 0.3), TRIANGLES)?;
    gl.glEnable(POLYGON_OFFSET_FILL)?;
    gl.glPolygonOffset(0.0, 8.0)?;
    color(gl, p, [0.0, 1.0, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.4, -0.4, 0.4, 0.4, 0.3), TRIANGLES)
}
