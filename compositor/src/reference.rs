//! The reference compositor: plain f64 code written from the thesis (§4.5–4.6), used as the
//! oracle for the GPU compositor. Deliberately simple: one loop over output pixels.

use strata_protocol::projection::Projection;

use crate::{Lighting, NormalSource, Props};
use strata_device::Gpu;

/// One surface as the reference sees it: CPU copies of its images.
#[derive(Debug, Clone)]
pub struct RefLayer {
    /// x, y (from the output's top), width, height in output pixels: where it shows (its
    /// image's size unless `props.source` scales it).
    pub rect: [i32; 4],
    /// Depth layer: larger is farther; equal values form one group.
    pub z: f32,
    /// RGBA8 rows, bottom row first (GL order), straight alpha.
    pub color: Vec<u8>,
    /// Depth rows (bottom first) in [0, 1], or `None` for a surface without depth (at its far
    /// plane: depth 1 when undeclared).
    pub depth: Option<Vec<f32>>,
    /// The per-surface normal.
    pub normal: [f32; 3],
    /// The declared projection by which its depth is compared (`None`: raw depth).
    pub projection: Option<Projection>,
    /// Which part of its image shows over `rect`, and its opacity.
    pub props: Props,
}

impl RefLayer {
    /// Its image's width and height.
    fn image(&self) -> [i32; 2] {
        self.props.source_for(self.rect).image
    }

    /// Its colour texel (x, y counted from the bottom), straight alpha in [0, 1].
    fn texel(&self, x: i32, y: i32) -> [f64; 4] {
        let at = ((y * self.image()[0] + x) * 4) as usize;
        std::array::from_fn(|i| f64::from(self.color[at + i]) / 255.0)
    }
}

/// `a / b` rounded down (b > 0).
fn fdiv(a: i64, b: i64) -> i64 {
    a.div_euclid(b)
}

/// The source texel (x, y from the image's top) whose area holds the centre of pixel `l` of
/// the rectangle (`l`: from the rectangle's corner; `n`: the rectangle's and `src`'s extent
/// along one axis; `o`: the source region's start).
fn nearest(l: i64, o: i32, src: i32, n: i32) -> i32 {
    (i64::from(o) + fdiv((2 * l + 1) * i64::from(src), 2 * i64::from(n))) as i32
}

/// The two source texels around the centre of pixel `l` along one axis (clamped to the
/// source region) and the weight of the second: centres at half-integers, as a bilinear
/// sampler takes them.
fn around(l: i64, o: i32, src: i32, n: i32) -> (i32, i32, f64) {
    let num = (2 * l + 1) * i64::from(src) - i64::from(n);
    let d = 2 * i64::from(n);
    let t0 = fdiv(num, d);
    let f = (num - t0 * d) as f64 / d as f64;
    let clamp = |t: i64| (i64::from(o) + t).clamp(i64::from(o), i64::from(o) + i64::from(src) - 1) as i32;
    (clamp(t0), clamp(t0 + 1), f)
}

/// `v` scaled to unit length, or zero for a zero or non-finite length (`encode::unit_normal`).
fn normalize(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !(l > 0.0 && l.is_finite()) {
        return [0.0, 0.0, 0.0];
    }
    [v[0] / l, v[1] / l, v[2] / l]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Depth of `l` at surface pixel (sx, sy) (sy counted from the bottom), 1 without depth, read
/// as the shader reads a texel: NaN as the far plane's window depth (1, or 0 when reversed),
/// then clamped to [0, 1].
fn depth_at(l: &RefLayer, sx: i32, sy: i32) -> f64 {
    let w = l.image()[0];
    match &l.depth {
        Some(d) => {
            let v = f64::from(d[(sy * w + sx) as usize]);
            if v.is_nan() {
                if l.projection.is_some_and(|p| p.reversed) {
                    0.0
                } else {
                    1.0
                }
            } else {
                v.clamp(0.0, 1.0)
            }
        }
        None => 1.0,
    }
}

/// Eye-space depth of `l` at surface pixel (sx, sy), by which a group selects: its window depth
/// linearised by its projection, the raw depth when it declares none; without a depth image
/// the surface lies at its far plane (1 when undeclared).
fn eye_depth_at(l: &RefLayer, sx: i32, sy: i32) -> f64 {
    match (&l.depth, &l.projection) {
        (Some(_), p) => {
            let d = depth_at(l, sx, sy);
            p.map_or(d, |p| p.eye_depth(d))
        }
        (None, p) => p.map_or(1.0, |p| f64::from(p.far)),
    }
}

/// The normal reconstructed from depth: central differences, one-sided at the edges.
fn depth_normal(l: &RefLayer, sx: i32, sy: i32, scale: f64) -> [f64; 3] {
    let [w, h] = l.image();
    let d = |x: i32, y: i32| depth_at(l, x.clamp(0, w - 1), y.clamp(0, h - 1));
    let (x0, x1) = ((sx - 1).max(0), (sx + 1).min(w - 1));
    let (y0, y1) = ((sy - 1).max(0), (sy + 1).min(h - 1));
    let dzdx = if x1 > x0 { (d(x1, sy) - d(x0, sy)) / f64::from(x1 - x0) } else { 0.0 };
    let dzdy = if y1 > y0 { (d(sx, y1) - d(sx, y0)) / f64::from(y1 - y0) } else { 0.0 };
    normalize([-dzdx * scale, -dzdy * scale, 1.0])
}

/// The surface group `z` selects at output pixel (px, py): its eye depth, the surface, the
/// pixel within its rectangle and the texel (x, y from the bottom) the select read; `None`
/// where no member's rectangle holds the pixel. The nearest eye depth wins; on a tie the later
/// surface (in stacking order) wins.
fn select(layers: &[RefLayer], z: f32, px: i32, py: i32) -> Option<(f64, &RefLayer, [i64; 2], i32, i32)> {
    let mut best: Option<(f64, &RefLayer, [i64; 2], i32, i32)> = None;
    for l in layers.iter().filter(|l| l.z == z) {
        // In 64 bits: a rectangle may lie anywhere in the i32 plane.
        let (lx, ly) = (i64::from(px) - i64::from(l.rect[0]), i64::from(py) - i64::from(l.rect[1]));
        if lx < 0 || ly < 0 || lx >= i64::from(l.rect[2]) || ly >= i64::from(l.rect[3]) {
            continue;
        }
        let src = l.props.source_for(l.rect);
        let r = src.region;
        let sx = nearest(lx, r[0], r[2], l.rect[2]);
        let sy = src.image[1] - 1 - nearest(ly, r[1], r[3], l.rect[3]);
        let d = eye_depth_at(l, sx, sy);
        if best.is_none_or(|b| d <= b.0) {
            best = Some((d, l, [lx, ly], sx, sy));
        }
    }
    best
}

/// Which of `layers` (in stacking order) output pixel (px, py) shows, for input: groups are
/// taken near to far, and the first whose selected surface is not transparent there (the
/// selected texel's alpha times the surface's opacity above 0) has it; `None` where none is.
pub fn pick(layers: &[RefLayer], px: i32, py: i32) -> Option<usize> {
    let mut zs: Vec<f32> = layers.iter().map(|l| l.z).collect();
    zs.sort_by(f32::total_cmp);
    zs.dedup();
    for z in zs {
        let Some((_, l, _, sx, sy)) = select(layers, z, px, py) else { continue };
        if l.texel(sx, sy)[3] * f64::from(l.props.opacity.clamp(0.0, 1.0)) > 0.0 {
            return layers.iter().position(|m| std::ptr::eq(m, l));
        }
    }
    None
}

/// Composites `layers` (in stacking order) into a `width`×`height` RGBA8 image, top row first.
pub fn composite(layers: &[RefLayer], width: u32, height: u32, background: [f32; 4], light: &Lighting) -> Vec<u8> {
    let mut zs: Vec<f32> = layers.iter().map(|l| l.z).collect();
    zs.sort_by(|a, b| b.total_cmp(a));
    zs.dedup();
    let mut out = Vec::with_capacity((width * height * 4) as usize);
    for py in 0..height as i32 {
        for px in 0..width as i32 {
            let bg = background.map(f64::from);
            // Premultiplied accumulation.
            let mut acc = [bg[0] * bg[3], bg[1] * bg[3], bg[2] * bg[3], bg[3]];
            for &z in &zs {
                let best = select(layers, z, px, py);
                let Some((_, l, [lx, ly], sx, sy)) = best else { continue };
                let src = l.props.source_for(l.rect);
                let r = src.region;
                let c = if r[2] == l.rect[2] && r[3] == l.rect[3] {
                    l.texel(sx, sy)
                } else {
                    // Bilinear, rows counted from the image's top, then flipped.
                    let (x0, x1, fx) = around(lx, r[0], r[2], l.rect[2]);
                    let (y0, y1, fy) = around(ly, r[1], r[3], l.rect[3]);
                    let flip = |y: i32| src.image[1] - 1 - y;
                    let mix = |a: [f64; 4], b: [f64; 4], t: f64| {
                        std::array::from_fn::<f64, 4, _>(|i| a[i] + (b[i] - a[i]) * t)
                    };
                    let top = mix(l.texel(x0, flip(y0)), l.texel(x1, flip(y0)), fx);
                    let bottom = mix(l.texel(x0, flip(y1)), l.texel(x1, flip(y1)), fx);
                    mix(top, bottom, fy)
                };
                let mut rgb = [c[0], c[1], c[2]];
                if light.enabled {
                    let n = match light.normals {
                        NormalSource::PerSurface => normalize(l.normal.map(f64::from)),
                        NormalSource::FromDepth => depth_normal(l, sx, sy, f64::from(light.depth_normal_scale)),
                    };
                    // A zero normal (also a non-finite one) has no direction: ambient only.
                    let zero = n == [0.0; 3];
                    let frag = [
                        (f64::from(px) + 0.5) / f64::from(width) * 2.0 - 1.0,
                        1.0 - (f64::from(py) + 0.5) / f64::from(height) * 2.0,
                        0.0,
                    ];
                    let lp = light.position.map(f64::from);
                    let vp = light.view.map(f64::from);
                    let ld = normalize([lp[0] - frag[0], lp[1] - frag[1], lp[2] - frag[2]]);
                    let vd = normalize([vp[0] - frag[0], vp[1] - frag[1], vp[2] - frag[2]]);
                    let diffuse = dot(n, ld).max(0.0);
                    // reflect(-L, n) = -L + 2 (n·L) n
                    let nl = dot(n, ld);
                    let r = [-ld[0] + 2.0 * nl * n[0], -ld[1] + 2.0 * nl * n[1], -ld[2] + 2.0 * nl * n[2]];
                    let specular = dot(vd, r).max(0.0).powf(f64::from(light.shininess));
                    // Shininess 0 gives specular 1 everywhere: powf(0, 0) = 1.
                    let f = f64::from(light.ambient) + if zero { 0.0 } else { diffuse + specular };
                    for (i, ch) in rgb.iter_mut().enumerate() {
                        *ch = (*ch * f * f64::from(light.color[i])).clamp(0.0, 1.0);
                    }
                }
                let a = c[3] * f64::from(l.props.opacity.clamp(0.0, 1.0));
                for i in 0..3 {
                    acc[i] = rgb[i] * a + acc[i] * (1.0 - a);
                }
                acc[3] = a + acc[3] * (1.0 - a);
            }
            for v in acc {
                out.push((v.clamp(0.0, 1.0) * 255.0).round() as u8);
            }
        }
    }
    out
}

/// A reference layer's images on the device, for the GPU compositor.
pub struct Uploaded {
    /// The colour image.
    pub color: wgpu::TextureView,
    /// The depth image, if the layer has depth.
    pub depth: Option<wgpu::TextureView>,
}

impl Uploaded {
    /// The GPU compositor's layer of `l` (uploaded as `self`), with the same projection; not
    /// marked opaque (a caller whose layer has alpha 1 everywhere may set `opaque`).
    pub fn layer(&self, l: &RefLayer) -> crate::Layer<'_> {
        crate::Layer {
            rect: l.rect,
            z: l.z,
            color: &self.color,
            depth: self.depth.as_ref(),
            normal: l.normal,
            projection: Projection::shader_params(l.projection.as_ref()),
            opaque: false,
            props: l.props,
        }
    }
}

/// Uploads a reference layer's colour and depth images, so that the GPU compositor can draw
/// what the reference draws.
pub fn upload(gpu: &Gpu, l: &RefLayer) -> Uploaded {
    let [w, h] = l.image();
    let size = wgpu::Extent3d { width: w as u32, height: h as u32, depth_or_array_layers: 1 };
    let mk = |format, usage| gpu.texture_2d("reference layer", format, (size.width, size.height), usage);
    let c = mk(wgpu::TextureFormat::Rgba8Unorm, wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST);
    gpu.write_texture(
        c.as_image_copy(),
        &l.color,
        wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(size.width * 4), rows_per_image: None },
        size,
    );
    let depth = l.depth.as_ref().map(|d| {
        let t = mk(
            wgpu::TextureFormat::Depth32Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        strata_scene::depth::Depth::of(gpu).write(&t, size.width, size.height, d);
        t.create_view(&Default::default())
    });
    Uploaded { color: c.create_view(&Default::default()), depth }
}
