//! Rows on what the compositor models of a scene, on the default two-surface scene:
//! - culling: an opaque full-output surface at a nearer z over the two surfaces, composited
//!   with culling on (only it is sampled) and off (all three are); the image is the same;
//! - depth target: the two surfaces with their depth images, and without (a config without
//!   depth gets no depth target, so each surface lies at its far plane everywhere).
//!
//! Errors are against the f64 reference given the scene's exact depths, as the other rows'.

use std::collections::HashMap;
use std::sync::Arc;

use anyhow::{Context, Result};
use strata_compositor::reference::{self, RefLayer};
use strata_compositor::{Compositor, Layer, Lighting};
use strata_device::Gpu;
use strata_protocol::projection::Projection;

use super::report::Row;
use super::scene::{exact_winners, images, inv_eye, projection, quantile, shown, BACKGROUND, DEFAULT, NORMALS};
use crate::composite::texture;

/// The nearer opaque surface's colour.
const COVER: [u8; 4] = [90, 90, 90, 255];

/// One of this module's cases.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Case {
    /// The opaque cover over the scene; culling on or off.
    Cover { cull: bool },
    /// The two surfaces, with or without depth images.
    Depth { with: bool },
}

/// The rows: culling on and off, then depth images with and without.
pub(super) fn rows(
    gpu: &Arc<Gpu>,
    w: u32,
    h: u32,
    frames: u32,
    refs: &mut HashMap<String, Vec<u8>>,
) -> Result<Vec<Row>> {
    let cases = [
        Case::Cover { cull: true },
        Case::Cover { cull: false },
        Case::Depth { with: true },
        Case::Depth { with: false },
    ];
    cases.iter().map(|&c| measure(gpu, c, w, h, frames, refs)).collect()
}

fn measure(
    gpu: &Arc<Gpu>,
    case: Case,
    w: u32,
    h: u32,
    frames: u32,
    refs: &mut HashMap<String, Vec<u8>>,
) -> Result<Row> {
    let s = DEFAULT;
    let light = Lighting::default();
    let mut im = images(&s, w, h);
    let rect = [0, 0, w as i32, h as i32];
    let with_depth = case != Case::Depth { with: false };
    let mut views = Vec::new();
    for i in 0..s.surfaces {
        let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
        let c = texture(gpu, w, h, wgpu::TextureFormat::Rgba8Unorm, usage);
        write_rgba(gpu, &c, &im.colour[i]);
        let d = with_depth.then(|| {
            let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT;
            let d = texture(gpu, w, h, s.storage.format(), usage);
            strata_scene::depth::Depth::of(gpu).write(&d, w, h, &im.stored[i]);
            d.create_view(&Default::default())
        });
        views.push((c.create_view(&Default::default()), d));
    }
    let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
    let cover = texture(gpu, w, h, wgpu::TextureFormat::Rgba8Unorm, usage);
    write_rgba(gpu, &cover, &COVER.repeat((w * h) as usize));
    let cover_view = cover.create_view(&Default::default());
    let mut layers: Vec<Layer<'_>> = views
        .iter()
        .enumerate()
        .map(|(i, (c, d))| Layer {
            rect,
            z: 0.5,
            color: c,
            depth: d.as_ref(),
            normal: NORMALS[i],
            projection: Projection::shader_params(Some(&projection(i, false))),
            opaque: false,
            props: Default::default(),
        })
        .collect();
    let cull = match case {
        Case::Cover { cull } => {
            layers.push(Layer {
                rect,
                z: 0.2,
                color: &cover_view,
                depth: None,
                normal: [0.0, 0.0, 1.0],
                projection: Projection::RAW,
                opaque: true,
                props: Default::default(),
            });
            cull
        }
        Case::Depth { .. } => true,
    };
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
    let out = texture(gpu, w, h, wgpu::TextureFormat::Rgba8Unorm, usage);
    let mut comp = Compositor::new(gpu.clone(), None)?.with_culling(cull);
    let ms = crate::composite::try_median_ms(frames, || {
        comp.composite(&layers, &light, &out, BACKGROUND, None)?;
        let _ = gpu.device.poll(wgpu::PollType::wait_indefinitely());
        Ok::<_, strata_compositor::CompositorError>(())
    })?;
    let (passes, chained) = (comp.last_passes, comp.last_stats.chained);
    let got = gpu.read_rgba8(&out, [0, 0, w, h]).context("reading the composite back")?;
    drop(layers);
    // The reference of the exact scene (the default row's, shared when it was computed).
    let mut ref_layers = im.ref_layers(s.surfaces, rect);
    let key = match case {
        Case::Cover { .. } => {
            ref_layers.push(RefLayer {
                rect,
                z: 0.2,
                color: COVER.repeat((w * h) as usize),
                depth: None,
                normal: [0.0, 0.0, 1.0],
                projection: None,
                props: Default::default(),
            });
            "model: opaque cover".to_string()
        }
        Case::Depth { .. } => format!("{} {} linear", s.surfaces, s.lit),
    };
    if !refs.contains_key(&key) {
        refs.insert(key.clone(), reference::composite(&ref_layers, w, h, BACKGROUND, &light));
    }
    let (max, sum) = diff(&got, &refs[&key]);
    // Without depth the select compares far planes: the reference given that input instead.
    let model_err = (case == Case::Depth { with: false }).then(|| {
        for l in &mut ref_layers {
            l.depth = None;
        }
        for (l, i) in ref_layers.iter_mut().zip(0..) {
            l.projection = Some(projection(i, false));
        }
        diff(&got, &reference::composite(&ref_layers, w, h, BACKGROUND, &light)).0
    });
    if !with_depth {
        // The eye distance a surface without depth implies: its far plane.
        let n = (w * h) as usize;
        for (i, e) in im.errors.chunks_mut(n).enumerate() {
            let far = f64::from(projection(i, false).far);
            for (k, v) in e.iter_mut().enumerate() {
                let (x, sy) = ((k % w as usize) as f64, (k / w as usize) as f64);
                let (t, u) = ((x + 0.5) / f64::from(w), (sy + 0.5) / f64::from(h));
                *v = (far - 1.0 / inv_eye(i, t, u)).abs();
            }
        }
    }
    let (wrong_line, wrong_all, line_pixels) = match case {
        Case::Depth { .. } => {
            let (win, band) = exact_winners(s.surfaces, w, h);
            let wrong: Vec<bool> = got.chunks(4).zip(&win).map(|(p, &e)| shown(p) != e).collect();
            let on_line = band.iter().filter(|&&b| b).count();
            let wrong_on_line = wrong.iter().zip(&band).filter(|(&x, &b)| x && b).count();
            let wrong_all = wrong.iter().filter(|&&x| x).count();
            (
                Some(wrong_on_line as f64 / on_line.max(1) as f64),
                Some(wrong_all as f64 / wrong.len().max(1) as f64),
                on_line,
            )
        }
        Case::Cover { .. } => (None, None, 0),
    };
    let depth_err_max = im.errors.iter().copied().fold(0.0, f64::max);
    let depth_err_p99 = quantile(&mut im.errors, 0.99);
    let (knob, setting, note) = match case {
        Case::Cover { cull: true } => (
            "culling",
            "opaque cover, on (default)",
            "an opaque full-output surface at a nearer z over the two: only it is sampled",
        ),
        Case::Cover { cull: false } => {
            ("culling", "opaque cover, off", "--cull off: the two surfaces beneath are selected and covered")
        }
        Case::Depth { with: true } => ("depth target", "with (default)", "the default row's scene"),
        Case::Depth { with: false } => (
            "depth target",
            "none",
            if model_err.is_some_and(|e| e <= 1) {
                "no depth image: each surface lies at its far plane (100 and 200 away), so the first shows everywhere; the f64 reference given no depth agrees within 1"
            } else {
                "no depth image: each surface lies at its far plane (100 and 200 away), so the first shows everywhere; the f64 reference given no depth differs by more than 1"
            },
        ),
    };
    Ok(Row {
        knob,
        setting,
        surfaces: layers_count(case, s.surfaces),
        depth_format: if with_depth { s.storage.name() } else { "none" },
        reversed: false,
        declared: true,
        lit: true,
        normals: "per-surface",
        max_textures: None,
        intermediate: "rgba8",
        passes,
        chained_cells: chained,
        ms,
        depth_err_max,
        depth_err_p99,
        line_pixels,
        wrong_line,
        wrong_all,
        stored_wrong_line: None,
        colour_err_max: max,
        colour_err_mean: sum as f64 / got.len().max(1) as f64,
        note,
    })
}

/// Surfaces composited in `case`.
fn layers_count(case: Case, surfaces: usize) -> usize {
    match case {
        Case::Cover { .. } => surfaces + 1,
        Case::Depth { .. } => surfaces,
    }
}

/// Max and sum of |a − b| over the bytes.
fn diff(a: &[u8], b: &[u8]) -> (u8, u64) {
    a.iter().zip(b).fold((0u8, 0u64), |(m, t), (&x, &y)| (m.max(x.abs_diff(y)), t + u64::from(x.abs_diff(y))))
}

/// Uploads RGBA8 `rgba` (rows bottom first) into `t`.
fn write_rgba(gpu: &Gpu, t: &wgpu::Texture, rgba: &[u8]) {
    gpu.write_texture(
        t.as_image_copy(),
        rgba,
        wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(t.width() * 4), rows_per_image: None },
        t.size(),
    );
}
