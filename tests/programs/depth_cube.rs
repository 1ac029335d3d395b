//! `GL_OES_depth_texture_cube_map`: a depth cube map, each face uploaded with its own depths,
//! sampled through `textureCube` in a tile per face; one face then rendered into as a
//! framebuffer's depth (cleared, drawn, read back with `GL_NV_read_depth`) and sampled again;
//! a packed depth-stencil face, and the errors of formats and sizes, as colours. (A cube of
//! faces of different depth types, and levels above 0, which Mesa takes, are left out: see
//! docs/architecture.md.)

use super::multi_draw::mark_all;
use super::*;

const DEPTH_COMPONENT: u32 = 0x1902;
const DEPTH_STENCIL: u32 = 0x84F9;
const UNSIGNED_INT_24_8: u32 = 0x84FA;
const ALWAYS: u32 = 0x0207;

/// A cube direction per face from the tile's coordinates.
const VS: &str = "attribute vec4 pos; attribute vec4 col; varying vec3 d;
    void main() { d = col.xyz; gl_Position = pos; }";
const FS: &str = "precision highp float; uniform samplerCube s; varying vec3 d;
    void main() { float z = textureCube(s, d).r; gl_FragColor = vec4(z, 1.0 - z, z * z, 1.0); }";
/// A constant colour for drawing into the face's framebuffer.
const FS_FLAT: &str = "precision mediump float; varying vec3 d; void main() { gl_FragColor = vec4(d, 1.0); }";

/// The depths of face `face`, `size`×`size`, as `GL_UNSIGNED_INT`: a gradient across the
/// face, offset per face.
fn depths(face: u32, size: usize) -> Vec<u8> {
    (0..size * size)
        .flat_map(|i| {
            let v =
                (face as f64 * 0.15 + (i % size) as f64 / size as f64 * 0.1 + (i / size) as f64 / size as f64 * 0.04)
                    .min(1.0);
            ((v * 4_294_967_295.0) as u32).to_ne_bytes()
        })
        .collect()
}

/// Draws the six tiles, one per face, each mapping its square onto that face's directions.
fn tiles(gl: Gl<'_>, n: &mut Names) -> R {
    for face in 0..6u32 {
        let (x0, y0) = (-1.0 + (face % 3) as f32 * 0.6, -1.0 + (face / 3) as f32 * 0.6);
        vertex_quad(gl, n, [x0, y0, x0 + 0.55, y0 + 0.55], |x, y| {
            let (u, v) = ((x - x0) / 0.55 * 1.8 - 0.9, (y - y0) / 0.55 * 1.8 - 0.9);
            let d = match face {
                0 => [1.0, -v, -u],
                1 => [-1.0, -v, u],
                2 => [u, 1.0, v],
                3 => [u, -1.0, -v],
                4 => [u, -v, 1.0],
                _ => [-u, -v, -1.0],
            };
            [x, y, 0.0, d[0], d[1], d[2], 1.0]
        })?;
    }
    Ok(())
}

fn depth_cube(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    let tex = n.next();
    gl.glBindTexture(TEXTURE_CUBE_MAP, tex)?;
    for face in 0..6u32 {
        let data = depths(face, 8);
        gl.glTexImage2D(
            TEXTURE_CUBE_MAP_POSITIVE_X + face,
            0,
            DEPTH_COMPONENT as i32,
            8,
            8,
            0,
            DEPTH_COMPONENT,
            UNSIGNED_INT,
            Some(Blob::borrowed(&data)),
        )?;
        marks.push(gl.glGetError()?);
    }
    gl.glTexParameteri(TEXTURE_CUBE_MAP, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_CUBE_MAP, TEXTURE_MAG_FILTER, NEAREST)?;
    let p = program(gl, n, VS, FS, &["pos", "col"])?;
    tiles(gl, n)?;
    marks.push(gl.glGetError()?);

    // Face +Y as a framebuffer's depth: cleared to 0.8, a quad drawn at window depth 0.25 over
    // its left half, read back, then sampled again.
    let (fb, color) = (n.next(), n.next());
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glBindRenderbuffer(RENDERBUFFER, color)?;
    gl.glRenderbufferStorage(RENDERBUFFER, 0x8058, 8, 8)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, color)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, DEPTH_ATTACHMENT, TEXTURE_CUBE_MAP_POSITIVE_X + 2, tex, 0)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glViewport(0, 0, 8, 8)?;
    gl.glClearDepthf(0.8)?;
    gl.glClear(DEPTH_BUFFER_BIT)?;
    program(gl, n, VS, FS_FLAT, &["pos", "col"])?;
    gl.glEnable(DEPTH_TEST)?;
    gl.glDepthFunc(ALWAYS)?;
    vertex_quad(gl, n, [-1.0, -1.0, 0.0, 1.0], |x, y| [x, y, -0.5, 1.0, 1.0, 1.0, 1.0])?;
    gl.glDisable(DEPTH_TEST)?;
    for x in [1, 6] {
        let px = gl.glReadPixels(x, 3, 1, 1, DEPTH_COMPONENT, UNSIGNED_SHORT)?;
        marks.push(gl.glGetError()?);
        marks.push(px.0.get(..2).map_or(0xF000, |b| u32::from(u16::from_ne_bytes([b[0], b[1]]))));
    }
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    gl.glUseProgram(p)?;
    gl.glBindTexture(TEXTURE_CUBE_MAP, tex)?;
    tiles(gl, n)?;

    // Packed depth and stencil in a cube face, and the pairs refused.
    let packed = n.next();
    gl.glBindTexture(TEXTURE_CUBE_MAP, packed)?;
    let data: Vec<u8> = (0..64u32).flat_map(|i| (i << 26 | 0x17).to_ne_bytes()).collect();
    gl.glTexImage2D(
        TEXTURE_CUBE_MAP_NEGATIVE_Z_OF,
        0,
        DEPTH_STENCIL as i32,
        8,
        8,
        0,
        DEPTH_STENCIL,
        UNSIGNED_INT_24_8,
        Some(Blob::borrowed(&data)),
    )?;
    marks.push(gl.glGetError()?);
    gl.glTexImage2D(TEXTURE_CUBE_MAP_NEGATIVE_Z_OF, 0, DEPTH_COMPONENT as i32, 8, 8, 0, DEPTH_COMPONENT, FLOAT, None)?;
    marks.push(gl.glGetError()?);
    gl.glTexImage2D(
        TEXTURE_CUBE_MAP_NEGATIVE_Z_OF,
        0,
        DEPTH_COMPONENT as i32,
        8,
        4,
        0,
        DEPTH_COMPONENT,
        UNSIGNED_INT,
        None,
    )?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}

/// `GL_TEXTURE_CUBE_MAP_NEGATIVE_Z`.
const TEXTURE_CUBE_MAP_NEGATIVE_Z_OF: u32 = TEXTURE_CUBE_MAP_POSITIVE_X + 5;

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "depth_cube", run: depth_cube, tol: DEFAULT, expects_error: false }]
}
