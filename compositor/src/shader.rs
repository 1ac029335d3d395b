//! Pass shapes and their shaders, composed with naga_oil: the module `shaders/composite.wgsl`
//! holds everything a pass does as WGSL functions, specialised by shader defs (one per
//! property of the shape, `PassKind::shader_defs`); Rust writes only what WGSL cannot loop
//! over, from the pass's description of its inputs (`inputs::PassInputs`): the binding
//! declarations and a `fs` of one call per surface, each passing that surface's textures
//! (`entry_points`). `Composer::compose` turns the two into one validated `naga::Module`.

use std::fmt::Write;

use naga_oil::compose::{ComposableModuleDescriptor, NagaModuleDescriptor};

use crate::inputs::{PassInputs, Texture, Uniform};
use crate::kind::PassKind;
use crate::CompositorError;

/// The pass's functions: a naga_oil module.
const MODULE: &str = include_str!("../../shaders/composite.wgsl");

/// Where `MODULE` comes from, for error messages.
const MODULE_FILE: &str = "shaders/composite.wgsl";

/// `MODULE`'s import path (its `#define_import_path`).
const MODULE_PATH: &str = "strata::composite";

/// The background fill of uncovered cells.
pub const FILL: &str = include_str!("../../shaders/fill.wgsl");

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
