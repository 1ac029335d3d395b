//! The shader floor of a composite: one pass, on the same device, that loads every surface's
//! colour and depth at each pixel and keeps the nearest colour, and nothing else (no cells, no
//! chaining, no lighting, no blending). What a composite takes beyond it is what its lighting,
//! chaining and planning add.

use strata_device::{texture_entry, Gpu, UNFILTERED};

/// The floor pass for `k` surfaces, or `None` when the device cannot sample their `2k`
/// textures in one pass.
pub(super) struct Floor {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

/// The WGSL of the floor pass over `k` surfaces.
fn wgsl(k: usize) -> String {
    let mut s = String::new();
    for i in 0..k {
        s += &format!(
            "@group(0) @binding({}) var c{i}: texture_2d<f32>;\n@group(0) @binding({}) var d{i}: texture_depth_2d;\n",
            2 * i,
            2 * i + 1
        );
    }
    s += "@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {\n";
    s += "    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));\n";
    s += "    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);\n}\n";
    s += "@fragment fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {\n";
    s += "    let q = vec2<i32>(p.xy);\n";
    s += "    var best = textureLoad(d0, q, 0);\n    var col = textureLoad(c0, q, 0);\n";
    for i in 1..k {
        s += &format!(
            "    {{ let d = textureLoad(d{i}, q, 0); let c = textureLoad(c{i}, q, 0); let nearer = d < best; \
             best = select(best, d, nearer); col = select(col, c, nearer); }}\n"
        );
    }
    s += "    return col;\n}\n";
    s
}

impl Floor {
    /// The floor pass over `k` surfaces on `gpu`, writing `format`.
    pub(super) fn new(gpu: &Gpu, k: usize, format: wgpu::TextureFormat) -> Option<Floor> {
        if k == 0 || 2 * k as u64 > u64::from(gpu.limits.max_sampled_textures_per_shader_stage) {
            return None;
        }
        let entries: Vec<wgpu::BindGroupLayoutEntry> = (0..k)
            .flat_map(|i| {
                [
                    texture_entry(2 * i as u32, UNFILTERED),
                    texture_entry(2 * i as u32 + 1, wgpu::TextureSampleType::Depth),
                ]
            })
            .collect();
        let target = wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL };
        let (layout, pipeline) = gpu.pipeline(
            "composite floor",
            wgpu::ShaderSource::Wgsl(wgsl(k).into()),
            &entries,
            &[Some(target)],
            None,
            strata_device::VertexInput::None,
        );
        Some(Floor { layout, pipeline })
    }

    /// Draws the pass over the surfaces' `(colour, depth)` views into `out` and waits for it.
    pub(super) fn run(
        &self,
        gpu: &Gpu,
        surfaces: &[(&wgpu::TextureView, &wgpu::TextureView)],
        out: &wgpu::TextureView,
    ) {
        let entries: Vec<wgpu::BindGroupEntry<'_>> = surfaces
            .iter()
            .enumerate()
            .flat_map(|(i, (c, d))| {
                [
                    wgpu::BindGroupEntry { binding: 2 * i as u32, resource: wgpu::BindingResource::TextureView(c) },
                    wgpu::BindGroupEntry { binding: 2 * i as u32 + 1, resource: wgpu::BindingResource::TextureView(d) },
                ]
            })
            .collect();
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &self.layout,
            entries: &entries,
        });
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        strata_device::fullscreen_pass(&mut enc, "composite floor", out, &self.pipeline, &group);
        gpu.submit(&gpu.lane, vec![enc.finish()]);
        let _ = gpu.device.poll(wgpu::PollType::wait_indefinitely());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_floor_keeps_the_nearest_of_every_surface() {
        let s = wgsl(3);
        assert_eq!(s.matches("textureLoad(d").count(), 3, "every depth is loaded");
        assert_eq!(s.matches("textureLoad(c").count(), 3, "every colour is loaded");
        assert!(s.contains("let nearer = d < best"));
    }
}
