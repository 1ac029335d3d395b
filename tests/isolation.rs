//! One client can never read, name or change another client's objects, segment or surfaces.
//!
//! Client A creates every kind of GL object (textures, buffers, a renderbuffer, framebuffers,
//! shaders, programs, including a shader and a program with non-empty info logs), a context, a
//! pbuffer and a window surface, and draws a known colour. Client B, on its own connection to
//! the same daemon, guesses: every name in 1..=64 of every object kind, and every EGL handle in
//! 1..=64. It must see none of A's objects (the `glIs*` queries are false, sources and logs are
//! empty), binding a guessed name must give B an empty object of its own (an FBO over a guessed
//! texture or renderbuffer is incomplete, sampling a guessed texture or reading a guessed
//! framebuffer never yields A's colour), and A's EGL handles must be invalid for B or name B's
//! own objects. B then deletes and destroys everything it guessed, and A's objects must be
//! intact. A's segment reaches A only as a descriptor: it never has a name, cannot be resized,
//! and the daemon holds no descriptor of it once A has mapped it (docs/security.md).

mod support;

use std::io::Write;
use std::os::unix::net::UnixStream;
use std::time::Duration;

use strata_client::{Calls, ClientError, ConnectOptions, Connection};
use strata_protocol::handshake::{self, ClientMessage, Hello, Purpose, ServerMessage, PROTOCOL_VERSION};
use strata_protocol::segment::Segment;
use strata_protocol::{Blob, Slice, Text};
use support::Daemon;

type R<T = ()> = Result<T, ClientError>;

const EGL_NONE: i32 = 0x3038;
const EGL_BAD_CONTEXT: i32 = 0x3006;
const EGL_BAD_SURFACE: i32 = 0x300D;
const EGL_WIDTH: i32 = 0x3057;
const EGL_HEIGHT: i32 = 0x3056;
const TEXTURE_2D: u32 = 0x0DE1;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;
const FLOAT: u32 = 0x1406;
const ARRAY_BUFFER: u32 = 0x8892;
const STATIC_DRAW: u32 = 0x88E4;
const BUFFER_SIZE: u32 = 0x8764;
const FRAMEBUFFER: u32 = 0x8D40;
const RENDERBUFFER: u32 = 0x8D41;
const RENDERBUFFER_WIDTH: u32 = 0x8D42;
const RGB565: u32 = 0x8D62;
const COLOR_ATTACHMENT0: u32 = 0x8CE0;
const FRAMEBUFFER_COMPLETE: u32 = 0x8CD5;
const COLOR_BUFFER_BIT: u32 = 0x4000;
const TRIANGLE_STRIP: u32 = 0x0005;
const FRAGMENT_SHADER: u32 = 0x8B30;
const TEXTURE_MIN_FILTER: u32 = 0x2801;
const TEXTURE_MAG_FILTER: u32 = 0x2800;
const NEAREST: i32 = 0x2600;

/// The colour A draws everywhere; B must never read it.
const A_COLOUR: [u8; 4] = [17, 211, 87, 255];
/// B's own clear colour.
const B_COLOUR: [u8; 4] = [250, 5, 130, 255];
/// The names and handles B guesses.
const GUESSES: std::ops::RangeInclusive<u32> = 1..=64;

const VS: &str = "attribute vec2 pos; varying vec2 uv;
void main() { uv = pos * 0.5 + 0.5; gl_Position = vec4(pos, 0.0, 1.0); }";
const FS: &str = "precision mediump float; uniform sampler2D tex; varying vec2 uv;
void main() { gl_FragColor = texture2D(tex, uv); }";

/// A's handles and names: what B guesses at.
struct AObjects {
    display: u32,
    pbuffer: u32,
    window: u32,
    context: u32,
}

fn egl<T>(r: R<Result<T, i32>>, what: &str) -> T {
    match r {
        Ok(Ok(v)) => v,
        Ok(Err(e)) => panic!("{what}: EGL error {e:#x}"),
        Err(e) => panic!("{what}: {e}"),
    }
}

fn connect(socket: &std::path::Path, name: &str) -> Connection {
    let opts = ConnectOptions { socket: socket.to_path_buf(), name: name.into(), ..ConnectOptions::default() };
    Connection::connect(&opts).unwrap_or_else(|e| panic!("{name}: connect: {e}"))
}

/// Initialises EGL and picks an RGBA8 config for pbuffers and windows.
fn display_and_config(c: &mut Connection) -> R<(u32, u32)> {
    let d = c.eglGetDisplay(0)?;
    egl(c.eglInitialize(d), "eglInitialize");
    let attribs = [0x3033, 0x0005, 0x3040, 4, 0x3024, 8, 0x3023, 8, 0x3022, 8, 0x3021, 8, EGL_NONE];
    let configs = egl(c.eglChooseConfig(d, Slice::new(&attribs), 1), "eglChooseConfig");
    Ok((d, *configs.first().expect("a config")))
}

/// The pixel at (0, 0) of the bound framebuffer (empty when it cannot be read).
fn pixel(c: &mut Connection) -> R<Vec<u8>> {
    Ok(c.glReadPixels(0, 0, 1, 1, RGBA, UNSIGNED_BYTE)?.0)
}

/// Compiles and links `vs` and `fs` into `(program, vertex shader, fragment shader)` with
/// `pos` at location 0, and a strip covering the viewport in buffer `quad`.
fn textured_quad(c: &mut Connection, names: (u32, u32, u32), quad: u32) -> R {
    strata_client::setup::link_program(c, names, VS, FS, &["pos"])?;
    let strip: Vec<u8> = [-1f32, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0].iter().flat_map(|f| f.to_le_bytes()).collect();
    c.glGenBuffers(Slice::new(&[quad]))?;
    c.glBindBuffer(ARRAY_BUFFER, quad)?;
    c.glBufferData(ARRAY_BUFFER, strip.len() as i64, Some(Blob::borrowed(&strip)), STATIC_DRAW)?;
    c.glVertexAttribPointer(0, 2, FLOAT, false, 0, 0)?;
    c.glEnableVertexAttribArray(0)
}

/// A 4x4 texture filled with `rgba`, sampled nearest.
fn solid_texture(c: &mut Connection, name: u32, rgba: [u8; 4]) -> R {
    c.glBindTexture(TEXTURE_2D, name)?;
    let texels = rgba.repeat(16);
    let data = Some(Blob::borrowed(&texels));
    c.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, data)?;
    c.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    c.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)
}

/// Client A: every kind of object, holding or drawing `A_COLOUR`.
fn build_a(a: &mut Connection) -> R<AObjects> {
    let (display, config) = display_and_config(a)?;
    let pbuffer = egl(
        a.eglCreatePbufferSurface(display, config, Slice::new(&[EGL_WIDTH, 32, EGL_HEIGHT, 32, EGL_NONE])),
        "A pbuffer",
    );
    let window =
        egl(a.eglCreateWindowSurface(display, config, 0, 0, 0, 0.0, 24, 24, Slice::new(&[EGL_NONE])), "A window");
    let context = egl(a.eglCreateContext(display, config, 0, Slice::new(&[0x3098, 2, EGL_NONE])), "A context");
    egl(a.eglMakeCurrent(display, window, window, context), "A current (window)");
    a.glClearColor(0.1, 0.2, 0.3, 1.0)?;
    a.glClear(COLOR_BUFFER_BIT)?;
    egl(a.eglSwapBuffers(display, window), "A swap");
    egl(a.eglMakeCurrent(display, pbuffer, pbuffer, context), "A current (pbuffer)");
    // Textures 1..=3, buffers 1 (a quad) and 2, shaders 1 and 2 in program 3.
    a.glGenTextures(Slice::new(&[1, 2, 3]))?;
    for t in [1, 2, 3] {
        solid_texture(a, t, A_COLOUR)?;
    }
    textured_quad(a, (3, 1, 2), 1)?;
    a.glGenBuffers(Slice::new(&[2]))?;
    a.glBindBuffer(ARRAY_BUFFER, 2)?;
    a.glBufferData(ARRAY_BUFFER, 64, Some(Blob::borrowed(&[0xA5; 64])), STATIC_DRAW)?;
    a.glBindBuffer(ARRAY_BUFFER, 1)?;
    // Shader 4 fails to compile and program 5 fails to link: both have info logs.
    a.glCreateShader(FRAGMENT_SHADER, 4)?;
    a.glShaderSource(4, Text::borrowed("this is not GLSL"))?;
    a.glCompileShader(4)?;
    a.glCreateProgram(5)?;
    a.glLinkProgram(5)?;
    assert!(!a.glGetShaderInfoLog(4)?.is_empty() && !a.glGetProgramInfoLog(5)?.is_empty(), "A has info logs");
    // Renderbuffer 1 behind framebuffer 2; texture 2 behind framebuffer 1.
    a.glGenRenderbuffers(Slice::new(&[1]))?;
    a.glBindRenderbuffer(RENDERBUFFER, 1)?;
    a.glRenderbufferStorage(RENDERBUFFER, RGB565, 32, 32)?;
    a.glGenFramebuffers(Slice::new(&[1, 2]))?;
    a.glBindFramebuffer(FRAMEBUFFER, 2)?;
    a.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, 1)?;
    a.glBindFramebuffer(FRAMEBUFFER, 1)?;
    a.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, 2, 0)?;
    for fb in [1, 2] {
        a.glBindFramebuffer(FRAMEBUFFER, fb)?;
        assert_eq!(a.glCheckFramebufferStatus(FRAMEBUFFER)?, FRAMEBUFFER_COMPLETE, "A's framebuffer {fb}");
        a.glClearColor(
            f32::from(A_COLOUR[0]) / 255.0,
            f32::from(A_COLOUR[1]) / 255.0,
            f32::from(A_COLOUR[2]) / 255.0,
            1.0,
        )?;
        a.glClear(COLOR_BUFFER_BIT)?;
    }
    a.glBindFramebuffer(FRAMEBUFFER, 0)?;
    assert_a_intact(a)?;
    assert_eq!(a.glGetError()?, 0, "A's set-up raised a GL error");
    Ok(AObjects { display, pbuffer, window, context })
}

/// A still has its objects: texture 1 drawn with program 3 gives its colour, framebuffer 1
/// holds it, and its names still exist.
fn assert_a_intact(a: &mut Connection) -> R {
    a.glBindFramebuffer(FRAMEBUFFER, 0)?;
    a.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    a.glClear(COLOR_BUFFER_BIT)?;
    a.glUseProgram(3)?;
    a.glBindBuffer(ARRAY_BUFFER, 1)?;
    a.glVertexAttribPointer(0, 2, FLOAT, false, 0, 0)?;
    a.glBindTexture(TEXTURE_2D, 1)?;
    a.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    assert_eq!(pixel(a)?, A_COLOUR, "A's texture 1 drawn with A's program 3");
    a.glBindFramebuffer(FRAMEBUFFER, 1)?;
    assert_eq!(pixel(a)?, A_COLOUR, "A's framebuffer 1");
    a.glBindFramebuffer(FRAMEBUFFER, 0)?;
    let exists = [
        a.glIsTexture(3)?,
        a.glIsBuffer(2)?,
        a.glIsRenderbuffer(1)?,
        a.glIsFramebuffer(2)?,
        a.glIsShader(4)?,
        a.glIsProgram(5)?,
    ];
    assert_eq!(exists, [true; 6], "A's objects exist");
    assert_eq!(a.glGetShaderSource(1)?, VS, "A's vertex shader source");
    Ok(())
}

/// B's EGL guesses at A's handles, before and after it has objects of its own.
fn probe_egl(b: &mut Connection, a: &AObjects) -> R<(u32, u32)> {
    let (d, config) = display_and_config(b)?;
    assert_eq!(d, a.display, "both clients' displays are their own display 1");
    for h in GUESSES {
        assert_eq!(b.eglQuerySurface(d, h, EGL_WIDTH)?, Err(EGL_BAD_SURFACE), "B queries surface {h}");
        assert_eq!(b.eglMakeCurrent(d, h, h, h)?, Err(EGL_BAD_SURFACE), "B makes {h} current");
        assert_eq!(b.eglSwapBuffers(d, h)?, Err(EGL_BAD_SURFACE), "B swaps surface {h}");
        assert_eq!(b.eglDestroySurface(d, h)?, Err(EGL_BAD_SURFACE), "B destroys surface {h}");
        assert_eq!(b.eglDestroyContext(d, h)?, Err(EGL_BAD_CONTEXT), "B destroys context {h}");
    }
    let surface =
        egl(b.eglCreatePbufferSurface(d, config, Slice::new(&[EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE])), "B pbuffer");
    for h in GUESSES.filter(|&h| h != surface) {
        assert_eq!(b.eglMakeCurrent(d, surface, surface, h)?, Err(EGL_BAD_CONTEXT), "B makes context {h} current");
        assert_eq!(b.eglQuerySurface(d, h, EGL_WIDTH)?, Err(EGL_BAD_SURFACE), "B queries surface {h}");
    }
    // Where B's pbuffer has the same handle as one of A's surfaces, it is B's: B's size.
    assert_eq!(b.eglQuerySurface(d, surface, EGL_WIDTH)?, Ok(16), "B's own pbuffer");
    for h in [a.pbuffer, a.window] {
        if let Ok(w) = b.eglQuerySurface(d, h, EGL_WIDTH)? {
            assert_eq!((h, w), (surface, 16), "A's surface {h} seen by B");
        }
    }
    let context = egl(b.eglCreateContext(d, config, 0, Slice::new(&[0x3098, 2, EGL_NONE])), "B context");
    for h in GUESSES.filter(|&h| h != context) {
        assert_eq!(b.eglMakeCurrent(d, surface, surface, h)?, Err(EGL_BAD_CONTEXT), "B makes context {h} current");
    }
    egl(b.eglMakeCurrent(d, surface, surface, context), "B current");
    Ok((d, surface))
}

/// B's GL guesses at A's names: nothing of A's can be seen, bound, sampled or read.
fn probe_gl(b: &mut Connection) -> R {
    for n in GUESSES {
        let seen = [
            b.glIsTexture(n)?,
            b.glIsBuffer(n)?,
            b.glIsRenderbuffer(n)?,
            b.glIsFramebuffer(n)?,
            b.glIsShader(n)?,
            b.glIsProgram(n)?,
        ];
        assert_eq!(
            seen, [false; 6],
            "B sees A's name {n} (texture, buffer, renderbuffer, framebuffer, shader, program)"
        );
        assert_eq!(b.glGetShaderSource(n)?, "", "B reads shader {n}'s source");
        assert_eq!(b.glGetShaderInfoLog(n)?, "", "B reads shader {n}'s log");
        assert_eq!(b.glGetProgramInfoLog(n)?, "", "B reads program {n}'s log");
        assert_eq!(b.glGetAttachedShaders(n)?, Vec::<u32>::new(), "B lists program {n}'s shaders");
        assert_eq!(b.glGetUniformLocation(n, Text::borrowed("tex"))?, -1, "B finds program {n}'s uniform");
        assert_eq!(b.glGetAttribLocation(n, Text::borrowed("pos"))?, -1, "B finds program {n}'s attribute");
    }
    b.glGetError()?;
    // B's own program and quad, under names far from the guesses.
    textured_quad(b, (1003, 1001, 1002), 1000)?;
    b.glGenFramebuffers(Slice::new(&[1004]))?;
    for n in GUESSES {
        // Sampling texture n draws B's empty texture: never A's colour.
        b.glBindFramebuffer(FRAMEBUFFER, 0)?;
        b.glClearColor(
            f32::from(B_COLOUR[0]) / 255.0,
            f32::from(B_COLOUR[1]) / 255.0,
            f32::from(B_COLOUR[2]) / 255.0,
            1.0,
        )?;
        b.glClear(COLOR_BUFFER_BIT)?;
        b.glBindTexture(TEXTURE_2D, n)?;
        b.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
        let px = pixel(b)?;
        assert!(px.len() == 4 && px != A_COLOUR, "B sampling texture {n} read {px:?}");
        // Texture n as B's colour attachment: no image, so incomplete.
        b.glBindFramebuffer(FRAMEBUFFER, 1004)?;
        b.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, n, 0)?;
        assert_ne!(b.glCheckFramebufferStatus(FRAMEBUFFER)?, FRAMEBUFFER_COMPLETE, "B's FBO over texture {n}");
        assert_ne!(pixel(b)?, A_COLOUR, "B reads texture {n} through an FBO");
        // Renderbuffer n: no storage.
        b.glBindRenderbuffer(RENDERBUFFER, n)?;
        assert_eq!(b.glGetRenderbufferParameteriv(RENDERBUFFER, RENDERBUFFER_WIDTH)?, 0, "B's renderbuffer {n}");
        b.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, n)?;
        assert_ne!(b.glCheckFramebufferStatus(FRAMEBUFFER)?, FRAMEBUFFER_COMPLETE, "B's FBO over renderbuffer {n}");
        // Framebuffer n: no attachments.
        b.glBindFramebuffer(FRAMEBUFFER, n)?;
        assert_ne!(b.glCheckFramebufferStatus(FRAMEBUFFER)?, FRAMEBUFFER_COMPLETE, "B's framebuffer {n}");
        assert_ne!(pixel(b)?, A_COLOUR, "B reads framebuffer {n}");
        // Buffer n: no data.
        b.glBindBuffer(ARRAY_BUFFER, n)?;
        assert_eq!(b.glGetBufferParameteriv(ARRAY_BUFFER, BUFFER_SIZE)?, 0, "B's buffer {n}");
        b.glGetError()?;
    }
    // B deletes every name it guessed; A's objects must not notice.
    let all: Vec<u32> = GUESSES.collect();
    b.glBindFramebuffer(FRAMEBUFFER, 0)?;
    b.glDeleteTextures(Slice::new(&all))?;
    b.glDeleteBuffers(Slice::new(&all))?;
    b.glDeleteRenderbuffers(Slice::new(&all))?;
    b.glDeleteFramebuffers(Slice::new(&all))?;
    for n in GUESSES {
        b.glDeleteShader(n)?;
        b.glDeleteProgram(n)?;
    }
    b.glGetError()?;
    Ok(())
}

/// The daemon's descriptors of segments: memory files, or names in `/dev/shm`.
fn daemon_segments(daemon: &Daemon) -> Vec<String> {
    let dir = format!("/proc/{}/fd", daemon.child.id());
    std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .filter_map(|e| std::fs::read_link(e.ok()?.path()).ok())
        .map(|l| l.to_string_lossy().into_owned())
        .filter(|l| l.starts_with("/memfd:strata") || l.starts_with("/dev/shm/strata"))
        .collect()
}

/// A handshake by hand: the segment arrives as one descriptor attached to the welcome, an
/// anonymous memory file sealed against resizing, which the daemon stops holding once the
/// client says it mapped it.
fn check_raw_segment(daemon: &Daemon) {
    use std::os::fd::AsRawFd;
    let mut stream = UnixStream::connect(&daemon.socket).expect("connect");
    stream.set_read_timeout(Some(Duration::from_secs(10))).expect("timeout");
    stream.write_all(&handshake::preamble(PROTOCOL_VERSION)).expect("preamble");
    let hello =
        Hello { name: "iso-raw".into(), role: "raw".into(), placement: None, tally: false, purpose: Purpose::Render };
    handshake::write_message(&mut stream, &hello).expect("hello");
    let (ServerMessage::Welcome { cmd_capacity, reply_capacity, .. }, fds) =
        handshake::read_message_with_fds(&stream, "welcome").expect("welcome")
    else {
        panic!("refused");
    };
    assert_eq!(fds.len(), 1, "the welcome carries exactly the segment");
    let fd = fds.into_iter().next().expect("fd");
    let link = std::fs::read_link(format!("/proc/self/fd/{}", fd.as_raw_fd())).expect("the descriptor's link");
    let link = link.to_string_lossy();
    assert!(link.starts_with("/memfd:strata-segment"), "the segment is {link}, not an anonymous memory file");
    // SAFETY: ftruncate on our own descriptor; the seal must refuse it.
    let shrunk = unsafe { libc::ftruncate(fd.as_raw_fd(), 4096) };
    let err = std::io::Error::last_os_error();
    assert!(shrunk < 0 && err.raw_os_error() == Some(libc::EPERM), "the client could shrink its segment: {err}");
    let mapped = Segment::open(fd, cmd_capacity, reply_capacity).expect("the client maps its segment");
    assert!(!daemon_segments(daemon).is_empty(), "the daemon holds the segment until the client has mapped it");
    handshake::write_message(&mut stream, &ClientMessage::Mapped).expect("mapped");
    daemon.wait_log("name=iso-raw");
    let deadline = std::time::Instant::now() + Duration::from_secs(10);
    while !daemon_segments(daemon).is_empty() && std::time::Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(20));
    }
    assert_eq!(daemon_segments(daemon), Vec::<String>::new(), "the daemon still holds descriptors of segments");
    mapped.command_ring().expect("the client's own mapping stays valid");
}

#[test]
fn a_client_cannot_reach_another_clients_objects_segment_or_surfaces() {
    let daemon = Daemon::start("isolation", &["--output", "t=64x64"]);
    let mut a = connect(&daemon.socket, "iso-a");
    let a_objects = build_a(&mut a).expect("client A");
    let mut b = connect(&daemon.socket, "iso-b");
    probe_egl(&mut b, &a_objects).expect("client B's EGL guesses");
    probe_gl(&mut b).expect("client B's GL guesses");
    assert_a_intact(&mut a).expect("A after B's guesses and deletions");
    assert_eq!(a.glGetError().expect("A's glGetError"), 0, "A's state after B's guesses");
    let (d, pbuffer, window) = (a_objects.display, a_objects.pbuffer, a_objects.window);
    assert_eq!(egl(a.eglQuerySurface(d, pbuffer, EGL_WIDTH), "A's pbuffer after B"), 32);
    assert_eq!(egl(a.eglQuerySurface(d, window, EGL_WIDTH), "A's window after B"), 24);
    egl(a.eglMakeCurrent(d, window, window, a_objects.context), "A's window and context after B");
    egl(a.eglSwapBuffers(d, window), "A swaps its window after B");

    // A and B mapped theirs: the daemon holds no descriptor of either, and no name.
    assert_eq!(daemon_segments(&daemon), Vec::<String>::new(), "the daemon holds descriptors of segments");
    check_raw_segment(&daemon);
}
