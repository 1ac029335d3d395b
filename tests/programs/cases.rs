//! The programs, each a plain function of a `Calls` backend, and [`all`], the list the oracle
//! runs. Rasterisation, vertex input and texturing have files of their own; what stays here
//! is GLSL (uniforms, control flow, the preprocessor, precision), buffers and client-side
//! arrays, readbacks, depth textures and points.

use super::*;

mod raster;
mod texturing;
mod vertices;

use raster::*;
use texturing::*;
use vertices::*;

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

/// `GL_OES_depth_texture`: a depth texture rendered into as a framebuffer's depth, then sampled.
fn depth_texture_render_and_sample(gl: Gl<'_>, n: &mut Names) -> R {
    // A shadow-map pass: depth only into a DEPTH_COMPONENT texture, then sample it.
    let tex = depth_texture_target(gl, n, 32)?;
    gl.glClear(DEPTH_BUFFER_BIT)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0; 4])?;
    draw_positions(gl, n, &[-1.0, -1.0, -0.8, 1.0, -1.0, 0.0, -1.0, 1.0, 0.9], TRIANGLES)?;
    draw_positions(gl, n, &quad(0.0, 0.0, 0.8, 0.8, -0.5), TRIANGLES)?;
    show_depth_texture(gl, n, tex)
}

/// `GL_OES_depth_texture`: a depth texture uploaded as 16-bit values, then sampled.
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
        c("stencil_separate_faces", stencil_separate_faces, DEFAULT),
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
