//! Programs of texturing: filters and wrap modes, formats, sub-image uploads, mipmaps,
//! incomplete and cube textures, texture units, copies from the framebuffer, and rendering to
//! textures and renderbuffers.

use super::*;

pub(super) fn texture_nearest(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 8, 8, RGBA, UNSIGNED_BYTE, &pattern(8, 8), NEAREST, CLAMP_TO_EDGE)?;
    textured_quad(gl, n, 0.0, 1.0)
}

pub(super) fn texture_linear_repeat(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 4, 4, RGBA, UNSIGNED_BYTE, &pattern(4, 4), LINEAR, REPEAT)?;
    textured_quad(gl, n, -0.5, 2.0)
}

pub(super) fn texture_mirrored(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 4, 4, RGBA, UNSIGNED_BYTE, &pattern(4, 4), NEAREST, MIRRORED_REPEAT)?;
    textured_quad(gl, n, -1.0, 2.0)
}

pub(super) fn texture_formats(gl: Gl<'_>, n: &mut Names) -> R {
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

pub(super) fn texture_5551(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let px: Vec<u8> = [0xF801u16, 0x07C1, 0x003F, 0x0000].iter().flat_map(|v| v.to_ne_bytes()).collect();
    texture(gl, n, 2, 2, RGBA, 0x8034, &px, NEAREST, CLAMP_TO_EDGE)?;
    textured_quad(gl, n, 0.0, 1.0)
}

pub(super) fn texture_subimage_alignment(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 8, 8, RGBA, UNSIGNED_BYTE, &pattern(8, 8), NEAREST, CLAMP_TO_EDGE)?;
    // A 3x2 RGB patch with the default alignment of 4: rows are padded to 12 bytes.
    let patch = [255u8, 255, 255, 0, 0, 0, 255, 0, 255, 0, 0, 0, 0, 255, 255, 255, 255, 0, 0, 0, 0];
    gl.glTexImage2D(TEXTURE_2D, 0, RGB as i32, 8, 8, 0, RGB, UNSIGNED_BYTE, Some(Blob::borrowed(&[64u8; 8 * 8 * 3])))?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 2, 3, 3, 2, RGB, UNSIGNED_BYTE, Blob::borrowed(&patch))?;
    textured_quad(gl, n, 0.0, 1.0)
}

pub(super) fn texture_mipmaps(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 64, 64, RGBA, UNSIGNED_BYTE, &pattern(64, 64), LINEAR_MIPMAP_LINEAR, REPEAT)?;
    gl.glGenerateMipmap(TEXTURE_2D)?;
    textured_quad(gl, n, 0.0, 5.0)
}

pub(super) fn texture_explicit_levels(gl: Gl<'_>, n: &mut Names) -> R {
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

pub(super) fn texture_incomplete_is_black(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(1.0, 1.0, 1.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    // Mipmapped minification with only level 0 defined: incomplete, samples (0, 0, 0, 1).
    texture(gl, n, 4, 4, RGBA, UNSIGNED_BYTE, &pattern(4, 4), LINEAR_MIPMAP_LINEAR, REPEAT)?;
    textured_quad(gl, n, 0.0, 1.0)
}

pub(super) fn texture_cube(gl: Gl<'_>, n: &mut Names) -> R {
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

pub(super) fn two_texture_units(gl: Gl<'_>, n: &mut Names) -> R {
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

pub(super) fn copy_tex_image(gl: Gl<'_>, n: &mut Names) -> R {
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

pub(super) fn render_to_texture(gl: Gl<'_>, n: &mut Names) -> R {
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
pub(super) fn client_quad(gl: Gl<'_>, p0: [f32; 2], p1: [f32; 2], t0: [f32; 2], t1: [f32; 2]) -> R {
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
pub(super) fn ping_pong_without_clears(gl: Gl<'_>, n: &mut Names) -> R {
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

pub(super) fn fbo_depth_renderbuffer(gl: Gl<'_>, n: &mut Names) -> R {
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
