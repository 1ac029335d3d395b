//! Every pass shape the compositor can build composes, through `Composer::compose`, to a valid
//! module whose bound globals are exactly its description's bind group layout.

use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};

use super::*;
use crate::inputs::{Input, PassInputs, Texture, Uniform};
use crate::plan::chunks;
use crate::resources::{block_size, PARAMS_SIZE};

/// The module validated with every check naga has.
fn validate(module: &naga::Module, what: &str) -> ModuleInfo {
    Validator::new(ValidationFlags::all(), Capabilities::default())
        .validate(module)
        .unwrap_or_else(|e| panic!("{what}: {}", e.emit_to_string("")))
}

/// Whether a layout entry's binding type is what the global of type `ty` in `space` is.
fn same_kind(
    module: &naga::Module,
    space: naga::AddressSpace,
    ty: naga::Handle<naga::Type>,
    entry: &wgpu::BindingType,
) -> bool {
    use naga::{ImageClass, ImageDimension, ScalarKind, TypeInner};
    match (space, &module.types[ty].inner, entry) {
        (naga::AddressSpace::Uniform, _, wgpu::BindingType::Buffer { ty: wgpu::BufferBindingType::Uniform, .. }) => {
            true
        }
        (
            naga::AddressSpace::Handle,
            TypeInner::Image { dim: ImageDimension::D2, arrayed: false, class },
            wgpu::BindingType::Texture {
                sample_type,
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
        ) => matches!(
            (class, sample_type),
            (
                ImageClass::Sampled { kind: ScalarKind::Float, multi: false },
                wgpu::TextureSampleType::Float { filterable: false }
            ) | (ImageClass::Depth { multi: false }, wgpu::TextureSampleType::Depth)
        ),
        _ => false,
    }
}

/// Asserts that the module's bound globals are exactly `inputs`' layout: one global per entry,
/// at its binding number in group 0, of its kind (a uniform buffer, or a 2D texture of its
/// sample type), named as the description names it; uniform blocks of the size the compositor
/// writes (`Params`, or a draw block of `surfaces`).
fn assert_bindings_match(module: &naga::Module, inputs: &PassInputs, surfaces: usize, what: &str) {
    let layout = inputs.layout();
    let bound: Vec<_> = module.global_variables.iter().filter(|(_, g)| g.binding.is_some()).collect();
    assert_eq!(bound.len(), layout.len(), "{what}: bound globals against layout entries");
    for (binding, input) in inputs.bindings() {
        let entry =
            layout.iter().find(|e| e.binding == binding).unwrap_or_else(|| panic!("{what}: no entry {binding}"));
        let (_, g) = bound
            .iter()
            .find(|(_, g)| g.binding.as_ref().is_some_and(|b| b.group == 0 && b.binding == binding))
            .unwrap_or_else(|| panic!("{what}: nothing bound at {binding}"));
        assert!(
            same_kind(module, g.space, g.ty, &entry.ty),
            "{what}: binding {binding} is {:?} in WGSL, {:?} in the layout",
            module.types[g.ty].inner,
            entry.ty
        );
        assert_eq!(g.name.as_deref(), Some(input.name().as_str()), "{what}: binding {binding}");
        if let Input::Uniform(u) = input {
            let size = u64::from(module.types[g.ty].inner.size(module.to_ctx()));
            let want = if u == Uniform::Params { PARAMS_SIZE } else { block_size(surfaces) };
            assert_eq!(size, want, "{what}: {u:?} block size");
            let dynamic = matches!(entry.ty, wgpu::BindingType::Buffer { has_dynamic_offset: true, .. });
            assert_eq!(dynamic, u == Uniform::Draw, "{what}: {u:?} dynamic offset");
        }
    }
}

/// Whether the module has `shaders/composite.wgsl`'s function `name` (only what is used is
/// composed in).
fn has_fn(module: &naga::Module, name: &str) -> bool {
    let decorated = naga_oil::compose::Composer::decorated_name(Some(MODULE_PATH), name);
    module.functions.iter().any(|(_, f)| f.name.as_deref() == Some(decorated.as_str()))
}

/// Whether some function reads `Params`'s member `background`.
fn reads_background(module: &naga::Module, info: &ModuleInfo) -> bool {
    module.functions.iter().any(|(h, f)| {
        f.expressions.iter().any(|(_, expr)| {
            let naga::Expression::AccessIndex { base, index } = *expr else { return false };
            match info[h][base].ty.inner_with(&module.types) {
                naga::TypeInner::Struct { members, .. } => {
                    members.get(index as usize).and_then(|m| m.name.as_deref()) == Some("background")
                }
                _ => false,
            }
        })
    })
}

/// Every shape a compositor sampling at most `max_textures` textures per pass can build: a
/// pass takes `p = ⌊max_textures/2⌋` surfaces, a chained pass the intermediate and at most
/// `p − 1`; the 2D copy; the light map and the passes that read one.
fn shapes(max_textures: u32) -> Vec<PassKind> {
    let p = (max_textures / 2) as usize;
    let mut out = vec![PassKind::light_map()];
    for surfaces in 1..=p {
        for bits in 0..256u32 {
            let k = PassKind {
                surfaces,
                intermediate: bits & 1 != 0,
                last: bits & 2 != 0,
                lit: bits & 4 != 0,
                from_depth: bits & 8 != 0,
                base: bits & 16 != 0,
                copy: bits & 32 != 0,
                map: bits & 64 != 0,
                factor: false,
                scaled: bits & 128 != 0,
            };
            // Passes that are never built: a non-last pass selects, the 2D copy is one unlit
            // surface on the background, a light map serves one lit surface with a
            // per-surface normal; a chained pass takes at most p − 1 surfaces.
            if (!k.last && !k.select())
                || (k.copy && (k.select() || k.lit || !k.base))
                || (k.map && (k.select() || !k.lit || k.from_depth || !k.last))
                || (k.intermediate && surfaces > p - 1)
            {
                continue;
            }
            out.push(k);
        }
    }
    out
}

#[test]
fn the_fill_binds_what_its_description_says() {
    let module = naga::front::wgsl::parse_str(FILL).unwrap_or_else(|e| panic!("{}", e.emit_to_string(FILL)));
    validate(&module, "fill");
    assert_bindings_match(&module, &PassInputs::of(None), 0, "fill");
}

/// The most textures a pass may sample: the device's limit where one opens (lavapipe offers
/// 37), and never less than wgpu's default (16).
fn device_limit() -> u32 {
    let default = wgpu::Limits::default().max_sampled_textures_per_shader_stage;
    let device = strata_device::Gpu::open().map(|g| g.limits.max_sampled_textures_per_shader_stage);
    device.map_or(default, |d| d.max(default))
}

#[test]
fn every_chained_pass_has_a_width_that_shapes_builds() {
    // Every pass of every group chained under every texture limit has one of the widths
    // `shapes` builds: at most p surfaces, at most p − 1 beside an intermediate.
    let limit = device_limit();
    for m in 4..=limit {
        let p = (m / 2) as usize;
        for k in 1..=4 * p {
            for (s, chunk) in chunks(k, p).iter().enumerate() {
                assert!(chunk.len() <= if s > 0 { p - 1 } else { p }, "m {m} k {k} pass {s}");
            }
        }
    }
}

#[test]
fn every_pass_shape_composes_to_a_valid_module_bound_as_described() {
    let mut composer = Composer::new().unwrap_or_else(|e| panic!("{e}"));
    let limit = device_limit();
    let mut seen = std::collections::HashSet::new();
    for m in 4..=limit {
        for k in shapes(m) {
            let inputs = PassInputs::of(Some(&k));
            assert!(inputs.textures().count() <= m as usize, "{k:?} samples more than {m} textures");
            if !seen.insert(k) {
                continue;
            }
            let what = format!("{k:?}");
            let module = composer.compose(&k).unwrap_or_else(|e| panic!("{e}"));
            let info = validate(&module, &what);
            assert_bindings_match(&module, &inputs, k.surfaces, &what);
            let entries: Vec<_> = module.entry_points.iter().map(|e| (e.name.as_str(), e.stage)).collect();
            assert_eq!(entries, [("vs", naga::ShaderStage::Vertex), ("fs", naga::ShaderStage::Fragment)], "{what}");
            let count = |f: fn(Texture) -> bool| inputs.textures().filter(|&t| f(t)).count();
            if k.factor {
                assert_eq!(inputs.textures().count(), 0, "the light map binds no image");
                assert!(has_fn(&module, "factor") && has_fn(&module, "light_map"), "{what}");
                continue;
            }
            assert_eq!(count(|t| matches!(t, Texture::Color(_))), k.surfaces, "{what}");
            assert_eq!(count(|t| matches!(t, Texture::Depth(_))), if k.depth() { k.surfaces } else { 0 }, "{what}");
            assert_eq!(count(|t| t == Texture::IntermediateGeometry), usize::from(k.intermediate), "{what}");
            assert_eq!(count(|t| t == Texture::LightMap), usize::from(k.map), "{what}");
            assert_eq!(has_fn(&module, "eye"), k.select(), "{what}: eye depth where the select runs");
            assert_eq!(has_fn(&module, "nearer"), k.surfaces > 1 || k.intermediate, "{what}");
            assert_eq!(has_fn(&module, "light"), k.last && k.lit && !k.copy, "{what}: lit");
            assert_eq!(has_fn(&module, "dn"), k.from_depth, "{what}: normals from depth");
            assert_eq!(reads_background(&module, &info), k.last && k.base && !k.copy, "{what}: on the background");
        }
    }
    // The widest passes under the device limit: p surfaces, p − 1 beside an intermediate.
    let p = (limit / 2) as usize;
    assert!(seen.iter().any(|k| k.surfaces == p && !k.intermediate));
    assert!(seen.iter().any(|k| k.surfaces == p - 1 && k.intermediate));
    assert!(!seen.iter().any(|k| k.surfaces > p || (k.intermediate && k.surfaces > p - 1)));
}

#[test]
fn a_shape_whose_shader_fails_is_an_error() {
    // A shape that is never built: one unlit surface read through a light map, which the
    // module's `finish` has no lighting for.
    let k = PassKind { map: true, lit: false, factor: false, ..PassKind::light_map() };
    let e = Composer::new().and_then(|mut c| c.compose(&k)).err();
    assert!(matches!(e, Some(CompositorError::Shader { .. })), "{e:?}");
}
