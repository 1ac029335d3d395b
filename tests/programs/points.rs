//! Points larger than a pixel: `gl_PointSize` from the vertex shader, `gl_PointCoord` in the
//! fragment shader, sizes per vertex, indexed points, points at the viewport's and the
//! framebuffer's edges.
//!
//! A point of odd size is centred on a pixel centre and one of even size on a pixel corner, so
//! that no square edge passes through a pixel centre (where GL leaves the rule to the
//! implementation); `points_unaligned` checks the general case with a tolerance.

use super::*;

/// GL_POINTS.
const POINTS: u32 = 0x0000;

/// Clip x (or y) of window coordinate `px` in a `W`-wide framebuffer.
fn clip(px: f32) -> f32 {
    px / (W as f32 / 2.0) - 1.0
}

/// Where a point of `size` goes near window position (`x`, `y`): a pixel centre for odd
/// sizes, a pixel corner for even ones.
fn at(x: i32, y: i32, size: i32) -> [f32; 2] {
    let o = if size % 2 == 1 { 0.5 } else { 0.0 };
    [clip(x as f32 + o), clip(y as f32 + o)]
}

const VS_SIZED: &str = "attribute vec4 pos; attribute float size; varying vec4 v;
    void main() { gl_Position = pos; gl_PointSize = size; v = vec4(size / 24.0, 0.5, 1.0 - size / 24.0, 1.0); }";
const FS_COORD: &str = "precision mediump float; varying vec4 v;
    void main() { gl_FragColor = vec4(gl_PointCoord, v.x, 1.0); }";

/// Draws `points` (x, y, size) with `VS_SIZED` and the bound fragment shader.
fn sized_points(gl: Gl<'_>, n: &mut Names, points: &[(i32, i32, i32)]) -> R {
    let mut v = Vec::new();
    for &(x, y, s) in points {
        v.extend_from_slice(&at(x, y, s));
        v.push(s as f32);
    }
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 2, FLOAT, false, 12, 0)?;
    attrib(gl, 1, 1, FLOAT, false, 12, 8)?;
    gl.glDrawArrays(POINTS, 0, points.len() as i32)
}

/// Large points with `gl_PointCoord` as colour: its origin is the upper left of each square.
fn points_sprite_coord(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.2, 0.2, 0.2, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    program(gl, n, VS_SIZED, FS_COORD, &["pos", "size"])?;
    sized_points(gl, n, &[(12, 12, 16), (44, 14, 9), (20, 44, 21), (48, 46, 12), (32, 30, 1), (6, 30, 3)])
}

/// A size from a uniform, and sizes outside the range: 0 and below are drawn at 1 pixel.
fn points_uniform_size(gl: Gl<'_>, n: &mut Names) -> R {
    let vs = "attribute vec4 pos; uniform float size; void main() { gl_Position = pos; gl_PointSize = size; }";
    let fs = "precision mediump float; uniform vec4 color;
        void main() { gl_FragColor = color * vec4(gl_PointCoord.yx, 1.0, 1.0); }";
    let p = program(gl, n, vs, fs, &["pos"])?;
    let size = gl.glGetUniformLocation(p, Text::borrowed("size"))?;
    color(gl, p, [1.0, 0.8, 0.6, 1.0])?;
    for (i, s) in [10.0f32, 7.0, 0.0, -3.0, 0.25].into_iter().enumerate() {
        gl.glUniform1f(size, s)?;
        let xy = at(8 + 12 * i as i32, 20 + 5 * i as i32, s.max(1.0) as i32);
        draw_positions(gl, n, &[xy[0], xy[1], 0.0], POINTS)?;
    }
    Ok(())
}

/// Indexed points (out of order, one repeated) with sizes per vertex, blended "over" each
/// other, so both the index order and every point's attributes matter.
fn points_indexed_blended(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.0, 0.0, 0.3, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glEnable(BLEND)?;
    gl.glBlendFunc(0x0302, 0x0303)?;
    let fs = "precision mediump float; varying vec4 v;
        void main() { gl_FragColor = vec4(v.xyz, 0.4 + 0.5 * gl_PointCoord.x); }";
    program(gl, n, VS_SIZED, fs, &["pos", "size"])?;
    let pts = [(20, 20, 20), (28, 26, 15), (36, 32, 24), (44, 40, 11), (14, 48, 6)];
    let mut v = Vec::new();
    for &(x, y, s) in &pts {
        v.extend_from_slice(&at(x, y, s));
        v.push(s as f32);
    }
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 2, FLOAT, false, 12, 0)?;
    attrib(gl, 1, 1, FLOAT, false, 12, 8)?;
    buffer(gl, n, ELEMENT_ARRAY_BUFFER, &[3u8, 0, 2, 4, 1, 3])?;
    gl.glDrawElements(POINTS, 6, UNSIGNED_BYTE, 0)?;
    // Client-side indices, 16-bit: the same gather, from indices sent with the draw.
    gl.glBindBuffer(ELEMENT_ARRAY_BUFFER, 0)?;
    let idx: Vec<u8> = [4u16, 2].iter().flat_map(|i| i.to_ne_bytes()).collect();
    gl.strataDrawElementsData(POINTS, 2, UNSIGNED_SHORT, Blob::borrowed(&idx))
}

/// A viewport smaller than the framebuffer: points straddling its edges, points whose centre
/// lies just outside it (both rasterisers draw what falls inside the viewport), and points
/// overlapping the framebuffer's edge. The viewport's bottom is the framebuffer's: below a
/// viewport's bottom edge, llvmpipe also draws the one row just outside it.
fn points_viewport_edge(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.1, 0.1, 0.1, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glViewport(16, 0, 32, 48)?;
    program(gl, n, VS_SIZED, FS_COORD, &["pos", "size"])?;
    // Positions in window pixels, converted for the 32x48 viewport at (16, 0).
    let vx = |px: f32| (px - 16.0) / 16.0 - 1.0;
    let vy = |py: f32| py / 24.0 - 1.0;
    let pts: [(f32, f32, f32); 7] = [
        (16.0, 28.0, 10.0), // centred on the left edge
        (47.5, 20.5, 9.0),  // centre just inside the right edge
        (30.0, 47.0, 12.0), // centre inside, near the top
        (13.5, 40.5, 7.0),  // centre outside, left
        (30.0, 50.0, 8.0),  // centre outside, above
        (50.5, 10.5, 5.0),  // centre outside, right
        (31.5, 4.5, 15.0),  // over the bottom edge
    ];
    let mut v = Vec::new();
    for (x, y, s) in pts {
        v.extend_from_slice(&[vx(x), vy(y), s]);
    }
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 2, FLOAT, false, 12, 0)?;
    attrib(gl, 1, 1, FLOAT, false, 12, 8)?;
    gl.glDrawArrays(POINTS, 0, pts.len() as i32)?;
    // Full viewport again: points hanging over the framebuffer's own edges.
    gl.glViewport(0, 0, W, H)?;
    sized_points(gl, n, &[(0, 0, 12), (63, 32, 9), (30, 64, 14)])
}

/// Points with depth: the nearer square wins where they overlap, and depth is constant over
/// each square.
fn points_depth(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let vs = "attribute vec4 pos; varying vec4 v;
        void main() { gl_Position = pos; gl_PointSize = 20.0; v = vec4(pos.z * 0.5 + 0.5, 1.0 - pos.z, 0.2, 1.0); }";
    program(gl, n, vs, FS_VARY, &["pos"])?;
    let mut v = Vec::new();
    for (i, z) in [0.5f32, -0.2, 0.1, -0.6].into_iter().enumerate() {
        let xy = at(18 + 8 * i as i32, 20 + 7 * i as i32, 20);
        v.extend_from_slice(&[xy[0], xy[1], z]);
    }
    draw_positions(gl, n, &v, POINTS)
}

/// Centres off the pixel grid: edge pixels may go either way under the two rasterisers.
fn points_unaligned(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_SIZED, FS_COORD, &["pos", "size"])?;
    let v = [clip(13.3), clip(17.8), 10.0, clip(40.6), clip(22.1), 13.0, clip(30.2), clip(47.7), 6.5];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 2, FLOAT, false, 12, 0)?;
    attrib(gl, 1, 1, FLOAT, false, 12, 8)?;
    gl.glDrawArrays(POINTS, 0, 3)
}

/// The programs of this module.
pub fn all() -> Vec<Case> {
    let c = |name, run, tol| Case { name, run, tol, expects_error: false };
    // Off-grid squares: a pixel whose centre lies within rounding of an edge may be covered by
    // one rasteriser and not the other (at most the perimeter of each square).
    let edges = Tol { max_diff: 1, min_fraction: 0.985 };
    vec![
        c("points_sprite_coord", points_sprite_coord, DEFAULT),
        c("points_uniform_size", points_uniform_size, DEFAULT),
        c("points_indexed_blended", points_indexed_blended, DEFAULT),
        c("points_viewport_edge", points_viewport_edge, DEFAULT),
        c("points_depth", points_depth, DEFAULT),
        c("points_unaligned", points_unaligned, edges),
    ]
}
