//! Clears: a clear of the whole target before any draw becomes the pass's load operations;
//! any other clear is a quad that honours the scissor and the write masks.

use crate::render::keys::ClearKey;
use crate::render::pass::CLEAR_PARAMS;
use crate::render::pass::{offset_of, Bind, Recorded};
use crate::render::targets::stored;
use crate::render::{Renderer, Target};

impl Renderer {
    /// `glClear` of the target's colour slots to `color` (as each image stores it: see
    /// [`stored`]; `glClearBuffer*` names one slot, and the others keep their contents), its
    /// depth and its stencil. A clear of the whole target with full masks becomes the pass's
    /// load operations when nothing has been drawn yet.
    #[allow(clippy::too_many_arguments)]
    pub fn clear(
        &mut self,
        target: &Target,
        color: Option<([f32; 4], wgpu::ColorWrites, Option<usize>)>,
        depth: Option<(f32, bool)>,
        stencil: Option<(u32, u32)>,
        scissor: Option<[u32; 4]>,
    ) {
        let full_color = color.is_none_or(|(_, m, only)| m == wgpu::ColorWrites::ALL && only.is_none());
        let full_depth = depth.is_none_or(|(_, w)| w);
        let full_stencil = stencil.is_none_or(|(_, m)| m & 0xff == 0xff);
        let whole = scissor.is_none_or(|s| s == [0, 0, target.width, target.height]);
        // Integer colour buffers clear only through the quad, which writes them integers.
        let int_slots = target.slots().iter().any(|s| s.is_some_and(|s| is_int(s.2)));
        let pass = self.pass_for(target);
        if pass.draws.is_empty() && full_color && full_depth && full_stencil && whole && !int_slots {
            if let Some((c, _, _)) = color {
                pass.clear_color = Some(c);
            }
            if let Some((d, _)) = depth {
                pass.clear_depth = Some(d.clamp(0.0, 1.0));
            }
            if let Some((s, _)) = stencil {
                pass.clear_stencil = Some(s & 0xff);
            }
            return;
        }
        // A quad that honours masks and the scissor.
        let key = ClearKey {
            color: color.map(|(_, m, _)| m),
            only: color.and_then(|(_, _, only)| only),
            depth: target.depth.as_ref().map(|(_, f)| {
                (
                    *f,
                    depth.is_some_and(|(_, w)| w) && f.has_depth_aspect(),
                    stencil.filter(|_| target.has_stencil()).map(|(_, m)| m),
                )
            }),
            slots: target.slots().iter().map(|s| s.map(|s| s.2)).collect(),
            samples: target.samples,
        };
        let pipeline = self.clear_pipeline(&key);
        let mut params = [0u8; CLEAR_PARAMS as usize];
        let c = color.map(|(c, _, _)| c).unwrap_or([0.0; 4]);
        for (slot, s) in target.slots().iter().enumerate() {
            let absent = s.map_or(wgpu::ColorWrites::empty(), |s| s.1);
            // An integer clear's value is the integers' bits (`glClearBuffer{i,ui}v`).
            let c = match s.is_some_and(|s| is_int(s.2)) {
                true => crate::integer::present(c.map(f32::to_bits), absent).map(f32::from_bits),
                false => stored(absent, c),
            };
            for (i, v) in c.iter().enumerate() {
                let at = slot * 16 + i * 4;
                params[at..at + 4].copy_from_slice(&v.to_ne_bytes());
            }
        }
        params[128..132].copy_from_slice(&depth.map(|(d, _)| d.clamp(0.0, 1.0)).unwrap_or(0.0).to_ne_bytes());
        let off = offset_of(&mut self.staging, &params, self.align) as u32;
        let scissor = scissor.unwrap_or([0, 0, target.width, target.height]);
        let pass = self.pass_for(target);
        pass.draws.push(Recorded {
            pipeline,
            bind: Bind::Clear(off),
            vertex: Vec::new(),
            index: None,
            count: 3,
            first: 0,
            instances: (0, 1),
            viewport: [0.0, 0.0, target.width as f32, target.height as f32, 0.0, 1.0],
            scissor,
            stencil_ref: stencil.map(|(s, _)| s).unwrap_or(0),
            blend_color: [0.0; 4],
            // Clears are no draws: an occlusion query does not count them.
            query: None,
        });
    }

    fn clear_pipeline(&mut self, key: &ClearKey) -> wgpu::RenderPipeline {
        if let Some(p) = self.clear_pipelines.get(key) {
            return p.clone();
        }
        // Compiled once for all clients (each compile costs the driver memory it keeps).
        if let Some(p) = self.fixed.clear_pipelines.lock().ok().and_then(|m| m.get(key).cloned()) {
            self.clear_pipelines.insert(key.clone(), p.clone());
            return p;
        }
        let write_mask = key.color.unwrap_or(wgpu::ColorWrites::empty());
        let targets: Vec<Option<wgpu::ColorTargetState>> = key
            .slots
            .iter()
            .enumerate()
            .map(|(i, s)| {
                // `glClear` leaves integer buffers alone (their clear is undefined in ES 3.0).
                let int = s.is_some_and(is_int);
                let cleared = if int { key.only == Some(i) } else { key.only.is_none_or(|o| o == i) };
                let write_mask = if cleared { write_mask } else { wgpu::ColorWrites::empty() };
                s.map(|format| wgpu::ColorTargetState { format, blend: None, write_mask })
            })
            .collect();
        let depth_stencil = key.depth.map(|(format, write, stencil)| {
            let face = wgpu::StencilFaceState {
                compare: wgpu::CompareFunction::Always,
                fail_op: wgpu::StencilOperation::Keep,
                depth_fail_op: wgpu::StencilOperation::Keep,
                pass_op: wgpu::StencilOperation::Replace,
            };
            wgpu::DepthStencilState {
                format,
                depth_write_enabled: Some(write),
                depth_compare: Some(wgpu::CompareFunction::Always),
                stencil: match stencil {
                    Some(mask) => wgpu::StencilState { front: face, back: face, read_mask: 0xff, write_mask: mask },
                    None => Default::default(),
                },
                bias: Default::default(),
            }
        });
        // Integer buffers need outputs of their own kind.
        let module = match key.slots.iter().any(|s| s.is_some_and(is_int)) {
            true => self.gpu.device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("integer clear"),
                source: wgpu::ShaderSource::Wgsl(int_clear_source(&key.slots).into()),
            }),
            false => self.fixed.clear_module.clone(),
        };
        let p = self.gpu.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("clear"),
            layout: Some(&self.fixed.clear_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil,
            multisample: wgpu::MultisampleState { count: key.samples, ..Default::default() },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: if key.slots.iter().any(Option::is_some) { &targets } else { &[] },
            }),
            multiview_mask: None,
            cache: None,
        });
        self.clear_pipelines.insert(key.clone(), p.clone());
        if let Ok(mut shared) = self.fixed.clear_pipelines.lock() {
            shared.insert(key.clone(), p.clone());
        }
        p
    }
}

/// Whether a colour buffer of `format` holds integers.
fn is_int(format: wgpu::TextureFormat) -> bool {
    matches!(format.sample_type(None, None), Some(wgpu::TextureSampleType::Sint | wgpu::TextureSampleType::Uint))
}

/// The clear shader (`shaders/clear.wgsl`) with each colour slot's output of its buffer's
/// kind: an integer buffer's the clear value's bits as integers.
fn int_clear_source(slots: &[Option<wgpu::TextureFormat>]) -> String {
    let base = include_str!("../../../shaders/clear.wgsl");
    let mut fields = String::new();
    let mut values = Vec::new();
    for i in 0..8 {
        let ty = match slots.get(i).copied().flatten().and_then(|f| f.sample_type(None, None)) {
            Some(wgpu::TextureSampleType::Sint) => "vec4<i32>",
            Some(wgpu::TextureSampleType::Uint) => "vec4<u32>",
            _ => "vec4<f32>",
        };
        fields.push_str(&format!("    @location({i}) c{i}: {ty},\n"));
        values.push(if ty == "vec4<f32>" { format!("c[{i}]") } else { format!("bitcast<{ty}>(c[{i}])") });
    }
    let start = base.find("struct Out {").unwrap_or(0);
    let end = base[start..].find("};").map_or(base.len(), |e| start + e + 2);
    let out = format!("struct Out {{\n{fields}}};");
    let source = format!("{}{out}{}", &base[..start], &base[end..]);
    source.replace("Out(c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7])", &format!("Out({})", values.join(", ")))
}
