//! GL misuse against the executor: every invalid call records the GL error a driver would and
//! changes nothing; draws that would read past a buffer or index beyond the vertex data are
//! refused with GL_INVALID_OPERATION before reaching the GPU; a malformed shader yields an info
//! log. Meanwhile a second client keeps drawing, and its images must keep matching Mesa's.

mod programs;
mod support;
#[path = "bad_input/textures.rs"]
mod textures;

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use programs::harness::{compare, render, render_with, strata_context};
use programs::*;
use strata_client::ClientError;
use strata_protocol::{Blob, Slice, Text};
use support::mesa::MesaGl;
use support::Daemon;

const NO_ERROR: u32 = 0;
const INVALID_ENUM: u32 = 0x0500;
const INVALID_VALUE: u32 = 0x0501;
const INVALID_OPERATION: u32 = 0x0502;
const INVALID_FRAMEBUFFER_OPERATION: u32 = 0x0506;

fn expect(gl: Gl<'_>, what: &str, want: u32) {
    let got = gl.glGetError().expect("glGetError");
    assert_eq!(got, want, "{what}: expected GL error {want:#x}, got {got:#x}");
}

fn misuse(gl: Gl<'_>) -> Result<(), ClientError> {
    let n = &mut Names::default();
    expect(gl, "fresh context", NO_ERROR);

    // Invalid enums and values: the error is recorded and the state is unchanged.
    gl.glEnable(0x1234)?;
    expect(gl, "glEnable(bad)", INVALID_ENUM);
    assert!(!gl.glIsEnabled(DEPTH_TEST)?);
    gl.glDepthFunc(0x9999)?;
    expect(gl, "glDepthFunc(bad)", INVALID_ENUM);
    assert_eq!(gl.glGetIntegerv(0x0B74)?[0], 0x0201, "depth func unchanged");
    gl.glBlendFunc(0x9999, 1)?;
    expect(gl, "glBlendFunc(bad)", INVALID_ENUM);
    gl.glViewport(0, 0, -1, 10)?;
    expect(gl, "glViewport(negative)", INVALID_VALUE);
    assert_eq!(gl.glGetIntegerv(0x0BA2)?[..4], [0, 0, W, H], "viewport unchanged");
    // Only the first error is kept until it is read.
    gl.glCullFace(0x7777)?;
    gl.glLineWidth(-1.0)?;
    expect(gl, "first of two errors", INVALID_ENUM);
    expect(gl, "flag cleared after reading", NO_ERROR);

    // Draw validation.
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 0.0, 0.0, 1.0])?;
    buffer(gl, n, ARRAY_BUFFER, &f32s(&[-1.0, -1.0, 0.0, 1.0, -1.0, 0.0, 0.0, 1.0, 0.0]))?;
    attrib(gl, 0, 3, FLOAT, false, 0, 0)?;
    gl.glDrawArrays(0x77, 0, 3)?;
    expect(gl, "glDrawArrays(bad mode)", INVALID_ENUM);
    gl.glDrawArrays(TRIANGLES, 0, -1)?;
    expect(gl, "glDrawArrays(negative count)", INVALID_VALUE);
    gl.glDrawArrays(TRIANGLES, 0, 300)?;
    expect(gl, "glDrawArrays past the end of the buffer", INVALID_OPERATION);
    gl.glDrawArrays(TRIANGLES, 2, 3)?;
    expect(gl, "glDrawArrays with first past the data", INVALID_OPERATION);
    let idx: Vec<u8> = [0u16, 1, 500].iter().flat_map(|i| i.to_ne_bytes()).collect();
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &idx)?;
    gl.glDrawElements(TRIANGLES, 3, UNSIGNED_SHORT, 0)?;
    expect(gl, "glDrawElements with an index beyond the vertices", INVALID_OPERATION);
    gl.glDrawElements(TRIANGLES, 100, UNSIGNED_SHORT, 0)?;
    expect(gl, "glDrawElements past the end of the index buffer", INVALID_OPERATION);
    gl.glDrawElements(TRIANGLES, 3, UNSIGNED_SHORT, 1 << 40)?;
    expect(gl, "glDrawElements at an absurd offset", INVALID_OPERATION);
    gl.glDrawElements(TRIANGLES, 3, FLOAT, 0)?;
    expect(gl, "glDrawElements(bad type)", INVALID_ENUM);
    gl.glBindBuffer(ELEMENT_ARRAY_BUFFER, 0)?;
    gl.glDrawElements(TRIANGLES, 3, UNSIGNED_SHORT, 0)?;
    expect(gl, "glDrawElements with no index buffer", INVALID_OPERATION);
    gl.glBindBuffer(ARRAY_BUFFER, 0)?;
    gl.glVertexAttribPointer(0, 3, FLOAT, false, 0, 0)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)?;
    expect(gl, "client array without data", INVALID_OPERATION);
    gl.strataVertexAttribData(0, Blob::borrowed(&[0u8; 12]))?;
    gl.glDrawArrays(TRIANGLES, 0, 3)?;
    expect(gl, "client array shorter than the draw", INVALID_OPERATION);

    // Shaders: a malformed one yields an info log, and so does linking it.
    let s = n.next();
    gl.glCreateShader(0x8B30, s)?;
    gl.glShaderSource(s, Text::borrowed("void main() { gl_FragColor = vec4(1.0) }"))?;
    gl.glCompileShader(s)?;
    assert_eq!(gl.glGetShaderiv(s, 0x8B81)?, 0, "compile status");
    assert!(!gl.glGetShaderInfoLog(s)?.is_empty(), "compile log");
    let bad = n.next();
    gl.glCreateProgram(bad)?;
    gl.glAttachShader(bad, s)?;
    gl.glLinkProgram(bad)?;
    assert_eq!(gl.glGetProgramiv(bad, 0x8B82)?, 0, "link status");
    assert!(!gl.glGetProgramInfoLog(bad)?.is_empty(), "link log");
    gl.glUseProgram(bad)?;
    expect(gl, "glUseProgram(unlinked)", INVALID_OPERATION);
    assert_eq!(gl.glGetIntegerv(0x8B8D)?[0], p as i32, "current program unchanged");
    gl.glCompileShader(987_654)?;
    expect(gl, "glCompileShader(unknown)", INVALID_VALUE);
    gl.glAttachShader(bad, bad)?;
    expect(gl, "glAttachShader(program as shader)", INVALID_OPERATION);

    // Uniforms of the wrong type or shape.
    let loc = gl.glGetUniformLocation(p, Text::borrowed("color"))?;
    gl.glUniform1i(loc, 3)?;
    expect(gl, "glUniform1i on a vec4", INVALID_OPERATION);
    gl.glUniform4fv(loc, Slice::new(&[0.0; 8]))?;
    expect(gl, "two vec4s into a non-array", INVALID_OPERATION);
    gl.glUniform4f(loc + 1000, 0.0, 0.0, 0.0, 0.0)?;
    expect(gl, "unknown location", INVALID_OPERATION);
    gl.glUniformMatrix4fv(loc, true, Slice::new(&[0.0; 16]))?;
    expect(gl, "transposed matrix in ES 2.0", INVALID_VALUE);
    gl.glUniform4f(-1, 0.0, 0.0, 0.0, 0.0)?;
    expect(gl, "location -1 is silently ignored", NO_ERROR);

    // Textures and buffers.
    let t = n.next();
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glBindTexture(TEXTURE_CUBE_MAP, t)?;
    expect(gl, "texture rebound to another target", INVALID_OPERATION);
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 2, 2, 1, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&[0; 16])))?;
    expect(gl, "non-zero border", INVALID_VALUE);
    gl.glTexImage2D(TEXTURE_2D, 0, RGB as i32, 2, 2, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&[0; 16])))?;
    expect(gl, "format differs from internal format", INVALID_OPERATION);
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 2, 2, 0, RGBA, FIXED, Some(Blob::borrowed(&[0; 64])))?;
    expect(gl, "GL_FIXED is no texel type", INVALID_ENUM);
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&[0; 16])))?;
    expect(gl, "pixel data shorter than the image", INVALID_OPERATION);
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 1 << 20, 1, 0, RGBA, UNSIGNED_BYTE, None)?;
    expect(gl, "texture beyond the maximum size", INVALID_VALUE);
    buffer(gl, n, ARRAY_BUFFER, &[0; 8])?;
    gl.glBufferSubData(ARRAY_BUFFER, 4, Blob::borrowed(&[0; 8]))?;
    expect(gl, "glBufferSubData past the end", INVALID_VALUE);
    gl.glBufferData(ARRAY_BUFFER, -5, None, STATIC_DRAW)?;
    expect(gl, "negative buffer size", INVALID_VALUE);

    // An incomplete framebuffer refuses to draw or clear.
    let fb = n.next();
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    assert_eq!(gl.glCheckFramebufferStatus(FRAMEBUFFER)?, 0x8CD7, "missing attachment");
    gl.glClear(COLOR_BUFFER_BIT)?;
    expect(gl, "glClear on an incomplete framebuffer", INVALID_FRAMEBUFFER_OPERATION);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;

    // A feedback loop passes GL validation (GL leaves its result undefined) but is a usage
    // conflict for wgpu: the GPU error must be caught and charged to this client.
    let (fb, dt) = (n.next(), n.next());
    gl.glBindTexture(TEXTURE_2D, dt)?;
    gl.glTexImage2D(TEXTURE_2D, 0, 0x1902, 16, 16, 0, 0x1902, UNSIGNED_SHORT, None)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, DEPTH_ATTACHMENT, TEXTURE_2D, dt, 0)?;
    gl.glEnable(DEPTH_TEST)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    textured_quad(gl, n, 0.0, 1.0)?;
    gl.glFinish()?;
    let e = gl.glGetError()?;
    assert!(e == NO_ERROR || e == 0x0505, "feedback loop: unexpected GL error {e:#x}");
    gl.glDisable(DEPTH_TEST)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glFinish()?;

    // Texture formats and the texture-side extensions.
    let mut check = |what: &str, got: u32, want: u32| assert_eq!(got, want, "{what}: got {got:#x}, expected {want:#x}");
    textures::misuse(gl, &mut check)?;
    textures::float_attachment(gl, &mut check)?;
    textures::stale_slice_attachment(gl, &mut check)?;
    gl.glViewport(0, 0, W, H)?;
    Ok(())
}

const OUT_OF_MEMORY: u32 = 0x0505;

/// The RGBA8 pixel at (x, y).
fn pixel(gl: Gl<'_>, x: i32, y: i32) -> [u8; 4] {
    let px = gl.glReadPixels(x, y, 1, 1, RGBA, UNSIGNED_BYTE).expect("glReadPixels").0;
    [px[0], px[1], px[2], px[3]]
}

/// Arguments whose sums and shifts leave the integer range: each is the GL error the
/// specification gives (or is clipped), never an overflow in the daemon, and changes nothing.
fn overflows(gl: Gl<'_>) -> Result<(), ClientError> {
    let n = &mut Names::starting_at(20_000);
    expect(gl, "start", NO_ERROR);
    let red = [255u8, 0, 0, 255].repeat(16);
    texture(gl, n, 4, 4, RGBA, UNSIGNED_BYTE, &red, NEAREST, CLAMP_TO_EDGE)?;
    let px = Blob::borrowed(&[0u8; 64]);
    for level in [32, 40, 14, -1] {
        gl.glTexSubImage2D(TEXTURE_2D, level, 0, 0, 1, 1, RGBA, UNSIGNED_BYTE, px.clone())?;
        expect(gl, &format!("glTexSubImage2D at level {level}"), INVALID_VALUE);
    }
    gl.glTexSubImage2D(TEXTURE_2D, 0, i32::MAX, 0, 2, 1, RGBA, UNSIGNED_BYTE, px.clone())?;
    expect(gl, "glTexSubImage2D with xoffset + width past i32::MAX", INVALID_VALUE);
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, i32::MAX - 1, 1, 4, RGBA, UNSIGNED_BYTE, px.clone())?;
    expect(gl, "glTexSubImage2D with yoffset + height past i32::MAX", INVALID_VALUE);
    gl.glCopyTexSubImage2D(TEXTURE_2D, 0, i32::MAX, 0, 0, 0, 2, 2)?;
    expect(gl, "glCopyTexSubImage2D with xoffset + width past i32::MAX", INVALID_VALUE);
    gl.glCopyTexSubImage2D(TEXTURE_2D, 40, 0, 0, 0, 0, 1, 1)?;
    expect(gl, "glCopyTexSubImage2D at level 40", INVALID_VALUE);
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGBA, 0, 0, i32::MAX, 1, 0)?;
    expect(gl, "glCopyTexImage2D wider than the maximum texture", INVALID_VALUE);
    // A source rectangle far outside the framebuffer: x + width passes i32::MAX; nothing of
    // it lies inside, so nothing is copied.
    gl.glCopyTexSubImage2D(TEXTURE_2D, 0, 0, 0, i32::MAX - 1, i32::MAX - 1, 2, 2)?;
    expect(gl, "glCopyTexSubImage2D from far outside the framebuffer", NO_ERROR);
    // The texture is still red everywhere.
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    textured_quad(gl, n, 0.0, 1.0)?;
    assert_eq!(pixel(gl, W / 2, H / 2), [255, 0, 0, 255], "texture unchanged by the refused updates");

    // A viewport whose x + width passes i32::MAX covers no pixel: the draw changes nothing.
    gl.glViewport(i32::MAX - 2, i32::MIN + 1, 64, 64)?;
    expect(gl, "glViewport far outside", NO_ERROR);
    assert_eq!(gl.glGetIntegerv(0x0BA2)?[..2], [i32::MAX - 2, i32::MIN + 1], "viewport as given");
    gl.glClearColor(0.0, 0.0, 1.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    textured_quad(gl, n, 0.0, 1.0)?;
    expect(gl, "drawing with the far viewport", NO_ERROR);
    assert_eq!(pixel(gl, W / 2, H / 2), [0, 0, 255, 255], "nothing drawn through the far viewport");
    gl.glViewport(0, 0, W, H)?;

    // Attribute pointers whose last element lies past u64: a read past the buffer.
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.0, 1.0, 0.0, 1.0])?;
    buffer(gl, n, ARRAY_BUFFER, &f32s(&quad(-1.0, -1.0, 1.0, 1.0, 0.0)))?;
    for (offset, stride) in [(u64::MAX - 3, 12), (1 << 63, i32::MAX), (u64::MAX, 0)] {
        attrib(gl, 0, 3, FLOAT, false, stride, offset)?;
        gl.glDrawArrays(TRIANGLES, 0, 6)?;
        expect(gl, &format!("draw with attribute offset {offset:#x}, stride {stride}"), INVALID_OPERATION);
        gl.glDrawArrays(0x0000, 0, 6)?;
        expect(gl, &format!("points with attribute offset {offset:#x}, stride {stride}"), INVALID_OPERATION);
    }
    assert_eq!(pixel(gl, W / 2, H / 2), [0, 0, 255, 255], "refused draws drew nothing");
    // Fans and loops of 2^31 vertices from constant attributes: their index lists would need
    // gigabytes, which the daemon refuses to allocate.
    gl.glDisableVertexAttribArray(0)?;
    for mode in [TRIANGLE_FAN, LINE_LOOP] {
        gl.glDrawArrays(mode, 0, i32::MAX)?;
        expect(gl, &format!("mode {mode:#x} with 2^31 vertices"), OUT_OF_MEMORY);
    }
    assert_eq!(pixel(gl, W / 2, H / 2), [0, 0, 255, 255], "refused draws drew nothing");

    // Reads: a rectangle whose x + width passes i32::MAX is clipped to the framebuffer; one
    // larger than any reply can carry is refused.
    let read = gl.glReadPixels(i32::MAX - 1, 0, 4, 1, RGBA, UNSIGNED_BYTE)?.0;
    expect(gl, "glReadPixels past i32::MAX", NO_ERROR);
    assert_eq!(read, vec![0; 16], "pixels outside the framebuffer read as zero");
    let huge = gl.glReadPixels(0, 0, i32::MAX, i32::MAX, RGBA, UNSIGNED_BYTE)?.0;
    expect(gl, "glReadPixels of 2^62 pixels", OUT_OF_MEMORY);
    assert!(huge.is_empty());

    // A uniform array too large for any uniform block fails to link, with a log.
    let vs = "uniform mat4 big[2000000000]; attribute vec4 pos; void main() { gl_Position = big[1] * pos; }";
    let (s1, s2, prog) = (n.next(), n.next(), n.next());
    gl.glCreateShader(0x8B31, s1)?;
    gl.glShaderSource(s1, Text::borrowed(vs))?;
    gl.glCompileShader(s1)?;
    gl.glCreateShader(0x8B30, s2)?;
    gl.glShaderSource(s2, Text::borrowed(FS_COLOR))?;
    gl.glCompileShader(s2)?;
    gl.glCreateProgram(prog)?;
    gl.glAttachShader(prog, s1)?;
    gl.glAttachShader(prog, s2)?;
    gl.glLinkProgram(prog)?;
    assert_eq!(gl.glGetProgramiv(prog, 0x8B82)?, 0, "a 128 GB uniform array does not link");
    assert!(gl.glGetProgramInfoLog(prog)?.contains("uniform"), "the log names the uniforms");
    gl.glClearColor(0.0, 0.0, 0.0, 0.0)?;
    expect(gl, "end", NO_ERROR);
    Ok(())
}

#[test]
fn gl_misuse_records_errors_while_another_client_draws_correctly() {
    let cases = programs::all();
    let case = cases.iter().find(|c| c.name == "many_draws_one_pass").expect("bystander program");
    let expected = match MesaGl::open(W, H).map_err(ClientError::Unsupported).and_then(|mut m| render(&mut m, case)) {
        Ok(e) => e,
        Err(e) if std::env::var_os("STRATA_REQUIRE_ORACLES").is_none() => {
            eprintln!("SKIPPED: Mesa GLES2 unavailable ({e}); install libegl-mesa0 libgles2 to run this test");
            return;
        }
        Err(e) => panic!("Mesa GLES2 unavailable ({e}) and STRATA_REQUIRE_ORACLES is set"),
    };
    let final_case = cases.iter().find(|c| c.name == "triangle_flat").expect("final program");
    let final_expected = MesaGl::open(W, H)
        .map_err(ClientError::Unsupported)
        .and_then(|mut m| render(&mut m, final_case))
        .expect("mesa");

    let daemon = Daemon::start("gles-bad", &[]);
    let socket = daemon.socket.clone();
    let done = Arc::new(AtomicBool::new(false));
    let stop = done.clone();
    let bystander = std::thread::spawn(move || {
        let cases = programs::all();
        let case = cases.iter().find(|c| c.name == "many_draws_one_pass").expect("case");
        let mut rounds = 0;
        while rounds < 3 || !stop.load(Ordering::Acquire) {
            let img =
                strata_context(&socket, "bystander").and_then(|mut c| render(&mut c, case)).expect("bystander render");
            if let Some(why) = compare(case, &img, &expected) {
                panic!("bystander image damaged in round {rounds}: {why}");
            }
            rounds += 1;
        }
        rounds
    });
    let mut gl = strata_context(&daemon.socket, "misuse").expect("misuse client");
    misuse(&mut gl).expect("misuse sequence");
    overflows(&mut gl).expect("overflow sequence");
    // The misbehaving client itself still renders correctly afterwards.
    let img = render_with(&mut gl, final_case, &mut Names::starting_at(50_000)).expect("final render");
    assert!(compare(final_case, &img, &final_expected).is_none(), "misuse client's later rendering differs from Mesa");
    done.store(true, Ordering::Release);
    let rounds = bystander.join().expect("bystander");
    assert!(rounds >= 3);
    daemon.wait_log("name=misuse role=app}: strata_gles::state: GPU validation error charged to this client");
    assert!(!daemon.log_text().contains("panicked"), "daemon panicked:\n{}", daemon.log_text());
}

/// The limits `glGetIntegerv` advertises meet ES 2.0's minimums and are real: a program that
/// uses every attribute, varying, sampler and uniform vector it claims links and draws.
#[test]
fn advertised_limits_are_es2_minimums_and_usable() {
    let daemon = Daemon::start("limits", &[]);
    let mut c = strata_context(&daemon.socket, "limits").expect("context");
    let gl: Gl<'_> = &mut c;
    let get = |gl: Gl<'_>, pname: u32| gl.glGetIntegerv(pname).expect("glGetIntegerv")[0];
    let attribs = get(gl, 0x8869);
    let varyings = get(gl, 0x8DFC);
    let units = get(gl, 0x8872);
    let vertex_vectors = get(gl, 0x8DFB);
    for (what, have, min) in [
        ("MAX_VERTEX_ATTRIBS", attribs, 8),
        ("MAX_VARYING_VECTORS", varyings, 8),
        ("MAX_TEXTURE_IMAGE_UNITS", units, 8),
        ("MAX_COMBINED_TEXTURE_IMAGE_UNITS", get(gl, 0x8B4D), 8),
        ("MAX_VERTEX_UNIFORM_VECTORS", vertex_vectors, 128),
        ("MAX_FRAGMENT_UNIFORM_VECTORS", get(gl, 0x8DFD), 16),
        ("MAX_TEXTURE_SIZE", get(gl, 0x0D33), 64),
        ("MAX_CUBE_MAP_TEXTURE_SIZE", get(gl, 0x851C), 16),
        ("MAX_RENDERBUFFER_SIZE", get(gl, 0x84E8), 1),
    ] {
        assert!(have >= min, "{what} is {have}, below ES 2.0's minimum {min}");
    }
    let version = gl.glGetString(0x1F02).expect("version").unwrap_or_default();
    assert!(version.starts_with("OpenGL ES 2.0"), "{version}");
    let glsl = gl.glGetString(0x8B8C).expect("glsl").unwrap_or_default();
    assert!(glsl.starts_with("OpenGL ES GLSL ES 1.00"), "{glsl}");

    // One program at every limit at once.
    let names: Vec<String> = (0..attribs).map(|i| format!("a{i}")).collect();
    let mut vs = String::new();
    for n in &names {
        vs.push_str(&format!("attribute vec4 {n};\n"));
    }
    for i in 0..varyings {
        vs.push_str(&format!("varying vec4 v{i};\n"));
    }
    vs.push_str(&format!(
        "uniform vec4 big[{}];\nvoid main() {{\n    vec4 s = big[{}];\n",
        vertex_vectors - 8,
        vertex_vectors - 9
    ));
    for n in &names {
        vs.push_str(&format!("    s += {n} * 0.001;\n"));
    }
    for i in 0..varyings {
        vs.push_str(&format!("    v{i} = s * {}.0;\n", i + 1));
    }
    vs.push_str("    gl_Position = vec4(a0.xy, 0.0, 1.0);\n}\n");
    let mut fs = String::from("precision mediump float;\n");
    for i in 0..varyings {
        fs.push_str(&format!("varying vec4 v{i};\n"));
    }
    for i in 0..units {
        fs.push_str(&format!("uniform sampler2D t{i};\n"));
    }
    fs.push_str("void main() {\n    vec4 c = vec4(0.0);\n");
    for i in 0..varyings {
        fs.push_str(&format!("    c += v{i} * 0.01;\n"));
    }
    for i in 0..units {
        fs.push_str(&format!("    c += texture2D(t{i}, vec2(0.5)) * 0.01;\n"));
    }
    fs.push_str("    gl_FragColor = c;\n}\n");
    let n = &mut Names::default();
    let attrib_refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let p = program(gl, n, &vs, &fs, &attrib_refs).expect("a program at every advertised limit links");
    for i in 0..units {
        let l = gl.glGetUniformLocation(p, Text::borrowed(&format!("t{i}"))).expect("loc");
        gl.glUniform1i(l, i).expect("unit");
    }
    buffer(gl, n, ARRAY_BUFFER, &f32s(&quad(-1.0, -1.0, 1.0, 1.0, 0.0))).expect("buffer");
    attrib(gl, 0, 3, FLOAT, false, 0, 0).expect("attrib");
    gl.glDrawArrays(TRIANGLES, 0, 6).expect("draw");
    gl.glFinish().expect("finish");
    expect(gl, "drawing at every limit", NO_ERROR);
}
