//! Pass shapes: what a pass samples and writes, which decides its shader (the defs that
//! specialise `shaders/composite.wgsl`) and its pipeline.

use std::collections::HashMap;

use naga_oil::compose::ShaderDefValue;

/// What the intermediate's geometry image holds, by lighting mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Geom {
    /// Unlit: the selected depth only.
    Depth,
    /// Lit: the selected depth and normal.
    DepthNormal,
}

impl Geom {
    /// The image format.
    pub fn format(self) -> wgpu::TextureFormat {
        match self {
            Geom::Depth => wgpu::TextureFormat::R32Float,
            Geom::DepthNormal => wgpu::TextureFormat::Rgba32Float,
        }
    }
}

/// One pass shape: everything that changes the shader or the pipeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PassKind {
    /// Surfaces sampled (each: colour, and depth when `depth()`).
    pub surfaces: usize,
    /// An earlier pass's result is a candidate.
    pub intermediate: bool,
    /// Writes the output (else an intermediate).
    pub last: bool,
    /// Lighting on.
    pub lit: bool,
    /// Normals from depth.
    pub from_depth: bool,
    /// Laid on the background in the shader (the cell's farthest group), not blended.
    pub base: bool,
    /// The 2D compositor's copy.
    pub copy: bool,
    /// One surface lit with a per-surface normal, the factor read from a light map.
    pub map: bool,
    /// The pass drawing a light map (one R32F target; no images bound).
    pub factor: bool,
    /// Some surface's source region is scaled to its rectangle: those surfaces are located by
    /// integer division and filtered (shapes without it carry none of that code).
    pub scaled: bool,
}

impl PassKind {
    /// Several candidates: the depth select runs.
    pub fn select(&self) -> bool {
        self.surfaces > 1 || self.intermediate
    }

    /// The surfaces' depth images are bound.
    pub fn depth(&self) -> bool {
        self.select() || self.from_depth
    }

    /// The pass drawing the light map of a normal.
    pub fn light_map() -> PassKind {
        PassKind {
            surfaces: 1,
            intermediate: false,
            last: true,
            lit: true,
            from_depth: false,
            base: false,
            copy: false,
            map: false,
            factor: true,
            scaled: false,
        }
    }

    /// The intermediate's geometry for this lighting mode.
    pub fn geom(&self) -> Geom {
        if self.lit {
            Geom::DepthNormal
        } else {
            Geom::Depth
        }
    }

    /// The shader defs that specialise `shaders/composite.wgsl` to this shape: each property
    /// the shape has (a def that is absent is off), and `SURFACES`, the number of surfaces.
    pub fn shader_defs(&self) -> HashMap<String, ShaderDefValue> {
        let flags = [
            ("SELECT", self.select()),
            ("INTERMEDIATE", self.intermediate),
            ("LAST", self.last),
            ("LIT", self.lit),
            ("FROM_DEPTH", self.from_depth),
            ("DEPTH", self.depth()),
            ("BASE", self.base),
            ("COPY", self.copy),
            ("MAP", self.map),
            ("FACTOR", self.factor),
            ("SCALED", self.scaled),
        ];
        flags
            .into_iter()
            .filter(|&(_, on)| on)
            .map(|(name, _)| (name.to_string(), ShaderDefValue::Bool(true)))
            .chain([("SURFACES".to_string(), ShaderDefValue::UInt(self.surfaces as u32))])
            .collect()
    }
}
