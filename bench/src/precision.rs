//! Precision knobs, each measured from both sides in one run: per setting, the composite's
//! speed (median ms of GPU-completed composites of a fixed scene) and its error against the f64
//! reference compositor (`strata_compositor::reference`).
//!
//! The scene: two (or three) full-output surfaces at one z, each showing a plane of its own eye
//! space under its own declared perspective projection (different near and far planes, so raw
//! depth and eye depth disagree). The planes lean off a common base plane (20 → 60 away, left
//! to right) by a little in 1/z, so they intersect along slanted lines where their depths are
//! close over many pixels: what decides the winner there is depth precision. Each surface has
//! its own colour (red, blue, green channel dominant) and normal; the output is lit.
//!
//! Per setting:
//! - depth error: the eye-space distance each surface's depth image implies (its stored value,
//!   quantised as the setting's depth format stores it, linearised in f64 by its declared
//!   projection) against the exact distance of its plane; max and p99 over both surfaces;
//! - wrong selection: the fraction of output pixels whose colour shows another surface than
//!   the exact (f64, analytic) nearest one, within `BAND` pixels of an intersection line, and
//!   over the whole output;
//! - colour error: max and mean |difference| of the RGBA8 output against
//!   `reference::composite` fed exact depths (eye distance linear in f32, orthographic 0..128:
//!   within 2e-6 of the plane; with normals from depth, the setting's own window depth
//!   unquantised in f32, since the normal is taken from the window depth's slope).
//!
//! The vertex data wire format (`--vertex-wire`) has a row per format: the client's frame time
//! and the eye-space error of the quantised geometry (see `wire`).
//!
//! The depth format rows model the formats (quantised f64 depth, synthetic images); the
//! "daemon depth" rows run them: `stratad serve --depth-format … [--reversed-z]` with two
//! clients drawing the planes, the composite's wrong selections and the clients' frame time
//! (see `daemon`).

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use strata_compositor::reference::{self, RefLayer};
use strata_compositor::{Compositor, Intermediate, Layer, Lighting, NormalSource};
use strata_device::Gpu;
use strata_protocol::projection::{Projection, ProjectionKind};

use crate::composite::texture;
use report::Row;

mod daemon;
mod model;
mod report;
mod wire;

/// `strata-bench precision` options.
#[derive(clap::Args)]
pub struct Args {
    /// Surface (and output) width.
    #[arg(long, default_value_t = 1280)]
    width: u32,
    /// Surface (and output) height.
    #[arg(long, default_value_t = 720)]
    height: u32,
    /// Timed composites per setting (the median is reported).
    #[arg(long, default_value_t = 21)]
    frames: u32,
    /// A quick run: 640x360 and 5 composites per setting.
    #[arg(long)]
    quick: bool,
    /// Where to write the rows (JSON) and the error-against-speed plot (PNG, same name).
    #[arg(long, default_value = "target/strata-bench/precision/precision.json")]
    out: PathBuf,
    /// Print only the final JSON line.
    #[arg(long)]
    json: bool,
}

/// Eye distance of the base plane at the left edge.
const Z_LEFT: f64 = 20.0;
/// Eye distance of the base plane at the right edge.
const Z_RIGHT: f64 = 60.0;
/// How far the surfaces lean off the base plane, in 1/z across the output: about 1.4e-4 eye
/// units of depth gap per pixel beside the lines.
const EPS: f64 = 1e-4;
/// Pixels either side of an intersection line counted as "along" it.
const BAND: usize = 8;
/// The reference's linear depth range (orthographic, near 0).
const REF_FAR: f32 = 128.0;
/// Near and far planes of the surfaces' perspective projections.
const PLANES: [(f32, f32); 3] = [(0.1, 100.0), (0.5, 200.0), (0.2, 150.0)];
/// Per-surface normals.
const NORMALS: [[f32; 3]; 3] = [[0.3, 0.2, 1.0], [-0.3, 0.2, 1.0], [0.0, -0.3, 1.0]];
/// The background (straight alpha); every pixel is covered.
const BACKGROUND: [f32; 4] = [0.0, 0.0, 0.0, 1.0];

/// How a depth format stores a window depth.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Storage {
    /// Depth16Unorm.
    Unorm16,
    /// Depth24Plus's 24 bits, emulated: quantised to 24 bits, held in Depth32Float.
    Unorm24,
    /// Depth32Float.
    Float32,
}

impl Storage {
    fn name(self) -> &'static str {
        match self {
            Storage::Unorm16 => "16unorm",
            Storage::Unorm24 => "24unorm",
            Storage::Float32 => "32float",
        }
    }

    /// The texture the surfaces' depth is uploaded as.
    fn format(self) -> wgpu::TextureFormat {
        match self {
            Storage::Unorm16 => wgpu::TextureFormat::Depth16Unorm,
            Storage::Unorm24 | Storage::Float32 => wgpu::TextureFormat::Depth32Float,
        }
    }

    /// Window depth `d` as the format stores it, read back as f32.
    fn quantise(self, d: f64) -> f32 {
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
struct Setting {
    knob: &'static str,
    name: &'static str,
    storage: Storage,
    reversed: bool,
    declared: bool,
    lit: bool,
    from_depth: bool,
    surfaces: usize,
    max_textures: Option<u32>,
    intermediate: Intermediate,
    note: &'static str,
}

/// The default setting: 32-bit float depth, declared projections, lit with per-surface
/// normals, two surfaces in one pass, RGBA8 intermediate.
const DEFAULT: Setting = Setting {
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
fn settings() -> Vec<Setting> {
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
fn inv_eye(i: usize, t: f64, u: f64) -> f64 {
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
fn projection(i: usize, reversed: bool) -> Projection {
    let (near, far) = PLANES[i];
    Projection { kind: ProjectionKind::Perspective, near, far, reversed }
}

/// The window depth of eye distance `z` under `p` (GL's depth range, flipped when reversed),
/// in f64.
fn window_depth(p: &Projection, z: f64) -> f64 {
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
fn colour(i: usize, t: f64, u: f64) -> [u8; 4] {
    let (g, h) = ((100.0 * t) as u8, (100.0 * u) as u8);
    match i {
        0 => [200, g, 0, 255],
        1 => [0, h, 200, 255],
        _ => [g, 200, 0, 255],
    }
}

/// The surface an output pixel shows, by its dominant channel (lighting scales all three
/// alike and never saturates the second channel).
fn shown(p: &[u8]) -> usize {
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
fn quantile(v: &mut [f64], p: f64) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let k = ((v.len() - 1) as f64 * p).round() as usize;
    *v.select_nth_unstable_by(k, f64::total_cmp).1
}

/// The scene's images for one setting, on the CPU.
struct Images {
    /// Colour per surface (rows bottom first).
    colour: Vec<Vec<u8>>,
    /// Depth as the setting stores it, per surface.
    stored: Vec<Vec<f32>>,
    /// The reference's depth images and projections, per surface.
    reference: Vec<(Vec<f32>, Projection)>,
    /// |eye distance implied by the stored depth − exact|, every pixel of every surface.
    errors: Vec<f64>,
    /// Per surface, the depth the select compares, from the stored depth in f64: eye
    /// distance when declared, the raw value when not.
    compared: Vec<Vec<f64>>,
}

impl Images {
    /// The reference compositor's layers of the first `surfaces` surfaces, exact depths, at
    /// one z over `rect`.
    fn ref_layers(&self, surfaces: usize, rect: [i32; 4]) -> Vec<RefLayer> {
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

fn images(s: &Setting, w: u32, h: u32) -> Images {
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
fn exact_winners(surfaces: usize, w: u32, h: u32) -> (Vec<usize>, Vec<bool>) {
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
fn stored_winners(compared: &[Vec<f64>], w: u32, h: u32) -> Vec<usize> {
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

/// Measures one setting.
fn measure(
    gpu: &Arc<Gpu>,
    s: &Setting,
    w: u32,
    h: u32,
    frames: u32,
    refs: &mut HashMap<String, Vec<u8>>,
) -> Result<Row> {
    let light = Lighting {
        enabled: s.lit,
        normals: if s.from_depth { NormalSource::FromDepth } else { NormalSource::PerSurface },
        ..Lighting::default()
    };
    let mut im = images(s, w, h);
    // The surfaces on the device: colour RGBA8, depth in the setting's format.
    let mut views = Vec::new();
    for i in 0..s.surfaces {
        let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
        let c = texture(gpu, w, h, wgpu::TextureFormat::Rgba8Unorm, usage);
        gpu.write_texture(
            c.as_image_copy(),
            &im.colour[i],
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(w * 4), rows_per_image: None },
            c.size(),
        );
        let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT;
        let d = texture(gpu, w, h, s.storage.format(), usage);
        strata_scene::depth::Depth::of(&gpu).write(&d, w, h, &im.stored[i]);
        views.push((c.create_view(&Default::default()), d.create_view(&Default::default())));
    }
    let rect = [0, 0, w as i32, h as i32];
    let layers: Vec<Layer<'_>> = views
        .iter()
        .enumerate()
        .map(|(i, (c, d))| Layer {
            rect,
            z: 0.5,
            color: c,
            depth: Some(d),
            normal: NORMALS[i],
            projection: if s.declared {
                Projection::shader_params(Some(&projection(i, s.reversed)))
            } else {
                Projection::RAW
            },
            opaque: false,
            props: Default::default(),
        })
        .collect();
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
    let out = texture(gpu, w, h, wgpu::TextureFormat::Rgba8Unorm, usage);
    let mut comp = Compositor::new(gpu.clone(), s.max_textures)?.with_intermediate(s.intermediate);
    let ms = crate::composite::try_median_ms(frames, || {
        comp.composite(&layers, &light, &out, BACKGROUND, None)?;
        let _ = gpu.device.poll(wgpu::PollType::wait_indefinitely());
        Ok::<_, strata_compositor::CompositorError>(())
    })?;
    let (passes, chained) = (comp.last_passes, comp.last_stats.chained);
    let got = gpu.read_rgba8(&out, [0, 0, w, h]).context("reading the composite back")?;
    drop(layers);
    drop(views);
    // The reference, shared by settings that give it the same input.
    let key = format!(
        "{} {} {}",
        s.surfaces,
        s.lit,
        if s.from_depth { format!("{:?}", s.reversed) } else { "linear".into() }
    );
    if !refs.contains_key(&key) {
        let ref_layers = im.ref_layers(s.surfaces, rect);
        refs.insert(key.clone(), reference::composite(&ref_layers, w, h, BACKGROUND, &light));
    }
    let want = &refs[&key];
    let (max, sum) =
        got.iter().zip(want).fold((0u8, 0u64), |(m, t), (&a, &b)| (m.max(a.abs_diff(b)), t + u64::from(a.abs_diff(b))));
    let (wrong_line, wrong_all, stored_wrong_line, line_pixels) = if s.surfaces > 1 {
        let (win, band) = exact_winners(s.surfaces, w, h);
        let wrong: Vec<bool> = got.chunks(4).zip(&win).map(|(p, &e)| shown(p) != e).collect();
        let on_line = band.iter().filter(|&&b| b).count();
        let wrong_on_line = wrong.iter().zip(&band).filter(|(&x, &b)| x && b).count();
        let wrong_all = wrong.iter().filter(|&&x| x).count();
        let stored = stored_winners(&im.compared, w, h);
        let stored_on_line = stored.iter().zip(&win).zip(&band).filter(|((a, b), &l)| l && a != b).count();
        (
            Some(wrong_on_line as f64 / on_line.max(1) as f64),
            Some(wrong_all as f64 / wrong.len() as f64),
            Some(stored_on_line as f64 / on_line.max(1) as f64),
            on_line,
        )
    } else {
        (None, None, None, 0)
    };
    let depth_err_max = im.errors.iter().copied().fold(0.0, f64::max);
    let depth_err_p99 = quantile(&mut im.errors, 0.99);
    Ok(Row {
        knob: s.knob,
        setting: s.name,
        surfaces: s.surfaces,
        depth_format: s.storage.name(),
        reversed: s.reversed,
        declared: s.declared,
        lit: s.lit,
        normals: if s.from_depth { "from-depth" } else { "per-surface" },
        max_textures: s.max_textures,
        intermediate: match s.intermediate {
            Intermediate::Rgba8 => "rgba8",
            Intermediate::Rgba16f => "rgba16f",
        },
        passes,
        chained_cells: chained,
        ms,
        depth_err_max,
        depth_err_p99,
        line_pixels,
        wrong_line,
        wrong_all,
        stored_wrong_line,
        colour_err_max: max,
        colour_err_mean: sum as f64 / got.len().max(1) as f64,
        note: s.note,
    })
}

/// Runs the benchmark and prints its table; the last line is JSON.
pub fn run(args: &Args) -> Result<()> {
    let (w, h, frames) = if args.quick { (640, 360, 5) } else { (args.width, args.height, args.frames) };
    if w == 0 || h == 0 || frames == 0 {
        bail!("--width, --height and --frames must be positive");
    }
    let gpu: Arc<Gpu> = Gpu::open()?;
    let all = settings();
    let pb = if args.json { ProgressBar::hidden() } else { ProgressBar::new(all.len() as u64) };
    pb.set_style(
        ProgressStyle::with_template("{msg:>28} [{bar:40}] {pos}/{len} {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut refs = HashMap::new();
    let mut rows = Vec::new();
    for s in &all {
        pb.set_message(s.name);
        rows.push(measure(&gpu, s, w, h, frames, &mut refs)?);
        pb.inc(1);
    }
    pb.set_message("culling, depth target");
    rows.extend(model::rows(&gpu, w, h, frames, &mut refs)?);
    pb.set_message("vertex wire");
    rows.extend(wire::rows(w, h)?);
    rows.extend(daemon::rows(w, h, |s| pb.set_message(format!("daemon depth {s}")))?);
    pb.finish_and_clear();
    if !args.json {
        report::print(&rows, w, h, frames);
    }
    let summary = serde_json::json!({
        "benchmark": "precision",
        "width": w,
        "height": h,
        "frames": frames,
        "band_px": BAND,
        "rows": rows.len(),
        "curve": args.out,
    });
    if let Some(dir) = args.out.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(&args.out, serde_json::to_string_pretty(&serde_json::json!({ "summary": summary, "rows": rows }))?)?;
    let png = args.out.with_extension("png");
    match report::scatter(&png, &format!("Precision knobs, {w}x{h}: error against speed"), &rows) {
        Ok(()) if !args.json => println!("rows: {} and {}", args.out.display(), png.display()),
        Ok(()) => {}
        Err(e) => eprintln!("plot not written: {e:#}"),
    }
    println!("{summary}");
    Ok(())
}
