//! The precision scene: planes under their own perspective projections leaning off a common
//! base plane, each setting's depth storage, the exact (f64) answers the measurements are held
//! to, and the synthetic images the model rows composite.

use strata_compositor::reference::RefLayer;
use strata_compositor::Intermediate;
use strata_protocol::projection::{Projection, ProjectionKind};

/// Eye distance of the base plane at the left edge.
pub(crate) const Z_LEFT: f64 = 20.0;
/// Eye distance of the base plane at the right edge.
pub(crate) const Z_RIGHT: f64 = 60.0;
/// How far the surfaces lean off the base plane, in 1/z across the output: about 1.4e-4 eye
/// units of depth gap per pixel beside the lines.
pub(crate) const EPS: f64 = 1e-4;
/// Pixels either side of an intersection line counted as "along" it.
pub(crate) const BAND: usize = 8;
/// The reference's linear depth range (orthographic, near 0).
pub(crate) const REF_FAR: f32 = 128.0;
/// Near and far planes of the surfaces' perspective projections.
pub(crate) const PLANES: [(f32, f32); 3] = [(0.1, 100.0), (0.5, 200.0), (0.2, 150.0)];
/// Per-surface normals.
pub(crate) const NORMALS: [[f32; 3]; 3] = [[0.3, 0.2, 1.0], [-0.3, 0.2, 1.0], [0.0, -0.3, 1.0]];
/// The background (straight alpha); every pixel is covered.
pub(crate) const BACKGROUND: [f32; 4] = [0.0, 0.0, 0.0, 1.0];

/// How a depth format stores a window depth.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Storage {
    /// Depth16Unorm.
    Unorm16,
    /// Depth24Plus's 24 bits, emulated: quantised to 24 bits, held in Depth32Float.
    Unorm24,
    /// Depth32Float.
    Float32,
}

impl Storage {
    pub(crate) fn name(self) -> &'static str {
        match self {
            Storage::Unorm16 => "16unorm",
            Storage::Unorm24 => "24unorm",
            Storage::Float32 => "32float",
        }
    }

    /// The texture the surfaces' depth is uploaded as.
    pub(crate) fn format(self) -> wgpu::TextureFormat {
        match self {
            Storage::Unorm16 => wgpu::TextureFormat::Depth16Unorm,
            Storage::Unorm24 | Storage::Float32 => wgpu::TextureFormat::Depth32Float,
        }
    }

    /// Window depth `d` as the format stores it, read back as f32.
    pub(crate) fn quantise(self, d: f64) -> f32 {
        let d = d.clamp(0.0, 1.0);
        match self {
            Storage::Unorm16 => ((d * 65535.0).round() / 65535.0) as f32,
            Storage::Unorm24 => ((d * 16_777_215.0).round() / 16_777_215.0) as f32,
            Storage::Float32 => d as f32,
        }
    }
}

/// One knob setting; the others at their defaults.
#[derive(Clone, Copy)]
pub(crate) struct Setting {
    pub(crate) knob: &'static str,
    pub(crate) name: &'static str,
    pub(crate) storage: Storage,
    pub(crate) reversed: bool,
    pub(crate) declared: bool,
    pub(crate) lit: bool,
    pub(crate) from_depth: bool,
    pub(crate) surfaces: usize,
    pub(crate) max_textures: Option<u32>,
    pub(crate) intermediate: Intermediate,
    pub(crate) note: &'static str,
}

/// The default setting: 32-bit float depth, declared projections, lit with per-surface
/// normals, two surfaces in one pass, RGBA8 intermediate.
pub(crate) const DEFAULT: Setting = Setting {
    knob: "default",
    name: "32float, declared, lit",
    storage: Storage::Float32,
    reversed: false,
    declared: true,
    lit: true,
    from_depth: false,
    surfaces: 2,
    max_textures: None,
    intermediate: Intermediate::Rgba8,
    note: "",
};

/// Every setting measured, one row each.
pub(crate) fn settings() -> Vec<Setting> {
    let d = DEFAULT;
    let emulated = "Depth24Plus emulated: quantised to 24 bits, stored in Depth32Float";
    vec![
        Setting { knob: "depth format", name: "16unorm", storage: Storage::Unorm16, ..d },
        Setting { knob: "depth format", name: "24unorm", storage: Storage::Unorm24, note: emulated, ..d },
        Setting { knob: "depth format", name: "32float (default)", ..d },
        Setting {
            knob: "depth format",
            name: "24unorm reversed-Z",
            storage: Storage::Unorm24,
            reversed: true,
            note: emulated,
            ..d
        },
        Setting { knob: "depth format", name: "32float reversed-Z", reversed: true, ..d },
        Setting {
            knob: "projection",
            name: "undeclared (raw)",
            declared: false,
            note: "same depth images, compared raw (Projection::RAW); depth error is their storage error",
            ..d
        },
        Setting {
            knob: "normals",
            name: "from depth",
            from_depth: true,
            note: "reference: unquantised f32 window depth",
            ..d
        },
        Setting { knob: "lighting", name: "off", lit: false, ..d },
        Setting { knob: "z-group", name: "1 surface (no select)", surfaces: 1, ..d },
        Setting { knob: "z-group", name: "3 surfaces, one pass", surfaces: 3, ..d },
        Setting {
            knob: "intermediate",
            name: "3 surf. chained, rgba8",
            surfaces: 3,
            max_textures: Some(4),
            note: "--max-textures 4: 2 surfaces per pass",
            ..d
        },
        Setting {
            knob: "intermediate",
            name: "3 surf. chained, rgba16f",
            surfaces: 3,
            max_textures: Some(4),
            intermediate: Intermediate::Rgba16f,
            note: "--max-textures 4: 2 surfaces per pass",
            ..d
        },
    ]
}

/// Surface `i`'s plane: 1/z at (t, u) across the output (u from the bottom). The planes all
/// pass through the centre, where they meet.
pub(crate) fn inv_eye(i: usize, t: f64, u: f64) -> f64 {
    let base = (1.0 - t) / Z_LEFT + t / Z_RIGHT;
    let (a, b) = (t - 0.5, u - 0.5);
    base + EPS
        * match i {
            0 => a + 0.5 * b,
            1 => -(a + 0.5 * b),
            _ => 1.5 * b - 0.5 * a,
        }
}

/// Surface `i`'s declared projection.
pub(crate) fn projection(i: usize, reversed: bool) -> Projection {
    let (near, far) = PLANES[i];
    Projection { kind: ProjectionKind::Perspective, near, far, reversed }
}

/// The window depth of eye distance `z` under `p` (GL's depth range, flipped when reversed),
/// in f64.
pub(crate) fn window_depth(p: &Projection, z: f64) -> f64 {
    let (n, f) = (f64::from(p.near), f64::from(p.far));
    let d = match p.kind {
        ProjectionKind::Orthographic => (z - n) / (f - n),
        ProjectionKind::Perspective => f * (z - n) / (z * (f - n)),
    };
    if p.reversed {
        1.0 - d
    } else {
        d
    }
}

/// Surface `i`'s colour at (t, u): its own dominant channel, a gradient in a second one.
pub(crate) fn colour(i: usize, t: f64, u: f64) -> [u8; 4] {
    let (g, h) = ((100.0 * t) as u8, (100.0 * u) as u8);
    match i {
        0 => [200, g, 0, 255],
        1 => [0, h, 200, 255],
        _ => [g, 200, 0, 255],
    }
}

/// The surface an output pixel shows, by its dominant channel (lighting scales all three
/// alike and never saturates the second channel).
pub(crate) fn shown(p: &[u8]) -> usize {
    let (r, g, b) = (p[0], p[1], p[2]);
    if r >= g && r >= b {
        0
    } else if b >= g {
        1
    } else {
        2
    }
}

/// The p-quantile of `v` (reordered).
pub(crate) fn quantile(v: &mut [f64], p: f64) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let k = ((v.len() - 1) as f64 * p).round() as usize;
    *v.select_nth_unstable_by(k, f64::total_cmp).1
}

/// The scene's images for one setting, on the CPU.
pub(crate) struct Images {
    /// Colour per surface (rows bottom first).
    pub(crate) colour: Vec<Vec<u8>>,
    /// Depth as the setting stores it, per surface.
    pub(crate) stored: Vec<Vec<f32>>,
    /// The reference's depth images and projections, per surface.
    pub(crate) reference: Vec<(Vec<f32>, Projection)>,
    /// |eye distance implied by the stored depth − exact|, every pixel of every surface.
    pub(crate) errors: Vec<f64>,
    /// Per surface, the depth the select compares, from the stored depth in f64: eye
    /// distance when declared, the raw value when not.
    pub(crate) compared: Vec<Vec<f64>>,
}

impl Images {
    /// The reference compositor's layers of the first `surfaces` surfaces, exact depths, at
    /// one z over `rect`.
    pub(crate) fn ref_layers(&self, surfaces: usize, rect: [i32; 4]) -> Vec<RefLayer> {
        (0..surfaces)
            .map(|i| RefLayer {
                rect,
                z: 0.5,
                color: self.colour[i].clone(),
                depth: Some(self.reference[i].0.clone()),
                normal: NORMALS[i],
                projection: Some(self.reference[i].1),
                props: Default::default(),
            })
            .collect()
    }
}

pub(crate) fn images(s: &Setting, w: u32, h: u32) -> Images {
    let n = (w * h) as usize;
    let mut im = Images {
        colour: Vec::new(),
        stored: Vec::new(),
        reference: Vec::new(),
        errors: Vec::with_capacity(n * s.surfaces),
        compared: Vec::new(),
    };
    let linear = Projection { kind: ProjectionKind::Orthographic, near: 0.0, far: REF_FAR, reversed: false };
    for i in 0..s.surfaces {
        let p = projection(i, s.reversed);
        let mut c = Vec::with_capacity(n * 4);
        let mut stored = Vec::with_capacity(n);
        let mut exact = Vec::with_capacity(n);
        let mut compared = Vec::with_capacity(n);
        for sy in 0..h {
            for x in 0..w {
                let (t, u) = ((f64::from(x) + 0.5) / f64::from(w), (f64::from(sy) + 0.5) / f64::from(h));
                let z = 1.0 / inv_eye(i, t, u);
                c.extend_from_slice(&colour(i, t, u));
                let d = window_depth(&p, z);
                let q = s.storage.quantise(d);
                let eye = p.eye_depth(f64::from(q));
                im.errors.push((eye - z).abs());
                compared.push(if s.declared { eye } else { f64::from(q) });
                stored.push(q);
                exact.push(if s.from_depth { d as f32 } else { (z / f64::from(REF_FAR)) as f32 });
            }
        }
        im.colour.push(c);
        im.stored.push(stored);
        im.compared.push(compared);
        im.reference.push((exact, if s.from_depth { p } else { linear }));
    }
    im
}

/// Per output pixel (top row first): the exact nearest surface, and whether it lies within
/// `BAND` pixels (in its row) of a pixel another surface wins.
pub(crate) fn exact_winners(surfaces: usize, w: u32, h: u32) -> (Vec<usize>, Vec<bool>) {
    let (w, h) = (w as usize, h as usize);
    let mut win = Vec::with_capacity(w * h);
    for py in 0..h {
        let u = ((h - 1 - py) as f64 + 0.5) / h as f64;
        for x in 0..w {
            let t = (x as f64 + 0.5) / w as f64;
            let best = (0..surfaces).fold(0, |b, i| if inv_eye(i, t, u) >= inv_eye(b, t, u) { i } else { b });
            win.push(best);
        }
    }
    let mut band = vec![false; w * h];
    for row in 0..h {
        let r = &win[row * w..(row + 1) * w];
        for x in 1..w {
            if r[x] != r[x - 1] {
                for b in band[row * w..(row + 1) * w].iter_mut().take((x + BAND).min(w)).skip(x.saturating_sub(BAND)) {
                    *b = true;
                }
            }
        }
    }
    (win, band)
}

/// Per output pixel (top row first): the surface an exact (f64) select of the stored depths
/// picks: the nearest, the later on a tie.
pub(crate) fn stored_winners(compared: &[Vec<f64>], w: u32, h: u32) -> Vec<usize> {
    let (w, h) = (w as usize, h as usize);
    let mut win = Vec::with_capacity(w * h);
    for py in 0..h {
        let row = (h - 1 - py) * w;
        for x in 0..w {
            win.push(
                (0..compared.len()).fold(0, |b, i| if compared[i][row + x] <= compared[b][row + x] { i } else { b }),
            );
        }
    }
    win
}
