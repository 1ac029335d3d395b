//! EGLImages (`GL_OES_EGL_image`) of a level above 0 and of a cube face, on Strata: what
//! Mesa cannot be compared on (`tests/client_calls/egl_image.rs` compares everything else).
//! Mesa writes an upload through a texture of a level-1 image elsewhere, and takes a cube
//! face's image into no texture; here the results are checked against the data uploaded: an
//! upload through a sibling of a level-1 image lands in that level of the source, and a clear
//! of a renderbuffer made from a cube face lands in that face.

mod programs;
mod support;

use programs::harness::strata_context;
use strata_client::Calls;
use strata_protocol::{Blob, Slice};
use support::Daemon;

const TEXTURE_2D: u32 = 0x0DE1;
const TEXTURE_CUBE_MAP: u32 = 0x8513;
const CUBE_POSITIVE_X: u32 = 0x8515;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;
const FRAMEBUFFER: u32 = 0x8D40;
const RENDERBUFFER: u32 = 0x8D41;
const COLOR_ATTACHMENT0: u32 = 0x8CE0;
const EGL_GL_TEXTURE_2D: i32 = 0x30B1;
const EGL_GL_CUBE_POSITIVE_Z: i32 = 0x30B7;
const EGL_TEXTURE_LEVEL: i32 = 0x30BC;
const NONE: i32 = 0x3038;

/// `w`×`h` RGBA texels, each a function of its position and `seed`.
fn texels(w: usize, h: usize, seed: u8) -> Vec<u8> {
    (0..w * h).flat_map(|i| [(i * 37) as u8 ^ seed, (i * 11 + 60) as u8, seed, 255]).collect()
}

#[test]
fn siblings_write_the_level_and_face_of_their_image() {
    let daemon = Daemon::start("egl-image", &[]);
    let mut c = strata_context(&daemon.socket, "egl-image").expect("context");
    let gl = &mut c;
    // A second context, whose handle the test needs for eglCreateImageKHR.
    let configs = gl.eglChooseConfig(1, Slice::new(&[0x3040, 4, NONE]), 1).expect("call").expect("configs");
    let ctx = gl.eglCreateContext(1, configs[0], 0, Slice::new(&[0x3098, 2, NONE])).expect("call").expect("context");
    let surface = gl.eglCreatePbufferSurface(1, configs[0], Slice::new(&[0x3057, 8, 0x3056, 8, NONE]));
    let surface = surface.expect("call").expect("pbuffer");
    gl.eglMakeCurrent(1, surface, surface, ctx).expect("call").expect("current");

    // A: an 8×8 mip chain; the image is its level 1.
    let names = [1u32, 2, 3, 4];
    gl.glGenTextures(Slice::new(&names)).expect("call");
    gl.glBindTexture(TEXTURE_2D, 1).expect("call");
    let mut levels = Vec::new();
    for (level, size) in [8usize, 4, 2, 1].into_iter().enumerate() {
        let data = texels(size, size, 10 + level as u8);
        gl.glTexImage2D(
            TEXTURE_2D,
            level as i32,
            RGBA as i32,
            size as i32,
            size as i32,
            0,
            RGBA,
            UNSIGNED_BYTE,
            Some(Blob::borrowed(&data)),
        )
        .expect("call");
        levels.push(data);
    }
    let image = gl.eglCreateImageKHR(1, ctx, EGL_GL_TEXTURE_2D, 1, Slice::new(&[EGL_TEXTURE_LEVEL, 1, NONE]));
    let image = image.expect("call").expect("an image of level 1");
    // Texture 2 is made from it; a 2×2 upload at (1, 1) goes through it.
    gl.glBindTexture(TEXTURE_2D, 2).expect("call");
    gl.glEGLImageTargetTexture2DOES(TEXTURE_2D, image).expect("call");
    let patch = texels(2, 2, 200);
    gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 1, 2, 2, RGBA, UNSIGNED_BYTE, Blob::borrowed(&patch)).expect("call");
    assert_eq!(gl.glGetError().expect("call"), 0);
    let mut want = levels[1].clone();
    for (y, x) in [(1, 1), (1, 2), (2, 1), (2, 2)] {
        let from = ((y - 1) * 2 + (x - 1)) * 4;
        want[(y * 4 + x) * 4..][..4].copy_from_slice(&patch[from..from + 4]);
    }
    // A's level 1 through a framebuffer attachment, and the sibling's level 0.
    gl.glGenFramebuffers(Slice::new(&[5])).expect("call");
    gl.glBindFramebuffer(FRAMEBUFFER, 5).expect("call");
    for (texture, level, what) in [(1, 1, "A level 1"), (2, 0, "the sibling")] {
        gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, texture, level).expect("call");
        let read = gl.glReadPixels(0, 0, 4, 4, RGBA, UNSIGNED_BYTE).expect("read");
        assert_eq!(read.0, want, "{what} after the upload through the sibling");
    }
    // A's other levels are untouched.
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, 1, 0).expect("call");
    assert_eq!(gl.glReadPixels(0, 0, 8, 8, RGBA, UNSIGNED_BYTE).expect("read").0, levels[0], "A level 0");

    // C: a 4×4 cube; a renderbuffer is made from face +Z and cleared in part.
    gl.glBindTexture(TEXTURE_CUBE_MAP, 3).expect("call");
    let faces: Vec<Vec<u8>> = (0..6).map(|f| texels(4, 4, 50 + f as u8)).collect();
    for (f, data) in faces.iter().enumerate() {
        gl.glTexImage2D(
            CUBE_POSITIVE_X + f as u32,
            0,
            RGBA as i32,
            4,
            4,
            0,
            RGBA,
            UNSIGNED_BYTE,
            Some(Blob::borrowed(data)),
        )
        .expect("call");
    }
    let image = gl.eglCreateImageKHR(1, ctx, EGL_GL_CUBE_POSITIVE_Z, 3, Slice::new(&[NONE]));
    let image = image.expect("call").expect("an image of face +Z");
    gl.glGenRenderbuffers(Slice::new(&[6])).expect("call");
    gl.glBindRenderbuffer(RENDERBUFFER, 6).expect("call");
    gl.glEGLImageTargetRenderbufferStorageOES(RENDERBUFFER, image).expect("call");
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, 6).expect("call");
    assert_eq!(gl.glReadPixels(0, 0, 4, 4, RGBA, UNSIGNED_BYTE).expect("read").0, faces[4], "face +Z");
    gl.glEnable(0x0C11).expect("call");
    gl.glScissor(0, 0, 2, 4).expect("call");
    gl.glClearColor(1.0, 0.0, 0.0, 1.0).expect("call");
    gl.glClear(0x4000).expect("call");
    gl.glDisable(0x0C11).expect("call");
    let mut want = faces[4].clone();
    for y in 0..4 {
        for x in 0..2 {
            want[(y * 4 + x) * 4..][..4].copy_from_slice(&[255, 0, 0, 255]);
        }
    }
    for (f, data) in faces.iter().enumerate() {
        gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, CUBE_POSITIVE_X + f as u32, 3, 0).expect("call");
        let read = gl.glReadPixels(0, 0, 4, 4, RGBA, UNSIGNED_BYTE).expect("read").0;
        assert_eq!(&read, if f == 4 { &want } else { data }, "cube face {f} after the renderbuffer's clear");
    }
    assert_eq!(gl.glGetError().expect("call"), 0);
}
