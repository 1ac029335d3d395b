//! Turns a plan into render passes: the uniform blocks and cell rectangles of every draw,
//! gathered into two uploads, and the bind groups they need.

use std::ops::Range;

use crate::inputs::{PassInputs, Texture};
use crate::kind::{Geom, PassKind};
use crate::plan::{chunks, GroupPlan, Rect};
use crate::resources::{block_size, Resources, PARAMS_SIZE};
use crate::{Layer, Lighting, NormalSource};

/// The largest side of an intermediate: chained cells are processed in tiles of at most this
/// size, so a chain's memory is bounded whatever the output's size.
pub const CHAIN_TILE: i32 = 2048;

/// One draw: a pass shape (`None`: the background fill) over some cells.
pub struct DrawOp {
    /// The shape.
    pub kind: Option<PassKind>,
    /// The images it binds, in the order of its `PassInputs::textures`.
    pub views: Vec<wgpu::TextureView>,
    /// Offset of its uniform block.
    pub block: u32,
    /// Its cells in the instance buffer.
    pub instances: Range<u32>,
}

/// One render pass: into the output (`None`), or other images (an intermediate's colour and
/// geometry, a light map).
pub struct PassOp {
    /// The render target.
    pub target: Option<Vec<wgpu::TextureView>>,
    /// Its draws, in order.
    pub draws: Vec<DrawOp>,
}

/// Collects a composite's passes, uniform blocks and cells.
pub struct Builder<'a> {
    /// Every layer of the composite.
    pub layers: &'a [Layer<'a>],
    /// Output size.
    pub size: (u32, u32),
    /// Surfaces per pass.
    pub per_pass: usize,
    /// The lighting in force.
    pub light: &'a Lighting,
    /// The uniform buffer's bytes.
    pub uniforms: Vec<u8>,
    /// The cells' clip-space rectangles.
    pub instances: Vec<f32>,
    /// The passes so far.
    pub passes: Vec<PassOp>,
    /// Dynamic-offset alignment.
    pub align: u64,
    /// Cells that needed the depth select, and those that chained.
    pub selects: usize,
    /// Cells (per group) that chained.
    pub chained: usize,
    /// Light maps by the bits of their unit normal.
    pub maps: Vec<([u32; 3], wgpu::TextureView)>,
}

/// `n` scaled to unit length, or zero (also for a non-finite length), as lighting uses it.
pub fn unit_normal(n: [f32; 3]) -> [f32; 3] {
    let n = n.map(f64::from);
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 && len.is_finite() {
        n.map(|v| (v / len) as f32)
    } else {
        [0.0; 3]
    }
}

/// A surface's entry in a uniform block (`Surf`, `SURF_SIZE` bytes): rectangle, source region,
/// unit normal (or zero) and has-depth flag, projection, image size and opacity.
fn surf_bytes(l: &Layer<'_>, out: &mut Vec<u8>) {
    let unit = unit_normal(l.normal);
    let source = l.props.source_for(l.rect);
    out.extend_from_slice(bytemuck::cast_slice(&l.rect));
    out.extend_from_slice(bytemuck::cast_slice(&source.region));
    out.extend_from_slice(bytemuck::cast_slice(&[
        unit[0],
        unit[1],
        unit[2],
        if l.depth.is_some() { 1.0 } else { 0.0 },
    ]));
    out.extend_from_slice(bytemuck::cast_slice(&l.projection));
    out.extend_from_slice(bytemuck::cast_slice(&[
        source.image[0] as f32,
        source.image[1] as f32,
        l.props.opacity.clamp(0.0, 1.0),
        0.0,
    ]));
}

impl<'a> Builder<'a> {
    /// A builder whose uniform buffer starts with the lighting and the background.
    pub fn new(
        layers: &'a [Layer<'a>],
        size: (u32, u32),
        per_pass: usize,
        light: &'a Lighting,
        background: [f32; 4],
        align: u64,
    ) -> Self {
        let a = background[3];
        let params: [f32; 20] = [
            light.position[0],
            light.position[1],
            light.position[2],
            0.0,
            light.color[0],
            light.color[1],
            light.color[2],
            light.depth_normal_scale,
            light.view[0],
            light.view[1],
            light.view[2],
            0.0,
            light.ambient,
            light.shininess,
            size.0 as f32,
            size.1 as f32,
            background[0] * a,
            background[1] * a,
            background[2] * a,
            a,
        ];
        let mut uniforms = Vec::with_capacity(4096);
        uniforms.extend_from_slice(bytemuck::cast_slice(&params));
        debug_assert_eq!(uniforms.len() as u64, PARAMS_SIZE);
        Builder {
            layers,
            size,
            per_pass,
            light,
            uniforms,
            instances: Vec::new(),
            passes: Vec::new(),
            align,
            selects: 0,
            chained: 0,
            maps: Vec::new(),
        }
    }

    /// Appends `rects` (output pixels) as clip-space rectangles of a target whose origin is
    /// `origin` and whose size is `size`.
    fn rects(&mut self, rects: &[Rect], origin: [i32; 2], size: (u32, u32)) -> Range<u32> {
        let first = (self.instances.len() / 4) as u32;
        let (w, h) = (f64::from(size.0), f64::from(size.1));
        for r in rects {
            let x = |v: i32| (f64::from(v - origin[0]) / w * 2.0 - 1.0) as f32;
            let y = |v: i32| (1.0 - f64::from(v - origin[1]) / h * 2.0) as f32;
            self.instances.extend_from_slice(&[x(r[0]), y(r[1]), x(r[2]), y(r[3])]);
        }
        first..(self.instances.len() / 4) as u32
    }

    /// Draws the light map `view` of unit normal `n` (before everything else).
    pub fn light_map(&mut self, n: [f32; 3], view: wgpu::TextureView) {
        let at = self.uniforms.len().next_multiple_of(self.align as usize);
        self.uniforms.resize(at, 0);
        // The origins and one `Surf`: no rectangle or source, the normal, no projection, no
        // image.
        self.uniforms.extend_from_slice(bytemuck::cast_slice(&[0i32; 12]));
        self.uniforms.extend_from_slice(bytemuck::cast_slice(&[n[0], n[1], n[2], 0.0]));
        self.uniforms.extend_from_slice(bytemuck::cast_slice(&[0.0f32; 8]));
        debug_assert_eq!((self.uniforms.len() - at) as u64, block_size(1));
        let instances = self.rects(&[[0, 0, self.size.0 as i32, self.size.1 as i32]], [0, 0], self.size);
        let draw = DrawOp { kind: Some(PassKind::light_map()), views: Vec::new(), block: at as u32, instances };
        self.passes.push(PassOp { target: Some(vec![view]), draws: vec![draw] });
    }

    /// Appends a uniform block: the target's and the intermediate's origins, then `members`.
    fn block(&mut self, target: [i32; 2], inter: [i32; 2], members: &[u32]) -> u32 {
        let at = self.uniforms.len().next_multiple_of(self.align as usize);
        self.uniforms.resize(at, 0);
        self.uniforms.extend_from_slice(bytemuck::cast_slice(&[target[0], target[1], inter[0], inter[1]]));
        for &m in members {
            surf_bytes(&self.layers[m as usize], &mut self.uniforms);
        }
        debug_assert_eq!((self.uniforms.len() - at) as u64, block_size(members.len()));
        at as u32
    }

    /// The images a draw of `kind` over `members` binds, walking its inputs: the members'
    /// colour and depth (the placeholder where a surface has none), the intermediate it
    /// `reads` (colour, geometry), the light `map`. An image the draw has no source for is
    /// left out, which `Resources::bind_group` reports.
    fn views(
        &self,
        res: &Resources,
        kind: &PassKind,
        members: &[u32],
        reads: Option<&[wgpu::TextureView; 2]>,
        map: Option<&wgpu::TextureView>,
    ) -> Vec<wgpu::TextureView> {
        let layer = |i: usize| members.get(i).map(|&m| &self.layers[m as usize]);
        PassInputs::of(Some(kind))
            .textures()
            .filter_map(|t| match t {
                Texture::Color(i) => layer(i).map(|l| l.color.clone()),
                Texture::Depth(i) => layer(i).map(|l| l.depth.unwrap_or(&res.dummy_depth).clone()),
                Texture::IntermediateColor => reads.map(|r| r[0].clone()),
                Texture::IntermediateGeometry => reads.map(|r| r[1].clone()),
                Texture::LightMap => map.cloned(),
            })
            .collect()
    }

    /// A pass shape with this composite's lighting, drawing surfaces `members`.
    fn kind(&self, members: &[u32], intermediate: bool, last: bool, base: bool) -> PassKind {
        let lit = self.light.enabled;
        PassKind {
            surfaces: members.len(),
            scaled: self.scaled(members),
            intermediate,
            last,
            lit,
            from_depth: lit && self.light.normals == NormalSource::FromDepth,
            base,
            copy: false,
            map: false,
            factor: false,
        }
    }

    /// Whether some of `members` has its source scaled to its rectangle.
    fn scaled(&self, members: &[u32]) -> bool {
        members.iter().any(|&m| self.layers.get(m as usize).is_some_and(|l| l.props.scaled(l.rect)))
    }

    /// Appends a draw to the current output pass (opening one if the last pass is not).
    fn output_draw(&mut self, d: DrawOp) {
        match self.passes.last_mut() {
            Some(p) if p.target.is_none() => p.draws.push(d),
            _ => self.passes.push(PassOp { target: None, draws: vec![d] }),
        }
    }

    /// The background fill of `rects`.
    pub fn fill(&mut self, rects: &[Rect]) {
        if rects.is_empty() {
            return;
        }
        let instances = self.rects(rects, [0, 0], self.size);
        self.output_draw(DrawOp { kind: None, views: Vec::new(), block: 0, instances });
    }

    /// The 2D compositor's copy of `layer` into `rects`.
    pub fn copy(&mut self, res: &Resources, layer: u32, rects: &[Rect]) {
        let kind = PassKind {
            surfaces: 1,
            intermediate: false,
            last: true,
            lit: false,
            from_depth: false,
            base: true,
            copy: true,
            map: false,
            factor: false,
            scaled: self.scaled(&[layer]),
        };
        let instances = self.rects(rects, [0, 0], self.size);
        let block = self.block([0, 0], [0, 0], &[layer]);
        let views = self.views(res, &kind, &[layer], None, None);
        self.output_draw(DrawOp { kind: Some(kind), views, block, instances });
    }

    /// One z-group's draws: one fetch or one select per cell, and chains where more than a
    /// pass's surfaces overlap.
    pub fn group(&mut self, res: &mut Resources, g: &GroupPlan) {
        let p = self.per_pass;
        let mut chains = Vec::new();
        for ((members, base), rects) in &g.draws {
            if members.len() <= p {
                if members.len() > 1 {
                    self.selects += rects.len();
                }
                let mut kind = self.kind(members, false, true, *base);
                let instances = self.rects(rects, [0, 0], self.size);
                let block = self.block([0, 0], [0, 0], members);
                let map = if kind.lit && !kind.from_depth && members.len() == 1 {
                    let bits = unit_normal(self.layers[members[0] as usize].normal).map(f32::to_bits);
                    self.maps.iter().find(|(n, _)| *n == bits).map(|(_, map)| map)
                } else {
                    None
                };
                kind.map = map.is_some();
                let views = self.views(res, &kind, members, None, map);
                self.output_draw(DrawOp { kind: Some(kind), views, block, instances });
            } else {
                self.selects += rects.len();
                self.chained += rects.len();
                chains.push((members, *base, rects));
            }
        }
        if chains.is_empty() {
            return;
        }
        // Chained cells, tile by tile (bounded intermediates).
        let mut tiles: std::collections::BTreeMap<(i32, i32), Vec<(usize, Rect)>> = Default::default();
        for (c, (_, _, rects)) in chains.iter().enumerate() {
            for r in rects.iter() {
                for ty in r[1].div_euclid(CHAIN_TILE)..=(r[3] - 1).div_euclid(CHAIN_TILE) {
                    for tx in r[0].div_euclid(CHAIN_TILE)..=(r[2] - 1).div_euclid(CHAIN_TILE) {
                        let (x0, y0) = (tx * CHAIN_TILE, ty * CHAIN_TILE);
                        let piece = [r[0].max(x0), r[1].max(y0), r[2].min(x0 + CHAIN_TILE), r[3].min(y0 + CHAIN_TILE)];
                        tiles.entry((tx, ty)).or_default().push((c, piece));
                    }
                }
            }
        }
        let geom = if self.light.enabled { Geom::DepthNormal } else { Geom::Depth };
        for pieces in tiles.values() {
            let x0 = pieces.iter().map(|(_, r)| r[0]).min().unwrap_or(0);
            let y0 = pieces.iter().map(|(_, r)| r[1]).min().unwrap_or(0);
            let x1 = pieces.iter().map(|(_, r)| r[2]).max().unwrap_or(0);
            let y1 = pieces.iter().map(|(_, r)| r[3]).max().unwrap_or(0);
            let origin = [x0, y0];
            let inter = res.intermediates(((x1 - x0) as u32, (y1 - y0) as u32), geom);
            let isize = inter.size;
            let targets: [[wgpu::TextureView; 2]; 2] =
                [0, 1].map(|i| [inter.color[i].1.clone(), inter.geometry[i].1.clone()]);
            let stages: Vec<Vec<Range<usize>>> = chains.iter().map(|(m, _, _)| chunks(m.len(), p)).collect();
            let most = stages.iter().map(Vec::len).max().unwrap_or(1);
            // Stage s < last writes intermediate s % 2, reading the other one from s ≥ 1.
            for s in 0..most - 1 {
                let mut draws = Vec::new();
                for (c, (members, _, _)) in chains.iter().enumerate() {
                    if stages[c].len() <= s + 1 {
                        continue;
                    }
                    let mine: Vec<Rect> = pieces.iter().filter(|(pc, _)| *pc == c).map(|(_, r)| *r).collect();
                    if mine.is_empty() {
                        continue;
                    }
                    let chunk = &members[stages[c][s].clone()];
                    let reads = (s > 0).then_some(&targets[(s + 1) % 2]);
                    let kind = self.kind(chunk, reads.is_some(), false, false);
                    let instances = self.rects(&mine, origin, isize);
                    let block = self.block(origin, origin, chunk);
                    let views = self.views(res, &kind, chunk, reads, None);
                    draws.push(DrawOp { kind: Some(kind), views, block, instances });
                }
                self.passes.push(PassOp { target: Some(targets[s % 2].to_vec()), draws });
            }
            for (c, (members, base, _)) in chains.iter().enumerate() {
                let mine: Vec<Rect> = pieces.iter().filter(|(pc, _)| *pc == c).map(|(_, r)| *r).collect();
                if mine.is_empty() {
                    continue;
                }
                let last = stages[c].len() - 1;
                let chunk = &members[stages[c][last].clone()];
                let kind = self.kind(chunk, true, true, *base);
                let instances = self.rects(&mine, [0, 0], self.size);
                let block = self.block([0, 0], origin, chunk);
                let views = self.views(res, &kind, chunk, Some(&targets[(last + 1) % 2]), None);
                self.output_draw(DrawOp { kind: Some(kind), views, block, instances });
            }
        }
    }
}
