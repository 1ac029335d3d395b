//! Passes: draws to one target accumulate in one render pass, with their uniforms and generated
//! vertex data in one per-pass staging area, until the target changes or something forces a
//! submission; then the staging area is uploaded in one write and the pass is encoded.

use std::collections::HashMap;
use std::sync::Arc;

use crate::enums::*;
use crate::error::error_chain;
use crate::glsl::types::Ty;
use crate::render::occlusion::{Occlusion, PassQueries};
use crate::render::pass::{offset_of, Bind, Pass, Recorded};
use crate::render::targets::stored;
use crate::render::{DrawSpec, RasterState, Renderer, SamplerState, Source, Target};

impl Renderer {
    /// Whether draws are recorded but not yet submitted.
    pub fn pending(&self) -> bool {
        self.pass.as_ref().is_some_and(|p| {
            !p.draws.is_empty() || p.clear_color.is_some() || p.clear_depth.is_some() || p.clear_stencil.is_some()
        })
    }

    /// Whether the open pass has draws that count for occlusion query `q`.
    pub fn counts_for(&self, q: &Arc<Occlusion>) -> bool {
        self.pass.as_ref().is_some_and(|p| p.draws.iter().any(|r| r.query.as_ref().is_some_and(|d| Arc::ptr_eq(d, q))))
    }

    /// The open pass for `target`; a pass open for another target is submitted first.
    pub(super) fn pass_for(&mut self, target: &Target) -> &mut Pass {
        if self.pass.as_ref().is_some_and(|p| p.target.key != target.key) {
            self.flush();
        }
        self.pass.get_or_insert_with(|| Pass {
            target: target.clone(),
            clear_color: None,
            clear_depth: None,
            clear_stencil: None,
            draws: Vec::new(),
        })
    }

    /// Records a validated draw into the target's pass.
    pub fn draw(&mut self, target: &Target, spec: DrawSpec<'_>) {
        // A capturing draw has a pass of its own: the buffers it writes as storage may be read
        // as vertices, indices or uniforms by the draws before and after it.
        let capturing = spec.capture.is_some();
        if capturing {
            self.flush();
        }
        self.record(target, spec);
        if capturing {
            self.flush();
        }
    }

    /// Records a validated draw into the target's pass: twice where the back face has stencil
    /// values of its own (front faces, then back faces, each with theirs).
    fn record(&mut self, target: &Target, mut spec: DrawSpec<'_>) {
        let depth_mask = spec
            .textures
            .iter()
            .enumerate()
            .filter(|(_, t)| t.as_ref().is_some_and(|t| t.3))
            .fold(0u32, |m, (i, _)| m | (1 << i));
        // The back faces' pipeline (front faces culled, the back face's masks), where they
        // have stencil values of their own; the draw itself then draws front faces only.
        let back = match spec.back_stencil.filter(|_| spec.capture.is_none()) {
            Some((reference, read, write)) => {
                let front = spec.raster.clone();
                spec.raster.cull = Some(wgpu::Face::Front);
                if let Some(s) = spec.raster.stencil.as_mut() {
                    (s.read_mask, s.write_mask) = (read, write);
                }
                let pipeline = self.pipeline(&spec, target, depth_mask);
                spec.raster = RasterState { cull: Some(wgpu::Face::Back), ..front };
                Some((pipeline, reference))
            }
            None => None,
        };
        let pipeline = self.pipeline(&spec, target, depth_mask);
        let (layout, _) = self.layouts(&spec.program, depth_mask);
        // Open the target's pass first: switching targets flushes the previous pass, which
        // uploads and empties the staging area, so this draw's data must go in after that.
        self.pass_for(target);
        let uniform =
            (!spec.uniforms.is_empty()).then(|| offset_of(&mut self.staging, &spec.uniforms, self.align) as u32);
        let mut textures = Vec::with_capacity(spec.textures.len());
        for (i, t) in spec.textures.iter().enumerate() {
            let ty = spec.program.info.samplers.get(i).map(|s| s.0);
            match t {
                Some((view, uid, state, unfilterable)) => {
                    // Images that cannot be filtered are read with a non-filtering sampler:
                    // nearest filters, nearest mipmap.
                    let state = if ty.is_some_and(Ty::is_shadow) {
                        // Shadow lookups clamp their levels of detail themselves and read the
                        // level they choose (`glsl::shadow`).
                        let min = if state.uses_mipmaps() { NEAREST_MIPMAP_NEAREST } else { NEAREST };
                        let (min_lod, max_lod) = (0.0f32.to_bits(), 1000.0f32.to_bits());
                        SamplerState { min, mag: NEAREST, min_lod, max_lod, ..*state }
                    } else if *unfilterable {
                        let min = if state.uses_mipmaps() { NEAREST_MIPMAP_NEAREST } else { NEAREST };
                        SamplerState { min, mag: NEAREST, ..*state }
                    } else {
                        *state
                    };
                    textures.push((view.clone(), *uid, self.sampler(state, false), state, self.sampler(state, true)))
                }
                None => {
                    let int = ty.and_then(Ty::int_sampler);
                    let (view, uid) = match ty.map(Ty::sampler_base) {
                        Some(t) if int.is_some() => {
                            let signed = int == Some(true);
                            let dim = match t {
                                Ty::Sampler2D => 0,
                                Ty::Sampler3D => 1,
                                _ => 2,
                            };
                            (
                                self.fixed.black_int[usize::from(signed)][dim].clone(),
                                u64::MAX - 4 - 3 * u64::from(signed) - dim as u64,
                            )
                        }
                        Some(Ty::SamplerCube | Ty::SamplerCubeShadow) => (self.fixed.black_cube.clone(), u64::MAX - 1),
                        Some(Ty::Sampler3D) => (self.fixed.black_3d.clone(), u64::MAX - 2),
                        Some(Ty::Sampler2DArray | Ty::Sampler2DArrayShadow) => {
                            (self.fixed.black_array.clone(), u64::MAX - 3)
                        }
                        _ => (self.fixed.black_2d.clone(), u64::MAX),
                    };
                    // Integer samplers bind non-filtering samplers.
                    let s = match int {
                        Some(_) => SamplerState { min: NEAREST, mag: NEAREST, ..SamplerState::default() },
                        None => SamplerState::default(),
                    };
                    textures.push((view, uid, self.sampler(s, false), s, self.sampler(s, true)));
                }
            }
        }
        let blocks: Vec<(wgpu::Buffer, u64)> =
            spec.blocks.into_iter().map(|b| b.unwrap_or_else(|| (self.fixed.zero_block.clone(), 0))).collect();
        let capture = spec.program.info.capture.as_ref().map(|c| match spec.capture {
            Some((params, buffers)) => {
                use wgpu::util::DeviceExt;
                let block = self.gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("capture numbers"),
                    contents: &params,
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                (block, buffers)
            }
            None => (self.fixed.zero_block.clone(), self.fixed.unused_capture[..c.strides.len()].to_vec()),
        });
        let align = 4;
        let mut vertex = Vec::with_capacity(spec.inputs.len());
        for i in spec.inputs {
            match i.source {
                Source::Buffer(b, off) => vertex.push((Source::Buffer(b, off), 0)),
                Source::Bytes(bytes) => {
                    let off = offset_of(&mut self.staging, &bytes, align);
                    vertex.push((Source::Bytes(Vec::new()), off));
                }
            }
        }
        let index = spec.index.map(|(src, fmt)| match src {
            Source::Buffer(b, off) => (Source::Buffer(b, off), 0, fmt),
            Source::Bytes(bytes) => {
                let off = offset_of(&mut self.staging, &bytes, align);
                (Source::Bytes(Vec::new()), off, fmt)
            }
        });
        self.draws += 1;
        let rec = Recorded {
            pipeline,
            bind: Bind::Program { program: spec.program, layout, uniform, textures, blocks, capture },
            vertex,
            index,
            count: spec.count,
            first: spec.first,
            instances: spec.instances,
            viewport: spec.viewport,
            scissor: spec.scissor,
            stencil_ref: spec.stencil_ref,
            blend_color: spec.blend_color,
            query: self.occlusion.clone(),
        };
        if let Some((pipeline, stencil_ref)) = back {
            let back = Recorded { pipeline, stencil_ref, ..rec.clone() };
            self.pass_for(target).draws.push(rec);
            self.pass_for(target).draws.push(back);
            return;
        }
        self.pass_for(target).draws.push(rec);
    }

    /// Encodes and submits the open pass. A GPU validation error is queued in `errors`.
    pub fn flush(&mut self) {
        let Some(pass) = self.pass.take() else { return };
        self.passes += 1;
        let guard = self.gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        self.upload_staging();
        let ring = self.ring.as_ref().map(|(b, _)| b.clone());
        let groups = self.bind_groups(&pass, ring.as_ref());
        let mut enc =
            self.gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("gles pass") });
        let queries = PassQueries::new(&self.gpu, pass.draws.iter().filter_map(|r| r.query.clone()).collect());
        encode(&mut enc, &pass, &groups, ring.as_ref(), queries.as_ref());
        if let Some(q) = &queries {
            q.resolve(&mut enc);
        }
        self.gpu.submit(&self.lane, vec![enc.finish()]);
        if let Some(q) = queries {
            q.read_back();
        }
        if let Some(e) = pollster::block_on(guard.pop()) {
            self.errors.push(error_chain(&e));
        }
    }

    /// Uploads this pass's uniforms and generated vertex data in one write, growing the ring
    /// if they do not fit.
    fn upload_staging(&mut self) {
        let d = &self.gpu.device;
        if !self.staging.is_empty() {
            let need = (self.staging.len() as u64).div_ceil(256) * 256;
            if self.ring.as_ref().is_none_or(|(_, cap)| *cap < need) {
                let cap = need.next_power_of_two().max(64 << 10);
                let buf = d.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("per-pass ring"),
                    size: cap,
                    usage: wgpu::BufferUsages::UNIFORM
                        | wgpu::BufferUsages::VERTEX
                        | wgpu::BufferUsages::INDEX
                        | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                self.ring = Some((buf, cap));
            }
            self.staging.resize(need as usize, 0);
            if let Some((ring, _)) = &self.ring {
                self.gpu.write_buffer(ring, 0, &self.staging);
            }
            self.staging.clear();
        }
    }

    /// The bind group of each recorded draw (`None`: it binds nothing), created once per
    /// program and texture set within the pass.
    fn bind_groups(&self, pass: &Pass, ring: Option<&wgpu::Buffer>) -> Vec<Option<wgpu::BindGroup>> {
        let d = &self.gpu.device;
        let mut groups: Vec<Option<wgpu::BindGroup>> = Vec::with_capacity(pass.draws.len());
        type Key = (u64, Vec<(u64, SamplerState)>, Vec<(wgpu::Buffer, u64)>);
        // A wgpu::Buffer hashes and compares by its id, which never changes.
        #[allow(clippy::mutable_key_type)]
        let mut cache: HashMap<Key, wgpu::BindGroup> = HashMap::new();
        let mut clear_group: Option<wgpu::BindGroup> = None;
        for r in &pass.draws {
            let g = match &r.bind {
                Bind::Clear(_) => {
                    if clear_group.is_none() {
                        if let Some(ring) = ring {
                            clear_group = Some(d.create_bind_group(&wgpu::BindGroupDescriptor {
                                label: Some("clear"),
                                layout: &self.fixed.clear_bgl,
                                entries: &[wgpu::BindGroupEntry {
                                    binding: 0,
                                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                                        buffer: ring,
                                        offset: 0,
                                        size: wgpu::BufferSize::new(crate::render::pass::CLEAR_PARAMS),
                                    }),
                                }],
                            }));
                        }
                    }
                    clear_group.clone()
                }
                Bind::Program { program, layout, uniform, textures, blocks, capture } => {
                    if uniform.is_none() && textures.is_empty() && blocks.is_empty() && capture.is_none() {
                        None
                    } else {
                        let mut key =
                            (program.id, textures.iter().map(|t| (t.1, t.3)).collect::<Vec<_>>(), blocks.clone());
                        if let Some((block, buffers)) = capture {
                            // Captures are in passes of their own: these tell them apart anyway.
                            key.2.push((block.clone(), u64::MAX));
                            key.2.extend(buffers.iter().map(|b| (b.clone(), u64::MAX - 1)));
                        }
                        if let Some(g) = cache.get(&key) {
                            Some(g.clone())
                        } else {
                            let mut entries = Vec::new();
                            if let (Some(_), Some(ring)) = (uniform, ring) {
                                entries.push(wgpu::BindGroupEntry {
                                    binding: 0,
                                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                                        buffer: ring,
                                        offset: 0,
                                        size: wgpu::BufferSize::new(u64::from(program.info.block_size)),
                                    }),
                                });
                            }
                            for (i, t) in textures.iter().enumerate() {
                                let b = program.info.samplers[i].1;
                                entries.push(wgpu::BindGroupEntry {
                                    binding: b,
                                    resource: wgpu::BindingResource::TextureView(&t.0),
                                });
                                entries.push(wgpu::BindGroupEntry {
                                    binding: b + 1,
                                    resource: wgpu::BindingResource::Sampler(&t.2),
                                });
                                entries.push(wgpu::BindGroupEntry {
                                    binding: b + 2,
                                    resource: wgpu::BindingResource::Sampler(&t.4),
                                });
                            }
                            for ((buffer, offset), b) in blocks.iter().zip(&program.info.blocks) {
                                entries.push(wgpu::BindGroupEntry {
                                    binding: b.binding,
                                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                                        buffer,
                                        offset: *offset,
                                        size: wgpu::BufferSize::new(u64::from(b.block.size)),
                                    }),
                                });
                            }
                            if let Some((block, buffers)) = capture {
                                entries.push(wgpu::BindGroupEntry {
                                    binding: crate::glsl::capture::PARAMS_BINDING,
                                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                                        buffer: block,
                                        offset: 0,
                                        size: wgpu::BufferSize::new(crate::glsl::capture::PARAMS_SIZE),
                                    }),
                                });
                                for (b, buffer) in buffers.iter().enumerate() {
                                    entries.push(wgpu::BindGroupEntry {
                                        binding: crate::glsl::capture::FIRST_BUFFER_BINDING + b as u32,
                                        resource: buffer.as_entire_binding(),
                                    });
                                }
                            }
                            let g = d.create_bind_group(&wgpu::BindGroupDescriptor {
                                label: None,
                                layout,
                                entries: &entries,
                            });
                            cache.insert(key, g.clone());
                            Some(g)
                        }
                    }
                }
            };
            groups.push(g);
        }
        groups
    }
}

/// Encodes `pass` with the bind groups from `bind_groups`, the ring holding its staged data,
/// and the query set its queried draws count into.
fn encode(
    enc: &mut wgpu::CommandEncoder,
    pass: &Pass,
    groups: &[Option<wgpu::BindGroup>],
    ring: Option<&wgpu::Buffer>,
    queries: Option<&PassQueries>,
) {
    let t = &pass.target;
    let colors: Vec<Option<wgpu::RenderPassColorAttachment<'_>>> = t
        .slots()
        .into_iter()
        .enumerate()
        .map(|(i, s)| {
            s.map(|(view, absent, _)| {
                let load = match pass.clear_color {
                    Some(c) => {
                        let [r, g, b, a] = stored(absent, c).map(f64::from);
                        wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a })
                    }
                    None => wgpu::LoadOp::Load,
                };
                wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: t.slices.get(i).copied().flatten(),
                    resolve_target: None,
                    ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
                }
            })
        })
        .collect();
    let depth = t.depth.as_ref().map(|(view, f)| wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: f.has_depth_aspect().then(|| wgpu::Operations {
            load: pass.clear_depth.map(wgpu::LoadOp::Clear).unwrap_or(wgpu::LoadOp::Load),
            store: wgpu::StoreOp::Store,
        }),
        stencil_ops: f.has_stencil_aspect().then(|| wgpu::Operations {
            load: pass.clear_stencil.map(wgpu::LoadOp::Clear).unwrap_or(wgpu::LoadOp::Load),
            store: wgpu::StoreOp::Store,
        }),
    });
    let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("gles"),
        color_attachments: if t.has_color() { &colors } else { &[] },
        depth_stencil_attachment: depth,
        timestamp_writes: None,
        occlusion_query_set: queries.map(PassQueries::set),
        multiview_mask: None,
    });
    let mut slot = 0;
    for (r, g) in pass.draws.iter().zip(groups) {
        // Every queried draw has its slot, counted even where nothing is drawn.
        let queried = r.query.is_some() && queries.is_some();
        if queried {
            rp.begin_occlusion_query(slot);
            slot += 1;
        }
        let [sx, sy, sw, sh] = r.scissor;
        if sw == 0 || sh == 0 {
            if queried {
                rp.end_occlusion_query();
            }
            continue;
        }
        rp.set_pipeline(&r.pipeline);
        match (&r.bind, g) {
            (Bind::Clear(off), Some(g)) => rp.set_bind_group(0, g, &[*off]),
            (Bind::Program { uniform: Some(off), .. }, Some(g)) => rp.set_bind_group(0, g, &[*off]),
            (Bind::Program { uniform: None, .. }, Some(g)) => rp.set_bind_group(0, g, &[]),
            _ => {}
        }
        for (slot, (src, off)) in r.vertex.iter().enumerate() {
            match src {
                Source::Buffer(b, o) => rp.set_vertex_buffer(slot as u32, b.slice(*o..)),
                Source::Bytes(_) => {
                    if let Some(ring) = ring {
                        rp.set_vertex_buffer(slot as u32, ring.slice(*off..));
                    }
                }
            }
        }
        let [x, y, w, h, n, f] = r.viewport;
        rp.set_viewport(x, y, w, h, n, f);
        rp.set_scissor_rect(sx, sy, sw, sh);
        rp.set_stencil_reference(r.stencil_ref);
        let [br, bg, bb, ba] = r.blend_color;
        rp.set_blend_constant(wgpu::Color { r: br, g: bg, b: bb, a: ba });
        let (i0, n) = r.instances;
        match &r.index {
            Some((src, off, fmt)) => {
                match src {
                    Source::Buffer(b, o) => rp.set_index_buffer(b.slice(*o..), *fmt),
                    Source::Bytes(_) => {
                        if let Some(ring) = ring {
                            rp.set_index_buffer(ring.slice(*off..), *fmt);
                        }
                    }
                }
                rp.draw_indexed(0..r.count, 0, i0..i0 + n);
            }
            None => {
                rp.draw(r.first..r.first + r.count, i0..i0 + n);
            }
        }
        if queried {
            rp.end_occlusion_query();
        }
    }
}
