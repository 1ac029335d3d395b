//! The programs. Each is a plain function of a `Calls` backend.

use super::*;

fn clear_color(gl: Gl<'_>, _: &mut Names) -> R {
    gl.glClearColor(0.2, 0.4, 0.6, 0.8)?;
    gl.glClear(COLOR_BUFFER_BIT)
}

fn scissor_clear(gl: Gl<'_>, _: &mut Names) -> R {
    gl.glClearColor(0.0, 0.0, 1.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glEnable(SCISSOR_TEST)?;
    gl.glScissor(10, 5, 30, 20)?;
    gl.glClearColor(1.0, 0.5, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)
}

fn color_mask_clear(gl: Gl<'_>, _: &mut Names) -> R {
    gl.glClearColor(0.1, 0.2, 0.3, 0.4)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glColorMask(false, true, false, true)?;
    gl.glClearColor(0.9, 0.9, 0.9, 0.9)?;
    gl.glClear(COLOR_BUFFER_BIT)
}

fn triangle_flat(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 0.25, 0.0, 1.0])?;
    draw_positions(gl, n, &[-0.8, -0.7, 0.0, 0.9, -0.5, 0.0, 0.1, 0.85, 0.0], TRIANGLES)
}

fn triangle_varying(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    let v =
        [-0.9f32, -0.9, 0.0, 1.0, 0.0, 0.0, 1.0, 0.9, -0.9, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.9, 0.0, 0.0, 0.0, 1.0, 0.5];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 3, FLOAT, false, 28, 0)?;
    attrib(gl, 1, 4, FLOAT, false, 28, 12)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

fn viewport_sub(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glViewport(8, 16, 40, 24)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.0, 1.0, 0.5, 1.0])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 0.5, 1.0, 0.0), TRIANGLES)
}

fn depth_less(gl: Gl<'_>, n: &mut Names) -> R {
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

fn depth_greater_cleared_zero(gl: Gl<'_>, n: &mut Names) -> R {
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

fn depth_range(gl: Gl<'_>, n: &mut Names) -> R {
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

fn cull_back(gl: Gl<'_>, n: &mut Names) -> R {
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

fn front_face_cw(gl: Gl<'_>, n: &mut Names) -> R {
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

fn gl_front_facing(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "precision mediump float; void main() { gl_FragColor = gl_FrontFacing ? vec4(0.0, 1.0, 0.0, 1.0) : vec4(1.0, 0.0, 0.0, 1.0); }";
    program(gl, n, VS_POS, fs, &["pos"])?;
    draw_positions(
        gl,
        n,
        &[-0.9, -0.5, 0.0, -0.1, -0.5, 0.0, -0.5, 0.5, 0.0, 0.1, -0.5, 0.0, 0.5, 0.5, 0.0, 0.9, -0.5, 0.0],
        TRIANGLES,
    )
}

fn frag_coord(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "precision highp float; void main() { gl_FragColor = vec4(gl_FragCoord.x / 64.0, gl_FragCoord.y / 64.0, gl_FragCoord.z, 1.0); }";
    program(gl, n, VS_POS, fs, &["pos"])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.25), TRIANGLES)
}

fn blend_alpha(gl: Gl<'_>, n: &mut Names) -> R {
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

fn blend_separate_subtract(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.8, 0.6, 0.4, 0.5)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glEnable(BLEND)?;
    gl.glBlendFuncSeparate(1, 1, 0x0302, 0)?;
    gl.glBlendEquationSeparate(0x800B, 0x800A)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.3, 0.2, 0.1, 0.4])?;
    draw_positions(gl, n, &quad(-0.7, -0.7, 0.7, 0.7, 0.0), TRIANGLES)
}

fn blend_constant(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.2, 0.2, 0.2, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glEnable(BLEND)?;
    gl.glBlendColor(0.5, 0.25, 1.0, 1.0)?;
    gl.glBlendFunc(0x8001, 0x8002)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 1.0, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.7, -0.7, 0.7, 0.7, 0.0), TRIANGLES)
}

fn stencil_mask(gl: Gl<'_>, n: &mut Names) -> R {
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

fn polygon_offset(gl: Gl<'_>, n: &mut Names) -> R {
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

fn indexed(gl: Gl<'_>, n: &mut Names, ty: u32) -> R {
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

fn elements_ubyte(gl: Gl<'_>, n: &mut Names) -> R {
    indexed(gl, n, UNSIGNED_BYTE)
}
fn elements_ushort(gl: Gl<'_>, n: &mut Names) -> R {
    indexed(gl, n, UNSIGNED_SHORT)
}
fn elements_uint(gl: Gl<'_>, n: &mut Names) -> R {
    indexed(gl, n, UNSIGNED_INT)
}

fn strip_and_fan(gl: Gl<'_>, n: &mut Names) -> R {
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

fn fan_indexed(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.6, 0.2, 0.9, 1.0])?;
    let verts = [0.0f32, 0.0, 0.0, 0.9, 0.0, 0.0, 0.6, 0.6, 0.0, 0.0, 0.9, 0.0, -0.6, 0.6, 0.0, -0.9, 0.0, 0.0];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&verts))?;
    attrib(gl, 0, 3, FLOAT, false, 0, 0)?;
    let idx: Vec<u8> = [0u16, 1, 2, 3, 4, 5].iter().flat_map(|i| i.to_ne_bytes()).collect();
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &idx)?;
    gl.glDrawElements(TRIANGLE_FAN, 6, UNSIGNED_SHORT, 0)
}

fn lines(gl: Gl<'_>, n: &mut Names) -> R {
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

fn attrib_formats(gl: Gl<'_>, n: &mut Names) -> R {
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

fn attrib_short_half(gl: Gl<'_>, n: &mut Names) -> R {
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

fn attrib_unnormalized_bytes(gl: Gl<'_>, n: &mut Names) -> R {
    let vs = "attribute vec4 pos; attribute vec4 col; varying vec4 v; void main() { v = col / 255.0; gl_Position = vec4(pos.xy / 100.0, 0.0, 1.0); }";
    program(gl, n, vs, FS_VARY, &["pos", "col"])?;
    let pos: Vec<u8> = [-90i8, -90, 90, -90, 0, 90].iter().map(|&v| v as u8).collect();
    buffer(gl, n, ARRAY_BUFFER, &pos)?;
    attrib(gl, 0, 2, BYTE, false, 0, 0)?;
    buffer(gl, n, ARRAY_BUFFER, &[200, 10, 10, 255, 10, 200, 10, 255, 10, 10, 200, 255])?;
    attrib(gl, 1, 4, UNSIGNED_BYTE, false, 0, 0)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

fn constant_attrib(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    gl.glVertexAttrib4f(1, 0.25, 0.5, 0.75, 1.0)?;
    draw_positions(gl, n, &quad(-0.5, -0.5, 0.5, 0.5, 0.0), TRIANGLES)
}

fn texture_nearest(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 8, 8, RGBA, UNSIGNED_BYTE, &pattern(8, 8), NEAREST, CLAMP_TO_EDGE)?;
    textured_quad(gl, n, 0.0, 1.0)
}

fn texture_linear_repeat(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 4, 4, RGBA, UNSIGNED_BYTE, &pattern(4, 4), LINEAR, REPEAT)?;
    textured_quad(gl, n, -0.5, 2.0)
}

fn texture_mirrored(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 4, 4, RGBA, UNSIGNED_BYTE, &pattern(4, 4), NEAREST, MIRRORED_REPEAT)?;
    textured_quad(gl, n, -1.0, 2.0)
}

fn texture_formats(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glPixelStorei(UNPACK_ALIGNMENT, 1)?;
    let cases: [(u32, u32, Vec<u8>); 6] = [
        (RGB, UNSIGNED_BYTE, vec![255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 0]),
        (LUMINANCE, UNSIGNED_BYTE, vec![0, 85, 170, 255]),
        (ALPHA, UNSIGNED_BYTE, vec![0, 85, 170, 255]),
        (LUMINANCE_ALPHA, UNSIGNED_BYTE, vec![255, 0, 200, 100, 100, 200, 0, 255]),
        (RGB, 0x8363, [0xF800u16, 0x07E0, 0x001F, 0xFFFF].iter().flat_map(|v| v.to_ne_bytes()).collect()),
        (RGBA, 0x8033, [0xF00Fu16, 0x0F0F, 0x00FF, 0x8888].iter().flat_map(|v| v.to_ne_bytes()).collect()),
    ];
    for (i, (fmt, ty, px)) in cases.iter().enumerate() {
        texture(gl, n, 2, 2, *fmt, *ty, px, NEAREST, CLAMP_TO_EDGE)?;
        let x0 = -1.0 + (i % 3) as f32 * 2.0 / 3.0;
        let y0 = -1.0 + (i / 3) as f32;
        let v = [
            x0,
            y0,
            0.0,
            0.0,
            x0 + 0.6,
            y0,
            1.0,
            0.0,
            x0 + 0.6,
            y0 + 0.9,
            1.0,
            1.0,
            x0,
            y0,
            0.0,
            0.0,
            x0 + 0.6,
            y0 + 0.9,
            1.0,
            1.0,
            x0,
            y0 + 0.9,
            0.0,
            1.0,
        ];
        buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
        attrib(gl, 0, 2, FLOAT, false, 16, 0)?;
        attrib(gl, 1, 2, FLOAT, false, 16, 8)?;
        gl.glDrawArrays(TRIANGLES, 0, 6)?;
    }
    Ok(())
}

fn texture_5551(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let px: Vec<u8> = [0xF801u16, 0x07C1, 0x003F, 0x0000].iter().flat_map(|v| v.to_ne_bytes()).collect();
    texture(gl, n, 2, 2, RGBA, 0x8034, &px, NEAREST, CLAMP_TO_EDGE)?;
    textured_quad(gl, n, 0.0, 1.0)
}

fn texture_subimage_alignment(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 8, 8, RGBA, UNSIGNED_BYTE, &pattern(8, 8), NEAREST, CLAMP_TO_EDGE)?;
    // A 3x2 RGB patch with the default alignment of 4: rows are padded to 12 bytes.
    let patch = [255u8, 255, 255, 0, 0, 0, 255, 0, 255, 0, 0, 0, 0, 255, 255, 255, 255, 0, 0, 0, 0];
    gl.glTexImage2D(TEXTURE_2D, 0, RGB as i32, 8, 8, 0, RGB, UNSIGNED_BYTE, Some(Blob::borrowed(&[64u8; 8 * 8 * 3])))?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 2, 3, 3, 2, RGB, UNSIGNED_BYTE, Blob::borrowed(&patch))?;
    textured_quad(gl, n, 0.0, 1.0)
}

fn texture_mipmaps(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 64, 64, RGBA, UNSIGNED_BYTE, &pattern(64, 64), LINEAR_MIPMAP_LINEAR, REPEAT)?;
    gl.glGenerateMipmap(TEXTURE_2D)?;
    textured_quad(gl, n, 0.0, 5.0)
}

fn texture_explicit_levels(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 4, 4, RGBA, UNSIGNED_BYTE, &[255u8; 64], NEAREST_MIPMAP_NEAREST, REPEAT)?;
    gl.glTexImage2D(
        TEXTURE_2D,
        1,
        RGBA as i32,
        2,
        2,
        0,
        RGBA,
        UNSIGNED_BYTE,
        Some(Blob::borrowed(&[255, 0, 0, 255].repeat(4))),
    )?;
    gl.glTexImage2D(TEXTURE_2D, 2, RGBA as i32, 1, 1, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&[0, 0, 255, 255])))?;
    // 4 texels per repeat, 32 repeats over 64 pixels: two texels per pixel selects level 1.
    textured_quad(gl, n, 0.0, 32.0)
}

fn texture_incomplete_is_black(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(1.0, 1.0, 1.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    // Mipmapped minification with only level 0 defined: incomplete, samples (0, 0, 0, 1).
    texture(gl, n, 4, 4, RGBA, UNSIGNED_BYTE, &pattern(4, 4), LINEAR_MIPMAP_LINEAR, REPEAT)?;
    textured_quad(gl, n, 0.0, 1.0)
}

fn texture_cube(gl: Gl<'_>, n: &mut Names) -> R {
    let vs = "attribute vec4 pos; varying vec3 d; void main() { d = vec3(pos.x, pos.y, 0.6); gl_Position = pos; }";
    let fs = "precision mediump float; uniform samplerCube c; varying vec3 d; void main() { gl_FragColor = textureCube(c, d) * 0.5 + textureCube(c, -d.zyx) * 0.5; }";
    program(gl, n, vs, fs, &["pos"])?;
    let t = n.next();
    gl.glBindTexture(TEXTURE_CUBE_MAP, t)?;
    let colours = [
        [255u8, 0, 0, 255],
        [0, 255, 0, 255],
        [0, 0, 255, 255],
        [255, 255, 0, 255],
        [0, 255, 255, 255],
        [255, 0, 255, 255],
    ];
    for (face, c) in colours.iter().enumerate() {
        let mut px = c.repeat(4);
        px[0] = 255 - px[0];
        gl.glTexImage2D(
            TEXTURE_CUBE_MAP_POSITIVE_X + face as u32,
            0,
            RGBA as i32,
            2,
            2,
            0,
            RGBA,
            UNSIGNED_BYTE,
            Some(Blob::borrowed(&px)),
        )?;
    }
    gl.glTexParameteri(TEXTURE_CUBE_MAP, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_CUBE_MAP, TEXTURE_MAG_FILTER, NEAREST)?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)
}

fn two_texture_units(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "precision mediump float; uniform sampler2D a; uniform sampler2D b; varying vec2 t; void main() { gl_FragColor = texture2D(a, t) * texture2D(b, t.yx); }";
    let p = program(gl, n, VS_TEX, fs, &["pos", "uv"])?;
    texture(gl, n, 4, 4, RGBA, UNSIGNED_BYTE, &pattern(4, 4), NEAREST, CLAMP_TO_EDGE)?;
    let t2 = n.next();
    gl.glActiveTexture(TEXTURE0 + 3)?;
    gl.glBindTexture(TEXTURE_2D, t2)?;
    gl.glTexImage2D(
        TEXTURE_2D,
        0,
        RGBA as i32,
        2,
        2,
        0,
        RGBA,
        UNSIGNED_BYTE,
        Some(Blob::borrowed(&[255, 128, 0, 255, 0, 255, 128, 255, 128, 0, 255, 255, 255, 255, 255, 255])),
    )?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    let la = gl.glGetUniformLocation(p, Text::borrowed("a"))?;
    let lb = gl.glGetUniformLocation(p, Text::borrowed("b"))?;
    gl.glUniform1i(la, 0)?;
    gl.glUniform1i(lb, 3)?;
    textured_quad(gl, n, 0.0, 1.0)
}

fn copy_tex_image(gl: Gl<'_>, n: &mut Names) -> R {
    triangle_varying(gl, n)?;
    let t = n.next();
    gl.glActiveTexture(TEXTURE0)?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGBA, 8, 8, 32, 32, 0)?;
    gl.glCopyTexSubImage2D(TEXTURE_2D, 0, 0, 0, 40, 4, 8, 8)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let v = [
        0.2f32, 0.2, 0.0, 0.0, 0.9, 0.2, 1.0, 0.0, 0.9, 0.9, 1.0, 1.0, 0.2, 0.2, 0.0, 0.0, 0.9, 0.9, 1.0, 1.0, 0.2,
        0.9, 0.0, 1.0,
    ];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 2, FLOAT, false, 16, 0)?;
    attrib(gl, 1, 2, FLOAT, false, 16, 8)?;
    gl.glDrawArrays(TRIANGLES, 0, 6)
}

fn render_to_texture(gl: Gl<'_>, n: &mut Names) -> R {
    let fb = n.next();
    let tex = n.next();
    gl.glBindTexture(TEXTURE_2D, tex)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 16, 16, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 0)?;
    if gl.glCheckFramebufferStatus(FRAMEBUFFER)? != 0x8CD5 {
        return Err(ClientError::Unsupported("framebuffer incomplete".into()));
    }
    gl.glViewport(0, 0, 16, 16)?;
    gl.glClearColor(0.0, 0.3, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    triangle_flat(gl, n)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    gl.glClearColor(0.1, 0.1, 0.1, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, tex)?;
    textured_quad(gl, n, 0.0, 1.0)
}

/// A quad from client memory: positions `p0..p1`, texture coordinates `t0..t1`.
fn client_quad(gl: Gl<'_>, p0: [f32; 2], p1: [f32; 2], t0: [f32; 2], t1: [f32; 2]) -> R {
    let pos = f32s(&[p0[0], p0[1], p1[0], p0[1], p0[0], p1[1], p1[0], p1[1]]);
    let uv = f32s(&[t0[0], t0[1], t1[0], t0[1], t0[0], t1[1], t1[0], t1[1]]);
    gl.glBindBuffer(ARRAY_BUFFER, 0)?;
    gl.glVertexAttribPointer(0, 2, FLOAT, false, 0, 0)?;
    gl.glEnableVertexAttribArray(0)?;
    gl.glVertexAttribPointer(1, 2, FLOAT, false, 0, 0)?;
    gl.glEnableVertexAttribArray(1)?;
    gl.strataVertexAttribData(0, Blob::borrowed(&pos))?;
    gl.strataVertexAttribData(1, Blob::borrowed(&uv))?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)
}

/// Render-to-texture ping-pong the way glmark2's desktop scene does it: every framebuffer
/// switch is followed directly by a draw (no clear), with client-side arrays and a uniform,
/// so each new pass begins with a draw that carries its own data.
fn ping_pong_without_clears(gl: Gl<'_>, n: &mut Names) -> R {
    let mut targets = Vec::new();
    for c in [[0.2f32, 0.0, 0.0, 1.0], [0.0, 0.0, 0.2, 1.0]] {
        let (fb, tex) = (n.next(), n.next());
        gl.glBindTexture(TEXTURE_2D, tex)?;
        gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 32, 32, 0, RGBA, UNSIGNED_BYTE, None)?;
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
        gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
        gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 0)?;
        gl.glViewport(0, 0, 32, 32)?;
        gl.glClearColor(c[0], c[1], c[2], c[3])?;
        gl.glClear(COLOR_BUFFER_BIT)?;
        targets.push((fb, tex));
    }
    let [(fa, ta), (fb, tb)] = [targets[0], targets[1]];
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    gl.glClearColor(0.1, 0.1, 0.1, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    // Into A: a flat quad in a uniform colour.
    gl.glBindFramebuffer(FRAMEBUFFER, fa)?;
    gl.glViewport(0, 0, 32, 32)?;
    let flat = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, flat, [1.0, 0.5, 0.0, 1.0])?;
    client_quad(gl, [-0.5, -0.9], [0.9, 0.3], [0.0, 0.0], [0.0, 0.0])?;
    // Into B: part of A.
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glViewport(0, 0, 32, 32)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, ta)?;
    client_quad(gl, [-1.0, -0.6], [0.6, 1.0], [0.1, 0.0], [0.8, 0.7])?;
    // The screen: B on the left, A on the right.
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    gl.glBindTexture(TEXTURE_2D, tb)?;
    client_quad(gl, [-1.0, -1.0], [0.0, 1.0], [0.0, 0.0], [1.0, 1.0])?;
    gl.glBindTexture(TEXTURE_2D, ta)?;
    client_quad(gl, [0.0, -1.0], [1.0, 1.0], [0.0, 0.0], [1.0, 1.0])
}

fn fbo_depth_renderbuffer(gl: Gl<'_>, n: &mut Names) -> R {
    let fb = n.next();
    let tex = n.next();
    let rb = n.next();
    gl.glBindTexture(TEXTURE_2D, tex)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 32, 32, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, LINEAR)?;
    gl.glBindRenderbuffer(RENDERBUFFER, rb)?;
    gl.glRenderbufferStorage(RENDERBUFFER, DEPTH_COMPONENT16, 32, 32)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 0)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, DEPTH_ATTACHMENT, RENDERBUFFER, rb)?;
    gl.glViewport(0, 0, 32, 32)?;
    depth_less(gl, n)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glDisable(DEPTH_TEST)?;
    gl.glViewport(0, 0, W, H)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, tex)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    textured_quad(gl, n, 0.0, 1.0)
}

fn uniform_types(gl: Gl<'_>, n: &mut Names) -> R {
    let vs = "attribute vec4 pos; uniform mat4 m4; uniform mat3 m3; uniform mat2 m2; varying vec2 q;
        void main() { q = m2 * pos.xy; vec3 p = m3 * vec3(pos.xy, 1.0); gl_Position = m4 * vec4(p.xy, 0.0, 1.0); }";
    let fs = "precision mediump float; uniform vec3 c3; uniform ivec2 i2; uniform bool flag; uniform float k[3]; varying vec2 q;
        void main() { float s = flag ? k[2] : k[0]; gl_FragColor = vec4(c3 * s, float(i2.x + i2.y) / 10.0) + vec4(q, 0.0, 0.0) * 0.1; }";
    let p = program(gl, n, vs, fs, &["pos"])?;
    let loc = |gl: Gl<'_>, name: &str| gl.glGetUniformLocation(p, Text::borrowed(name));
    let l = loc(gl, "m4")?;
    gl.glUniformMatrix4fv(
        l,
        false,
        Slice::new(&[0.8, 0.1, 0.0, 0.0, -0.1, 0.8, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.05, -0.05, 0.0, 1.0]),
    )?;
    let l = loc(gl, "m3")?;
    gl.glUniformMatrix3fv(l, false, Slice::new(&[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.1, 0.1, 1.0]))?;
    let l = loc(gl, "m2")?;
    gl.glUniformMatrix2fv(l, false, Slice::new(&[2.0, 0.0, 0.0, 3.0]))?;
    let l = loc(gl, "c3")?;
    gl.glUniform3f(l, 0.2, 0.5, 0.9)?;
    let l = loc(gl, "i2")?;
    gl.glUniform2i(l, 3, 4)?;
    let l = loc(gl, "flag")?;
    gl.glUniform1i(l, 1)?;
    let l = loc(gl, "k")?;
    gl.glUniform1fv(l, Slice::new(&[0.1, 0.5, 0.9]))?;
    let l = loc(gl, "k[1]")?;
    gl.glUniform1f(l, 0.3)?;
    draw_positions(gl, n, &quad(-0.9, -0.9, 0.9, 0.9, 0.0), TRIANGLES)
}

fn glsl_control_flow(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "precision highp float;
        varying vec4 v;
        float steps(float x) { float acc = 0.0; for (int i = 0; i < 8; i++) { if (float(i) > x * 8.0) break; acc += 0.125; } return acc; }
        void main() {
            if (v.x < 0.1) discard;
            vec3 c = v.y > 0.5 ? vec3(steps(v.x), 0.2, 0.4) : vec3(0.1, steps(v.z), mod(v.x * 10.0, 1.0));
            gl_FragColor = vec4(clamp(c, 0.0, 1.0), 1.0);
        }";
    program(gl, n, VS_COLOR, fs, &["pos", "col"])?;
    let v = [
        -1.0f32, -1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, -1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 1.0, 1.0, 0.5, 1.0,
        -1.0, -1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 1.0, 1.0, 0.5, 1.0, -1.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0,
    ];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 3, FLOAT, false, 28, 0)?;
    attrib(gl, 1, 4, FLOAT, false, 28, 12)?;
    gl.glDrawArrays(TRIANGLES, 0, 6)
}

fn preprocessor_and_builtins(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "#ifdef GL_ES\nprecision mediump float;\n#endif\n#define SCALE(x) ((x) * 0.5 + 0.5)\nvarying vec4 v;
        void main() { vec3 n = normalize(v.xyz * 2.0 - 1.0); float d = max(dot(n, normalize(vec3(0.3, 0.5, 1.0))), 0.0);
        gl_FragColor = vec4(SCALE(n.x), pow(d, 4.0), smoothstep(0.2, 0.8, v.z), 1.0); }";
    program(gl, n, VS_COLOR, fs, &["pos", "col"])?;
    let v =
        [-0.9f32, -0.9, 0.0, 0.1, 0.2, 0.9, 1.0, 0.9, -0.9, 0.0, 0.9, 0.3, 0.5, 1.0, 0.0, 0.9, 0.0, 0.5, 0.9, 0.1, 1.0];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 3, FLOAT, false, 28, 0)?;
    attrib(gl, 1, 4, FLOAT, false, 28, 12)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

fn attrib_location_query(gl: Gl<'_>, n: &mut Names) -> R {
    // No BindAttribLocation: the program asks where the linker put its attributes.
    let p = names_program(gl, n, VS_COLOR, FS_VARY)?;
    let pos = gl.glGetAttribLocation(p, Text::borrowed("pos"))?;
    let col = gl.glGetAttribLocation(p, Text::borrowed("col"))?;
    let v =
        [-0.9f32, 0.9, 0.0, 1.0, 1.0, 0.0, 1.0, 0.9, 0.9, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, -0.9, 0.0, 1.0, 0.0, 1.0, 1.0];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, pos as u32, 3, FLOAT, false, 28, 0)?;
    attrib(gl, col as u32, 4, FLOAT, false, 28, 12)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

fn names_program(gl: Gl<'_>, n: &mut Names, vs: &str, fs: &str) -> Result<u32, ClientError> {
    program(gl, n, vs, fs, &[])
}

fn buffer_sub_data(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 0.6, 0.2, 1.0])?;
    let mut v = quad(-0.9, -0.9, -0.1, -0.1, 0.0);
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 3, FLOAT, false, 0, 0)?;
    gl.glDrawArrays(TRIANGLES, 0, 6)?;
    for x in v.iter_mut().step_by(3) {
        *x += 1.0;
    }
    gl.glBufferSubData(ARRAY_BUFFER, 0, Blob::borrowed(&f32s(&v)))?;
    color(gl, p, [0.2, 0.6, 1.0, 1.0])?;
    gl.glDrawArrays(TRIANGLES, 0, 6)
}

fn many_draws_one_pass(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    buffer(gl, n, ARRAY_BUFFER, &f32s(&quad(-0.1, -0.1, 0.1, 0.1, 0.0)))?;
    attrib(gl, 0, 3, FLOAT, false, 0, 0)?;
    let vs2 = "attribute vec4 pos; uniform vec2 off; void main() { gl_Position = pos + vec4(off, 0.0, 0.0); }";
    let p2 = program(gl, n, vs2, FS_COLOR, &["pos"])?;
    let off = gl.glGetUniformLocation(p2, Text::borrowed("off"))?;
    for i in 0..64 {
        let (x, y) = ((i % 8) as f32 * 0.25 - 0.875, (i / 8) as f32 * 0.25 - 0.875);
        gl.glUniform2f(off, x, y)?;
        color(gl, p2, [i as f32 / 64.0, 1.0 - i as f32 / 64.0, 0.5, 1.0])?;
        gl.glDrawArrays(TRIANGLES, 0, 6)?;
    }
    let _ = p;
    Ok(())
}

fn read_pixels_after_errors(gl: Gl<'_>, n: &mut Names) -> R {
    // Invalid calls record errors and change nothing.
    gl.glClearColor(0.3, 0.3, 0.3, 1.0)?;
    gl.glEnable(0x1234)?;
    gl.glDrawArrays(0x77, 0, 3)?;
    gl.glViewport(0, 0, -1, 5)?;
    gl.glBlendFunc(0x9999, 1)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    triangle_flat(gl, n)
}

fn client_arrays(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    gl.glBindBuffer(ARRAY_BUFFER, 0)?;
    // Interleaved client memory: xy as floats, then RGBA as normalised bytes.
    let mut mem = Vec::new();
    for (x, y, c) in
        [(-0.9f32, -0.9f32, [255u8, 0, 0, 255]), (0.9, -0.9, [0, 255, 0, 255]), (0.0, 0.9, [0, 0, 255, 255])]
    {
        mem.extend_from_slice(&x.to_ne_bytes());
        mem.extend_from_slice(&y.to_ne_bytes());
        mem.extend_from_slice(&c);
    }
    gl.glVertexAttribPointer(0, 2, FLOAT, false, 12, 0)?;
    gl.glEnableVertexAttribArray(0)?;
    gl.glVertexAttribPointer(1, 4, UNSIGNED_BYTE, true, 12, 0)?;
    gl.glEnableVertexAttribArray(1)?;
    gl.strataVertexAttribData(0, Blob::borrowed(&mem))?;
    gl.strataVertexAttribData(1, Blob::borrowed(&mem[8..]))?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

fn client_indices(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.9, 0.4, 0.7, 1.0])?;
    let verts = [-0.9f32, -0.9, 0.0, 0.9, -0.9, 0.0, 0.9, 0.9, 0.0, -0.9, 0.9, 0.0];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&verts))?;
    attrib(gl, 0, 3, FLOAT, false, 0, 0)?;
    gl.glBindBuffer(ELEMENT_ARRAY_BUFFER, 0)?;
    gl.strataDrawElementsData(TRIANGLE_STRIP, 4, UNSIGNED_BYTE, Blob::borrowed(&[0, 1, 3, 2]))
}

fn vertex_texture_fetch(gl: Gl<'_>, n: &mut Names) -> R {
    // Each vertex reads its colour and a height from a texture, as glmark2's terrain does.
    let vs = "attribute vec4 pos; attribute vec2 uv; uniform sampler2D s; varying vec4 v;
        void main() { vec4 t = texture2D(s, uv); v = t; gl_Position = pos + vec4(0.0, t.r * 0.3, 0.0, 0.0); }";
    program(gl, n, vs, FS_VARY, &["pos", "uv"])?;
    texture(gl, n, 4, 4, RGBA, UNSIGNED_BYTE, &pattern(4, 4), NEAREST, CLAMP_TO_EDGE)?;
    let v = [-0.9f32, -0.9, 0.1, 0.1, 0.9, -0.9, 0.9, 0.1, 0.0, 0.5, 0.4, 0.9];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 2, FLOAT, false, 16, 0)?;
    attrib(gl, 1, 2, FLOAT, false, 16, 8)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

fn precision_high_branch(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "#ifdef GL_FRAGMENT_PRECISION_HIGH\nprecision highp float;\n#define K 1.0\n#else\nprecision mediump float;\n#define K 0.0\n#endif\nvoid main() { gl_FragColor = vec4(K, 0.5, 1.0 - K, 1.0); }";
    program(gl, n, VS_POS, fs, &["pos"])?;
    draw_positions(gl, n, &quad(-0.5, -0.5, 0.5, 0.5, 0.0), TRIANGLES)
}

const FS_DEPTH: &str = "precision highp float; uniform sampler2D s; varying vec2 t;
    void main() { float d = texture2D(s, t).r; gl_FragColor = vec4(d, fract(d * 16.0), 0.0, 1.0); }";

fn depth_texture_render_and_sample(gl: Gl<'_>, n: &mut Names) -> R {
    // A shadow-map pass: depth only into a DEPTH_COMPONENT texture, then sample it.
    let (fb, tex) = (n.next(), n.next());
    gl.glBindTexture(TEXTURE_2D, tex)?;
    gl.glTexImage2D(TEXTURE_2D, 0, 0x1902, 32, 32, 0, 0x1902, UNSIGNED_INT, None)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, DEPTH_ATTACHMENT, TEXTURE_2D, tex, 0)?;
    if gl.glCheckFramebufferStatus(FRAMEBUFFER)? != 0x8CD5 {
        return Err(ClientError::Unsupported("depth-only framebuffer incomplete".into()));
    }
    gl.glViewport(0, 0, 32, 32)?;
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(DEPTH_BUFFER_BIT)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0; 4])?;
    draw_positions(gl, n, &[-1.0, -1.0, -0.8, 1.0, -1.0, 0.0, -1.0, 1.0, 0.9], TRIANGLES)?;
    draw_positions(gl, n, &quad(0.0, 0.0, 0.8, 0.8, -0.5), TRIANGLES)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glDisable(DEPTH_TEST)?;
    gl.glViewport(0, 0, W, H)?;
    program(gl, n, VS_TEX, FS_DEPTH, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, tex)?;
    textured_quad(gl, n, 0.0, 1.0)
}

fn depth_texture_upload(gl: Gl<'_>, n: &mut Names) -> R {
    let tex = n.next();
    gl.glBindTexture(TEXTURE_2D, tex)?;
    let values: Vec<u8> = (0..16 * 16).flat_map(|i: u32| ((i * 257) as u16).to_ne_bytes()).collect();
    gl.glTexImage2D(TEXTURE_2D, 0, 0x1902, 16, 16, 0, 0x1902, UNSIGNED_SHORT, Some(Blob::borrowed(&values)))?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    program(gl, n, VS_TEX, FS_DEPTH, &["pos", "uv"])?;
    textured_quad(gl, n, 0.0, 1.0)
}

fn points(gl: Gl<'_>, n: &mut Names) -> R {
    let vs = "attribute vec4 pos; void main() { gl_PointSize = 1.0; gl_Position = pos; }";
    let p = program(gl, n, vs, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 1.0, 0.2, 1.0])?;
    // Points at pixel centres.
    let c = |px: f32| (px + 0.5) / 32.0 - 1.0;
    let v: Vec<f32> = (0..20).flat_map(|i| [c((i * 3) as f32), c((i * 2 + 5) as f32), 0.0]).collect();
    draw_positions(gl, n, &v, 0x0000)
}

fn uniform_variants(gl: Gl<'_>, n: &mut Names) -> R {
    let fs =
        "precision highp float; uniform ivec3 a; uniform ivec4 b; uniform vec2 c[2]; uniform vec3 d; uniform vec4 e[2];
        uniform int f[3]; uniform ivec2 g; uniform bvec2 h;
        void main() {
            vec4 o = vec4(float(a.x + a.y + a.z) / 30.0, float(b.w - b.x) / 20.0, c[1].y, 1.0);
            o.rgb += d * 0.25 + e[1].xyz * 0.25;
            o.r += float(f[2]) / 50.0 + float(g.y) / 40.0;
            if (h.y) o.b = 1.0 - o.b;
            gl_FragData[0] = clamp(o, 0.0, 1.0);
        }";
    let p = program(gl, n, VS_POS, fs, &["pos"])?;
    let l = |gl: Gl<'_>, name: &str| gl.glGetUniformLocation(p, Text::borrowed(name));
    let x = l(gl, "a")?;
    gl.glUniform3i(x, 3, 4, 5)?;
    let x = l(gl, "b")?;
    gl.glUniform4iv(x, Slice::new(&[1, 2, 3, 9]))?;
    let x = l(gl, "c")?;
    gl.glUniform2fv(x, Slice::new(&[0.1, 0.2, 0.3, 0.6]))?;
    let x = l(gl, "d")?;
    gl.glUniform3fv(x, Slice::new(&[0.4, 0.2, 0.8]))?;
    let x = l(gl, "e[1]")?;
    gl.glUniform4fv(x, Slice::new(&[0.9, 0.1, 0.5, 1.0]))?;
    let x = l(gl, "f")?;
    gl.glUniform1iv(x, Slice::new(&[1, 2, 7]))?;
    let x = l(gl, "g")?;
    gl.glUniform2iv(x, Slice::new(&[0, 8]))?;
    let x = l(gl, "h")?;
    gl.glUniform2i(x, 0, 1)?;
    draw_positions(gl, n, &quad(-0.9, -0.9, 0.9, 0.9, 0.0), TRIANGLES)
}

fn points_coord(gl: Gl<'_>, n: &mut Names) -> R {
    let vs = "attribute vec4 pos; void main() { gl_PointSize = 1.0; gl_Position = pos; }";
    let fs = "precision mediump float; void main() { gl_FragColor = vec4(gl_PointCoord, 0.5, 1.0); }";
    program(gl, n, vs, fs, &["pos"])?;
    let c = |px: f32| (px + 0.5) / 32.0 - 1.0;
    let v: Vec<f32> = (0..16).flat_map(|i| [c((i * 4) as f32), c(((i * 7) % 60) as f32), 0.0]).collect();
    draw_positions(gl, n, &v, 0x0000)
}

fn mipmap_filters(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    for (i, filter) in [0x2701i32, 0x2702].into_iter().enumerate() {
        texture(gl, n, 16, 16, RGBA, UNSIGNED_BYTE, &pattern(16, 16), filter, REPEAT)?;
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
        gl.glGenerateMipmap(TEXTURE_2D)?;
        let (x0, x1) = if i == 0 { (-1.0, 0.0) } else { (0.0, 1.0) };
        let v = [
            x0, -1.0, 0.0, 0.0, x1, -1.0, 3.0, 0.0, x1, 1.0, 3.0, 6.0, x0, -1.0, 0.0, 0.0, x1, 1.0, 3.0, 6.0, x0, 1.0,
            0.0, 6.0,
        ];
        buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
        attrib(gl, 0, 2, FLOAT, false, 16, 0)?;
        attrib(gl, 1, 2, FLOAT, false, 16, 8)?;
        gl.glDrawArrays(TRIANGLES, 0, 6)?;
    }
    Ok(())
}

fn depth_and_color_masks(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClearColor(0.2, 0.2, 0.2, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    // Drawn without depth writes: the later, farther quad still covers it.
    gl.glDepthMask(false)?;
    color(gl, p, [1.0, 0.0, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-0.8, -0.8, 0.3, 0.3, -0.5), TRIANGLES)?;
    gl.glDepthMask(true)?;
    gl.glColorMask(false, true, true, false)?;
    color(gl, p, [1.0, 0.7, 0.4, 1.0])?;
    draw_positions(gl, n, &quad(-0.5, -0.5, 0.8, 0.8, 0.5), TRIANGLES)
}

fn attrib_ushort(gl: Gl<'_>, n: &mut Names) -> R {
    let vs = "attribute vec4 pos; attribute vec4 col; varying vec4 v; void main() { v = vec4(col.xy / 1000.0, col.z, 1.0); gl_Position = pos; }";
    program(gl, n, vs, FS_VARY, &["pos", "col"])?;
    let pos: Vec<u8> = [0u16, 0, 65535, 0, 32768, 65535].iter().flat_map(|v| v.to_ne_bytes()).collect();
    buffer(gl, n, ARRAY_BUFFER, &pos)?;
    gl.glVertexAttribPointer(0, 2, UNSIGNED_SHORT, true, 0, 0)?;
    gl.glEnableVertexAttribArray(0)?;
    // Unnormalised shorts, three components (converted), plus a constant w.
    let col: Vec<u8> = [900u16, 100, 1, 100, 900, 0, 500, 500, 1].iter().flat_map(|v| v.to_ne_bytes()).collect();
    buffer(gl, n, ARRAY_BUFFER, &col)?;
    attrib(gl, 1, 3, UNSIGNED_SHORT, false, 0, 0)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

fn read_pixels_round_trip(gl: Gl<'_>, n: &mut Names) -> R {
    triangle_varying(gl, n)?;
    // Read a sub-rectangle back and show it, enlarged, in the corner.
    let px = gl.glReadPixels(10, 12, 20, 16, 0x1908, UNSIGNED_BYTE)?.0;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 20, 16, RGBA, UNSIGNED_BYTE, &px, NEAREST, CLAMP_TO_EDGE)?;
    let v = [
        0.2f32, 0.2, 0.0, 0.0, 1.0, 0.2, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.2, 0.2, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.2,
        1.0, 0.0, 1.0,
    ];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 2, FLOAT, false, 16, 0)?;
    attrib(gl, 1, 2, FLOAT, false, 16, 8)?;
    gl.glDrawArrays(TRIANGLES, 0, 6)
}

fn respecified_buffer_between_draws(gl: Gl<'_>, n: &mut Names) -> R {
    // One buffer re-specified with glBufferData between draws, a uniform changed each time.
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let vs = "attribute vec2 pos; attribute vec3 col; uniform vec3 plane; varying vec3 v;
        void main() { v = col; gl_Position = vec4(pos, plane.x * pos.x + plane.y * pos.y + plane.z, 1.0); }";
    let fs = "precision mediump float; varying vec3 v; void main() { gl_FragColor = vec4(v, 1.0); }";
    let p = program(gl, n, vs, fs, &["pos", "col"])?;
    let loc = gl.glGetUniformLocation(p, Text::borrowed("plane"))?;
    let b = n.next();
    gl.glBindBuffer(ARRAY_BUFFER, b)?;
    gl.glVertexAttribPointer(0, 2, FLOAT, false, 20, 0)?;
    gl.glVertexAttribPointer(1, 3, FLOAT, false, 20, 8)?;
    gl.glEnableVertexAttribArray(0)?;
    gl.glEnableVertexAttribArray(1)?;
    let base = [-0.9f32, -0.9, 1.0, 0.5, 0.1, 0.9, -0.9, 1.0, 0.5, 0.1, 0.0, 0.9, 1.0, 0.5, 0.1];
    let needle = [-0.05f32, -0.01, 1.0, 0.1, 0.1, 0.05, 0.01, 1.0, 0.1, 0.1, -0.2, 0.78, 1.0, 0.9, 0.9];
    for (verts, lift) in [(&base[..], 0.0f32), (&needle[..], 0.03)] {
        gl.glUniform3f(loc, 0.0, 0.5, -lift)?;
        gl.glBufferData(ARRAY_BUFFER, (verts.len() * 4) as i64, Some(Blob::borrowed(&f32s(verts))), 0x88E8)?;
        gl.glDrawArrays(TRIANGLES, 0, 3)?;
    }
    Ok(())
}

fn sampler_parameter_function(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "precision mediump float; uniform sampler2D s; varying vec2 t;
        vec4 blend2(sampler2D tex, vec2 uv) { return texture2D(tex, uv) * 0.5 + texture2D(tex, uv.yx) * 0.5; }
        void main() { gl_FragColor = blend2(s, t); }";
    program(gl, n, VS_TEX, fs, &["pos", "uv"])?;
    texture(gl, n, 8, 8, RGBA, UNSIGNED_BYTE, &pattern(8, 8), NEAREST, CLAMP_TO_EDGE)?;
    textured_quad(gl, n, 0.0, 1.0)
}

fn matrix_varying(gl: Gl<'_>, n: &mut Names) -> R {
    let vs = "attribute vec4 pos; attribute vec4 col; varying mat3 m; varying vec2 p;
        void main() { m = mat3(col.xyz, col.yzx, vec3(0.2, 0.4, 0.6)); p = pos.xy; gl_Position = pos; }";
    let fs = "precision mediump float; varying mat3 m; varying vec2 p;
        void main() { gl_FragColor = vec4(m * vec3(0.5 + 0.5 * p.x, 0.3, 0.5 - 0.5 * p.y) * 0.6, 1.0); }";
    program(gl, n, vs, fs, &["pos", "col"])?;
    let v =
        [-0.9f32, -0.9, 0.0, 1.0, 0.2, 0.1, 1.0, 0.9, -0.9, 0.0, 0.1, 1.0, 0.3, 1.0, 0.0, 0.9, 0.0, 0.4, 0.2, 1.0, 1.0];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 3, FLOAT, false, 28, 0)?;
    attrib(gl, 1, 4, FLOAT, false, 28, 12)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

/// Every program, with its tolerance.
pub fn all() -> Vec<Case> {
    let c = |name, run, tol| Case { name, run, tol, expects_error: false };
    // Line rasterisation: both rasterisers are llvmpipe-derived, but GL (diamond-exit) and
    // Vulkan (rectangular) line rules may place endpoint pixels differently; allow endpoints.
    let lines_tol = Tol { max_diff: 1, min_fraction: 0.995 };
    // Trilinear minification: mip levels are box-filtered by both, but the LOD and the
    // 8-bit rounding of each level can differ by a few steps.
    let mip_tol = Tol { max_diff: 6, min_fraction: 0.98 };
    // Transcendentals (pow, normalize) in mediump differ in the last bits between the two
    // shader compilers.
    let math_tol = Tol { max_diff: 3, min_fraction: 0.995 };
    // FS_DEPTH shows fract(16·d) to make depth errors visible: it magnifies the difference
    // between Mesa's unorm depth storage and wgpu's Depth32Float sixteenfold, so the last
    // bit of that channel may round either way (at most 2/255).
    let depth_tol = Tol { max_diff: 2, min_fraction: 0.999 };
    vec![
        c("clear_color", clear_color, DEFAULT),
        c("scissor_clear", scissor_clear, DEFAULT),
        c("color_mask_clear", color_mask_clear, DEFAULT),
        c("triangle_flat", triangle_flat, DEFAULT),
        c("triangle_varying", triangle_varying, DEFAULT),
        c("viewport_sub", viewport_sub, DEFAULT),
        c("depth_less", depth_less, DEFAULT),
        c("depth_greater_cleared_zero", depth_greater_cleared_zero, DEFAULT),
        c("depth_range", depth_range, DEFAULT),
        c("cull_back", cull_back, DEFAULT),
        c("front_face_cw", front_face_cw, DEFAULT),
        c("gl_front_facing", gl_front_facing, DEFAULT),
        c("frag_coord", frag_coord, DEFAULT),
        c("blend_alpha", blend_alpha, DEFAULT),
        c("blend_separate_subtract", blend_separate_subtract, DEFAULT),
        c("blend_constant", blend_constant, DEFAULT),
        c("stencil_mask", stencil_mask, DEFAULT),
        c("polygon_offset", polygon_offset, DEFAULT),
        c("elements_ubyte", elements_ubyte, DEFAULT),
        c("elements_ushort", elements_ushort, DEFAULT),
        c("elements_uint", elements_uint, DEFAULT),
        c("strip_and_fan", strip_and_fan, DEFAULT),
        c("fan_indexed", fan_indexed, DEFAULT),
        c("lines", lines, lines_tol),
        c("attrib_formats", attrib_formats, DEFAULT),
        c("attrib_short_half", attrib_short_half, DEFAULT),
        c("attrib_unnormalized_bytes", attrib_unnormalized_bytes, DEFAULT),
        c("constant_attrib", constant_attrib, DEFAULT),
        c("texture_nearest", texture_nearest, DEFAULT),
        c("texture_linear_repeat", texture_linear_repeat, DEFAULT),
        c("texture_mirrored", texture_mirrored, DEFAULT),
        c("texture_formats", texture_formats, DEFAULT),
        c("texture_5551", texture_5551, DEFAULT),
        c("texture_subimage_alignment", texture_subimage_alignment, DEFAULT),
        c("texture_mipmaps", texture_mipmaps, mip_tol),
        c("texture_explicit_levels", texture_explicit_levels, DEFAULT),
        c("texture_incomplete_is_black", texture_incomplete_is_black, DEFAULT),
        c("texture_cube", texture_cube, DEFAULT),
        c("two_texture_units", two_texture_units, DEFAULT),
        c("copy_tex_image", copy_tex_image, DEFAULT),
        c("render_to_texture", render_to_texture, DEFAULT),
        c("ping_pong_without_clears", ping_pong_without_clears, DEFAULT),
        c("fbo_depth_renderbuffer", fbo_depth_renderbuffer, DEFAULT),
        c("uniform_types", uniform_types, DEFAULT),
        c("glsl_control_flow", glsl_control_flow, DEFAULT),
        c("preprocessor_and_builtins", preprocessor_and_builtins, math_tol),
        c("attrib_location_query", attrib_location_query, DEFAULT),
        c("buffer_sub_data", buffer_sub_data, DEFAULT),
        c("client_arrays", client_arrays, DEFAULT),
        c("vertex_texture_fetch", vertex_texture_fetch, DEFAULT),
        c("depth_texture_render_and_sample", depth_texture_render_and_sample, depth_tol),
        c("depth_texture_upload", depth_texture_upload, depth_tol),
        c("points", points, DEFAULT),
        c("points_coord", points_coord, DEFAULT),
        c("uniform_variants", uniform_variants, DEFAULT),
        c("mipmap_filters", mipmap_filters, mip_tol),
        c("depth_and_color_masks", depth_and_color_masks, DEFAULT),
        c("attrib_ushort", attrib_ushort, DEFAULT),
        c("read_pixels_round_trip", read_pixels_round_trip, DEFAULT),
        c("respecified_buffer_between_draws", respecified_buffer_between_draws, DEFAULT),
        c("sampler_parameter_function", sampler_parameter_function, DEFAULT),
        c("matrix_varying", matrix_varying, DEFAULT),
        c("precision_high_branch", precision_high_branch, DEFAULT),
        c("client_indices", client_indices, DEFAULT),
        c("many_draws_one_pass", many_draws_one_pass, DEFAULT),
        Case { name: "read_pixels_after_errors", run: read_pixels_after_errors, tol: DEFAULT, expects_error: true },
    ]
}
