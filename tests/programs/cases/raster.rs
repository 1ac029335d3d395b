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

/// Front- and back-facing triangles with stencil references, read masks and write masks of
/// their own (`glStencilFuncSeparate`, `glStencilMaskSeparate`), the result shown by equality
/// tests; the same with front faces culled.
pub(super) fn stencil_separate_faces(gl: Gl<'_>, n: &mut Names) -> R {
    const FRONT: u32 = 0x0404;
    const BACK: u32 = 0x0405;
    const FRONT_AND_BACK: u32 = 0x0408;
    const ALWAYS: u32 = 0x0207;
    const EQUAL: u32 = 0x0202;
    const KEEP: u32 = 0x1E00;
    const REPLACE: u32 = 0x1E01;
    const INCR: u32 = 0x1E02;
    gl.glClearStencil(0)?;
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT | STENCIL_BUFFER_BIT)?;
    gl.glEnable(STENCIL_TEST)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    // Front faces write 0x11 through mask 0x0F, back faces 0x2C through 0xF0.
    gl.glStencilFuncSeparate(FRONT, ALWAYS, 0x11, 0xFF)?;
    gl.glStencilFuncSeparate(BACK, ALWAYS, 0x2C, 0xFF)?;
    gl.glStencilOpSeparate(FRONT_AND_BACK, KEEP, KEEP, REPLACE)?;
    gl.glStencilMaskSeparate(FRONT, 0x0F)?;
    gl.glStencilMaskSeparate(BACK, 0xF0)?;
    gl.glColorMask(false, false, false, false)?;
    let mut back = quad(0.0, -1.0, 0.8, 0.5, 0.0);
    back.reverse();
    let back: Vec<f32> = back.chunks(3).flat_map(|c| [c[2], c[1], c[0]]).collect();
    draw_positions(gl, n, &quad(-0.8, -0.5, 0.3, 0.8, 0.0), TRIANGLES)?;
    draw_positions(gl, n, &back, TRIANGLES)?;
    // Back faces only (front ones culled) count up where the stencil, read through 0x30, is
    // 0x20; front faces would need 0x01 through 0x0F.
    gl.glEnable(CULL_FACE)?;
    gl.glCullFace(FRONT)?;
    gl.glStencilFuncSeparate(FRONT, EQUAL, 0x01, 0x0F)?;
    gl.glStencilFuncSeparate(BACK, EQUAL, 0x20, 0x30)?;
    gl.glStencilOpSeparate(FRONT_AND_BACK, KEEP, KEEP, INCR)?;
    gl.glStencilMaskSeparate(FRONT_AND_BACK, 0xFF)?;
    draw_positions(gl, n, &back, TRIANGLES)?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
    gl.glDisable(CULL_FACE)?;
    gl.glColorMask(true, true, true, true)?;
    gl.glStencilMaskSeparate(FRONT_AND_BACK, 0)?;
    for (value, c) in [
        (0x01, [1.0, 0.0, 0.0, 1.0]),
        (0x20, [0.0, 1.0, 0.0, 1.0]),
        (0x21, [0.0, 0.0, 1.0, 1.0]),
        (0x2D, [1.0, 1.0, 0.0, 1.0]),
    ] {
        gl.glStencilFunc(EQUAL, value, 0xFF)?;
        color(gl, p, c)?;
        draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
    }
    gl.glStencilMask(0xFF)?;
    gl.glDisable(STENCIL_TEST)
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
