//! `GL_EXT_texture_mirror_clamp_to_edge` on Strata, against the extension's own equations.
//! Mesa advertises the extension on ES 2.0 but refuses `GL_MIRROR_CLAMP_TO_EDGE_EXT` as a
//! wrap there (`GL_INVALID_ENUM`; Mesa 22.3 accepts it only on desktop GL), so it cannot be
//! the oracle. The expected pixels are computed here from GL's texel selection (ES 3.2
//! §8.14.2, Table 8.20: `clamp(mirror(i), 0, size - 1)` with `mirror(a) = a ≥ 0 ? a :
//! -(1 + a)`, applied to the nearest texel or to both texels a linear filter weighs), and the
//! other wraps likewise: a 4×4 texture drawn with coordinates from -2.5 to 2.5 (each side
//! shows the image mirrored once and the edge clamped beyond it), nearest and linear, on s, t
//! and both with every other wrap on the other axis; projective lookups; a sampler parameter
//! from a sampler array indexed in a loop; a vertex-stage lookup; the parameter's errors; and
//! the r wrap of a 3D texture (`GL_OES_texture_3D`), through a uniform and a parameter.

mod programs;
mod support;

use programs::harness::strata_context;
use programs::{attrib, buffer, f32s, program, textured_quad, Gl, Names, FS_TEX, VS_TEX};
use strata_client::Calls;
use strata_protocol::wire::{Blob, Slice, Text};
use support::Daemon;

const TEXTURE_2D: u32 = 0x0DE1;
const TEXTURE_3D: u32 = 0x806F;
const WRAP_R: u32 = 0x8072;
const WRAP_S: u32 = 0x2802;
const WRAP_T: u32 = 0x2803;
const MIN_FILTER: u32 = 0x2801;
const MAG_FILTER: u32 = 0x2800;
const NEAREST: i32 = 0x2600;
const LINEAR: i32 = 0x2601;
const MIRROR_CLAMP: i32 = 0x8743;
const CLAMP: i32 = 0x812F;
const REPEAT: i32 = 0x2901;
const MIRRORED_REPEAT: i32 = 0x8370;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;

/// Pixels across each drawn square.
const SIDE: usize = 12;

/// Texel (x, y) of the 4×4 image.
fn texel(x: usize, y: usize) -> [f64; 4] {
    [(x * 80) as f64, (y * 80) as f64, ((x + y) * 30 + 20) as f64, 255.0]
}

/// The texel index wrap `mode` gives integer coordinate `a` of an axis of `size` texels.
fn wrap(mode: i32, a: i64, size: i64) -> usize {
    let mirror = |a: i64| if a >= 0 { a } else { -(1 + a) };
    let i = match mode {
        MIRROR_CLAMP => mirror(a).clamp(0, size - 1),
        CLAMP => a.clamp(0, size - 1),
        REPEAT => a.rem_euclid(size),
        _ => (size - 1) - mirror(a.rem_euclid(2 * size) - size),
    };
    i as usize
}

/// Weights and texel indices along one axis for coordinate `c`: one texel (nearest) or two.
fn axis(mode: i32, c: f64, linear: bool) -> Vec<(f64, usize)> {
    let u = c * 4.0;
    if linear {
        let base = (u - 0.5).floor();
        let a = u - 0.5 - base;
        vec![(1.0 - a, wrap(mode, base as i64, 4)), (a, wrap(mode, base as i64 + 1, 4))]
    } else {
        vec![(1.0, wrap(mode, u.floor() as i64, 4))]
    }
}

/// GL's sample of the image at (s, t) with wraps `(ws, wt)`, filtered as `linear` says.
fn sample((ws, wt): (i32, i32), (s, t): (f64, f64), linear: bool) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (a, x) in axis(ws, s, linear) {
        for (b, y) in axis(wt, t, linear) {
            for (o, v) in out.iter_mut().zip(texel(x, y)) {
                *o += a * b * v;
            }
        }
    }
    out
}

/// The coordinate at pixel `i` of a square drawn from -2.5 to 2.5.
fn coord(i: usize) -> f64 {
    -2.5 + (i as f64 + 0.5) * 5.0 / SIDE as f64
}

/// Checks `got` (a `SIDE`×`SIDE` read) against `expected(x, y)` within `tol`; the worst
/// difference.
fn check(what: &str, got: &[u8], tol: f64, expected: impl Fn(usize, usize) -> [f64; 4]) -> f64 {
    let mut worst: f64 = 0.0;
    for y in 0..SIDE {
        for x in 0..SIDE {
            let want = expected(x, y);
            let px = &got[(y * SIDE + x) * 4..][..4];
            for c in 0..4 {
                let d = (f64::from(px[c]) - want[c]).abs();
                worst = worst.max(d);
                assert!(d <= tol, "{what}: pixel ({x}, {y}) channel {c}: {} against {:.2}", px[c], want[c]);
            }
        }
    }
    worst
}

/// Defines the 4×4 image on the bound texture.
fn image(gl: Gl<'_>) {
    let data: Vec<u8> = (0..16).flat_map(|i| texel(i % 4, i / 4).map(|v| v as u8)).collect();
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&data)))
        .expect("upload");
}

/// Sets the bound texture's filters and wraps.
fn params(gl: Gl<'_>, filter: i32, (s, t): (i32, i32)) {
    for (p, v) in [(MIN_FILTER, filter), (MAG_FILTER, filter), (WRAP_S, s), (WRAP_T, t)] {
        gl.glTexParameteri(TEXTURE_2D, p, v).expect("parameter");
    }
    assert_eq!(gl.glGetError().expect("error"), 0, "the parameters");
}

/// Draws the bound program's window-filling quad with coordinates from -2.5 to 2.5 into a
/// `SIDE`-pixel square, and reads it.
fn draw(gl: Gl<'_>, n: &mut Names) -> Vec<u8> {
    gl.glViewport(0, 0, SIDE as i32, SIDE as i32).expect("viewport");
    textured_quad(gl, n, -2.5, 2.5).expect("draw");
    gl.glReadPixels(0, 0, SIDE as i32, SIDE as i32, RGBA, UNSIGNED_BYTE).expect("read").0
}

/// Projective lookups through a vec3 and a vec4 coordinate whose projections are exactly the
/// coordinate.
const FS_PROJ: &str = "precision highp float; uniform sampler2D s; varying vec2 t;
    void main() { vec4 a = texture2DProj(s, vec3(t * 2.0, 2.0)); vec4 b = texture2DProj(s, vec4(t * -0.5, 0.3, -0.5));
                  gl_FragColor = t.x + t.y > 0.0 ? a : b; }";
/// A lookup through a function's sampler parameter, from a sampler array indexed by a loop.
const FS_ARRAY: &str = "precision highp float; uniform sampler2D s[2]; varying vec2 t;
    vec4 look(sampler2D x, vec2 c) { return texture2D(x, c); }
    void main() { vec4 sum = vec4(0.0); for (int i = 0; i < 2; i++) { sum += look(s[i], t) * (i == 0 ? 0.75 : 0.25); } gl_FragColor = sum; }";
/// One point per pixel, coloured by a vertex-stage lookup at its coordinate.
const VS_LOOKUP: &str = "attribute vec4 pos; attribute vec2 uv; uniform sampler2D s; varying vec4 c;
    void main() { c = texture2DLod(s, uv, 0.0); gl_PointSize = 1.0; gl_Position = pos; }";
const FS_VARYING: &str = "precision mediump float; varying vec4 c; void main() { gl_FragColor = c; }";

#[test]
fn mirror_clamp_to_edge_wraps_as_the_extension_defines() {
    let mut daemon = Daemon::start("mirror-clamp", &[]);
    let mut c = strata_context(&daemon.socket, "mirror-clamp").expect("context");
    let gl = &mut c;
    let mut n = Names::default();
    let extensions = gl.glGetString(0x1F03).expect("io").unwrap_or_default();
    assert!(extensions.split(' ').any(|e| e == "GL_EXT_texture_mirror_clamp_to_edge"));
    program(gl, &mut n, VS_TEX, FS_TEX, &["pos", "uv"]).expect("program");
    let tex = n.next();
    gl.glGenTextures(Slice::new(&[tex])).expect("gen");
    gl.glBindTexture(TEXTURE_2D, tex).expect("bind");
    image(gl);
    let at = |x: usize, y: usize| (coord(x), coord(y));
    let mut worst: f64 = 0.0;
    for (filter, tol) in [(NEAREST, 0.0), (LINEAR, 2.0)] {
        for wraps in [
            (MIRROR_CLAMP, CLAMP),
            (CLAMP, MIRROR_CLAMP),
            (MIRROR_CLAMP, MIRROR_CLAMP),
            (MIRROR_CLAMP, REPEAT),
            (MIRRORED_REPEAT, MIRROR_CLAMP),
            (REPEAT, MIRRORED_REPEAT),
        ] {
            params(gl, filter, wraps);
            let got = draw(gl, &mut n);
            let what = format!("filter {filter:#x}, wraps {:#x} {:#x}", wraps.0, wraps.1);
            worst = worst.max(check(&what, &got, tol, |x, y| sample(wraps, at(x, y), filter == LINEAR)));
        }
    }
    eprintln!("plain lookups: worst difference {worst}");

    // Projective lookups.
    let both = (MIRROR_CLAMP, MIRROR_CLAMP);
    params(gl, LINEAR, both);
    program(gl, &mut n, VS_TEX, FS_PROJ, &["pos", "uv"]).expect("program");
    let got = draw(gl, &mut n);
    check("projective", &got, 2.0, |x, y| sample(both, at(x, y), true));

    // A sampler parameter: array element 0 mirrors and clamps, element 1 repeats.
    params(gl, NEAREST, both);
    let p = program(gl, &mut n, VS_TEX, FS_ARRAY, &["pos", "uv"]).expect("program");
    let second = n.next();
    gl.glGenTextures(Slice::new(&[second])).expect("gen");
    gl.glActiveTexture(0x84C1).expect("unit");
    gl.glBindTexture(TEXTURE_2D, second).expect("bind");
    image(gl);
    params(gl, NEAREST, (REPEAT, REPEAT));
    gl.glActiveTexture(0x84C0).expect("unit");
    let loc = gl.glGetUniformLocation(p, Text::borrowed("s")).expect("location");
    gl.glUniform1iv(loc, Slice::new(&[0, 1])).expect("units");
    let got = draw(gl, &mut n);
    check("sampler parameter", &got, 1.0, |x, y| {
        let (a, b) = (sample(both, at(x, y), false), sample((REPEAT, REPEAT), at(x, y), false));
        std::array::from_fn(|c| a[c] * 0.75 + b[c] * 0.25)
    });

    // A vertex-stage lookup, one point per pixel.
    program(gl, &mut n, VS_LOOKUP, FS_VARYING, &["pos", "uv"]).expect("program");
    let mut points = Vec::new();
    for y in 0..SIDE {
        for x in 0..SIDE {
            let clip = |i: usize| (i as f32 + 0.5) / SIDE as f32 * 2.0 - 1.0;
            points.extend([clip(x), clip(y), coord(x) as f32, coord(y) as f32]);
        }
    }
    buffer(gl, &mut n, 0x8892, &f32s(&points)).expect("buffer");
    attrib(gl, 0, 2, 0x1406, false, 16, 0).expect("attrib");
    attrib(gl, 1, 2, 0x1406, false, 16, 8).expect("attrib");
    gl.glClear(0x4000).expect("clear");
    gl.glDrawArrays(0, 0, (SIDE * SIDE) as i32).expect("draw");
    let got = gl.glReadPixels(0, 0, SIDE as i32, SIDE as i32, RGBA, UNSIGNED_BYTE).expect("read").0;
    check("vertex lookup", &got, 0.0, |x, y| sample(both, at(x, y), false));

    // The parameter: read back; a cube map takes it; an external texture refuses it.
    assert_eq!(gl.glGetTexParameteriv(TEXTURE_2D, WRAP_S).expect("get"), vec![MIRROR_CLAMP]);
    gl.glBindTexture(0x8513, n.next()).expect("bind");
    gl.glTexParameterf(0x8513, WRAP_T, MIRROR_CLAMP as f32).expect("parameter");
    assert_eq!(gl.glGetError().expect("error"), 0, "a cube map");
    gl.glBindTexture(0x8D65, n.next()).expect("bind");
    gl.glTexParameteri(0x8D65, WRAP_S, MIRROR_CLAMP).expect("parameter");
    assert_eq!(gl.glGetError().expect("error"), 0x0500, "an external texture");
    daemon.assert_running();
}

/// Texel (x, y, z) of the 4×4×4 image.
fn texel3(x: usize, y: usize, z: usize) -> [f64; 4] {
    [(x * 80) as f64, (y * 80) as f64, (z * 80) as f64, (255 - (x + y) * 20) as f64]
}

/// GL's sample of the 3D image at (s, t, r) with wraps `w`, filtered as `linear` says.
fn sample3(w: [i32; 3], c: [f64; 3], linear: bool) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (a, x) in axis(w[0], c[0], linear) {
        for (b, y) in axis(w[1], c[1], linear) {
            for (e, z) in axis(w[2], c[2], linear) {
                for (o, v) in out.iter_mut().zip(texel3(x, y, z)) {
                    *o += a * b * e * v;
                }
            }
        }
    }
    out
}

/// r runs against s and t: r = 0.45 (s − t) + 0.55, from about -1.6 to 2.7 over the square,
/// never on a texel boundary.
const FS_3D: &str = "#extension GL_OES_texture_3D : enable
    precision highp float; uniform lowp sampler3D s; varying vec2 t;
    void main() { gl_FragColor = texture3D(s, vec3(t, (t.x - t.y) * 0.45 + 0.55)); }";
/// The same through a function's sampler parameter.
const FS_3D_PARAM: &str = "#extension GL_OES_texture_3D : enable
    precision highp float; uniform lowp sampler3D s; varying vec2 t;
    vec4 look(lowp sampler3D x, vec3 c) { return texture3D(x, c); }
    void main() { gl_FragColor = look(s, vec3(t, (t.x - t.y) * 0.45 + 0.55)); }";

/// `GL_OES_texture_3D`'s r wrap takes the mirror too: a 4×4×4 image sampled with r running
/// across the square, nearest and linear, each axis mirrored and clamped in turn, through a
/// sampler uniform and a sampler parameter.
#[test]
fn mirror_clamp_to_edge_wraps_r_of_3d_textures() {
    let mut daemon = Daemon::start("mirror-clamp-3d", &[]);
    let mut c = strata_context(&daemon.socket, "mirror-clamp-3d").expect("context");
    let gl = &mut c;
    let mut n = Names::default();
    let tex = n.next();
    gl.glGenTextures(Slice::new(&[tex])).expect("gen");
    gl.glBindTexture(TEXTURE_3D, tex).expect("bind");
    let data: Vec<u8> = (0..64).flat_map(|i| texel3(i % 4, i / 4 % 4, i / 16).map(|v| v as u8)).collect();
    gl.glTexImage3DOES(TEXTURE_3D, 0, RGBA, 4, 4, 4, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&data)))
        .expect("upload");
    let at = |x: usize, y: usize| [coord(x), coord(y), (coord(x) - coord(y)) * 0.45 + 0.55];
    let mut worst: f64 = 0.0;
    for fs in [FS_3D, FS_3D_PARAM] {
        program(gl, &mut n, VS_TEX, fs, &["pos", "uv"]).expect("program");
        for (filter, tol) in [(NEAREST, 0.0), (LINEAR, 2.0)] {
            for wraps in [
                [CLAMP, CLAMP, MIRROR_CLAMP],
                [MIRROR_CLAMP, REPEAT, MIRROR_CLAMP],
                [REPEAT, MIRROR_CLAMP, CLAMP],
                [MIRROR_CLAMP, MIRROR_CLAMP, MIRRORED_REPEAT],
            ] {
                for (p, v) in [(MIN_FILTER, filter), (MAG_FILTER, filter), (WRAP_S, wraps[0]), (WRAP_T, wraps[1])] {
                    gl.glTexParameteri(TEXTURE_3D, p, v).expect("parameter");
                }
                gl.glTexParameteri(TEXTURE_3D, WRAP_R, wraps[2]).expect("parameter");
                assert_eq!(gl.glGetError().expect("error"), 0, "the parameters");
                let got = draw(gl, &mut n);
                let what = format!("filter {filter:#x}, wraps {wraps:x?}");
                worst = worst.max(check(&what, &got, tol, |x, y| sample3(wraps, at(x, y), filter == LINEAR)));
            }
        }
    }
    eprintln!("3D lookups: worst difference {worst}");
    assert_eq!(gl.glGetTexParameteriv(TEXTURE_3D, WRAP_R).expect("get"), vec![MIRRORED_REPEAT]);
    daemon.assert_running();
}
