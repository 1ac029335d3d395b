//! Pass shapes and their shaders, composed with naga_oil: the module `shaders/composite.wgsl`
//! holds everything a pass does as WGSL functions, specialised by shader defs (one per
//! property of the shape, `PassKind::shader_defs`); Rust writes only what WGSL cannot loop
//! over, from the pass's description of its inputs (`inputs::PassInputs`): the binding
//! declarations and a `fs` of one call per surface, each passing that surface's textures
//! (`entry_points`). `Composer::compose` turns the two into one validated `naga::Module`.

use std::collections::HashMap;
use std::fmt::Write;

use naga_oil::compose::{ComposableModuleDescriptor, NagaModuleDescriptor, ShaderDefValue};

use crate::inputs::{PassInputs, Texture, Uniform};
use crate::CompositorError;

/// The pass's functions: a naga_oil module.
const MODULE: &str = include_str!("../../shaders/composite.wgsl");

/// Where `MODULE` comes from, for error messages.
const MODULE_FILE: &str = "shaders/composite.wgsl";

/// `MODULE`'s import path (its `#define_import_path`).
const MODULE_PATH: &str = "strata::composite";

/// The background fill of uncovered cells.
pub const FILL: &str = include_str!("../../shaders/fill.wgsl");

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

/// The WGSL of pass shape `k`'s entry points over `inputs` (its description): the module
/// imported as `c`, every binding declared, and a `fs` that starts from the intermediate or the
/// first surface, takes each further surface if nearer (one call each, passing the surface's
/// textures), and finishes; the light-map pass only computes the factor.
pub fn entry_points(k: &PassKind, inputs: &PassInputs) -> String {
    let (p, d) = (Uniform::Params.name(), Uniform::Draw.name());
    let mut s = format!("#import {MODULE_PATH} as c\n\n");
    s += &inputs.declarations();
    s +=
        "\n@vertex fn vs(@builtin(vertex_index) v: u32, @location(0) r: vec4<f32>) -> @builtin(position) vec4<f32> {\n";
    s += "    return c::corner(v, r);\n}\n\n";
    s += "@fragment fn fs(@builtin(position) pos: vec4<f32>) -> c::Out {\n";
    let _ = writeln!(s, "    let px = c::pixel(pos, {d}.origin);");
    if k.factor {
        let _ = writeln!(s, "    return c::light_map({p}, {d}.surf[0], px);\n}}");
        return s;
    }
    // Surface i's arguments: the lighting, its `Surf`, the pixel and its textures (colour,
    // then depth where the pass binds it).
    let surface = |i: usize| {
        let textures = inputs.arguments(&[Texture::Color(i), Texture::Depth(i)]);
        format!("{p}, {d}.surf[{i}], px{textures}")
    };
    let further = if k.intermediate {
        let textures = inputs.arguments(&[Texture::IntermediateColor, Texture::IntermediateGeometry]);
        let _ = writeln!(s, "    var b = c::intermediate({d}.origin, px{textures});");
        0
    } else {
        let _ = writeln!(s, "    var b = c::first({});", surface(0));
        1
    };
    for i in further..k.surfaces {
        let _ = writeln!(s, "    b = c::nearer(b, {});", surface(i));
    }
    let _ = writeln!(s, "    return c::finish(b, {p}, px{});\n}}", inputs.arguments(&[Texture::LightMap]));
    s
}

/// Composes pass shaders: `shaders/composite.wgsl` added once, each shape's shader made from it
/// (naga_oil keeps the module built for each set of defs).
pub struct Composer(naga_oil::compose::Composer);

impl Composer {
    /// A composer holding `shaders/composite.wgsl`.
    pub fn new() -> Result<Composer, CompositorError> {
        let mut composer = naga_oil::compose::Composer::default();
        let added = composer.add_composable_module(ComposableModuleDescriptor {
            source: MODULE,
            file_path: MODULE_FILE,
            ..Default::default()
        });
        if let Err(e) = added {
            let message = e.emit_to_string(&composer);
            return Err(CompositorError::Shader { kind: MODULE_FILE.into(), message });
        }
        Ok(Composer(composer))
    }

    /// The validated shader of pass shape `k` (entry points `vs` and `fs`), with the bindings
    /// of `PassInputs::of(Some(k))`.
    pub fn compose(&mut self, k: &PassKind) -> Result<naga::Module, CompositorError> {
        let source = entry_points(k, &PassInputs::of(Some(k)));
        self.0
            .make_naga_module(NagaModuleDescriptor {
                source: &source,
                file_path: "compositor pass",
                shader_defs: k.shader_defs(),
                ..Default::default()
            })
            .map_err(|e| CompositorError::Shader {
                kind: format!("{k:?}"),
                message: format!("{}\n{source}", e.emit_to_string(&self.0)),
            })
    }
}

#[cfg(test)]
#[path = "shader_tests.rs"]
mod tests;
