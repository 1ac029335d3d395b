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
use strata_compositor::reference::{self};
use strata_compositor::{Compositor, Intermediate, Layer, Lighting, NormalSource};
use strata_device::Gpu;
use strata_protocol::projection::Projection;

use crate::composite::texture;
use report::Row;
use scene::{
    exact_winners, images, projection, quantile, settings, shown, stored_winners, Setting, BACKGROUND, BAND, NORMALS,
};

mod daemon;
mod model;
mod report;
mod scene;
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
        strata_scene::depth::Depth::of(gpu).write(&d, w, h, &im.stored[i]);
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
