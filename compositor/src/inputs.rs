//! The one description of a pass's inputs: what each binding of its bind group holds, in
//! binding order. The WGSL declarations and the per-surface calls of the pass's shader
//! (`shader.rs`), its bind group layout and bind groups (`resources.rs`) and the views a draw
//! binds (`encode.rs`) are all derived from it, so none of them knows a binding number.

use std::fmt::Write;

use crate::kind::PassKind;
use strata_device::{texture_entry, UNFILTERED};

/// What one binding of a pass holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Input {
    /// A uniform block.
    Uniform(Uniform),
    /// An image, read with `textureLoad`.
    Texture(Texture),
}

/// The uniform blocks a pass binds (both in the one uniform buffer).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Uniform {
    /// The lighting and the background (`Params`), at the start of the buffer.
    Params,
    /// The draw's block (`Draw`: origins and one `Surf` per surface), at a dynamic offset.
    Draw,
}

/// The images a pass binds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Texture {
    /// Surface `i`'s colour (RGBA8).
    Color(usize),
    /// Surface `i`'s depth (a depth format; a 1×1 placeholder for a surface without one).
    Depth(usize),
    /// The intermediate's colour: the selected colour of the chain's earlier passes.
    IntermediateColor,
    /// The intermediate's geometry: the selected eye depth and normal.
    IntermediateGeometry,
    /// The light map: the lighting factor of every output pixel for the surface's normal.
    LightMap,
}

impl Uniform {
    /// Its variable's name in the pass's WGSL.
    pub fn name(self) -> &'static str {
        match self {
            Uniform::Params => "P",
            Uniform::Draw => "D",
        }
    }

    /// Its WGSL type (a struct of `shaders/composite.wgsl`, imported as `c`).
    pub fn wgsl_type(self) -> &'static str {
        match self {
            Uniform::Params => "c::Params",
            Uniform::Draw => "c::Draw",
        }
    }

    /// Whether it is bound at a dynamic offset (one block per draw).
    pub fn dynamic(self) -> bool {
        self == Uniform::Draw
    }
}

impl Texture {
    /// Its variable's name in the pass's WGSL.
    pub fn name(self) -> String {
        match self {
            Texture::Color(i) => format!("color{i}"),
            Texture::Depth(i) => format!("depth{i}"),
            Texture::IntermediateColor => "icolor".into(),
            Texture::IntermediateGeometry => "igeom".into(),
            Texture::LightMap => "lmap".into(),
        }
    }

    /// Its WGSL type.
    pub fn wgsl_type(self) -> &'static str {
        match self {
            Texture::Depth(_) => "texture_depth_2d",
            _ => "texture_2d<f32>",
        }
    }

    /// What its view is sampled as.
    pub fn sample_type(self) -> wgpu::TextureSampleType {
        match self {
            Texture::Depth(_) => wgpu::TextureSampleType::Depth,
            _ => UNFILTERED,
        }
    }
}

impl Input {
    /// Its variable's name in the pass's WGSL.
    pub fn name(self) -> String {
        match self {
            Input::Uniform(u) => u.name().into(),
            Input::Texture(t) => t.name(),
        }
    }

    /// Its WGSL declaration at `binding` of group 0.
    pub fn declaration(self, binding: u32) -> String {
        let (space, ty) = match self {
            Input::Uniform(u) => ("<uniform>", u.wgsl_type()),
            Input::Texture(t) => ("", t.wgsl_type()),
        };
        format!("@group(0) @binding({binding}) var{space} {}: {ty};", self.name())
    }

    /// Its bind group layout entry at `binding` (read by the fragment stage).
    pub fn layout_entry(self, binding: u32) -> wgpu::BindGroupLayoutEntry {
        match self {
            Input::Uniform(u) => wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: u.dynamic(),
                    min_binding_size: None,
                },
                count: None,
            },
            Input::Texture(t) => texture_entry(binding, t.sample_type()),
        }
    }
}

/// A pass's inputs in binding order: input `n` is `@group(0) @binding(n)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PassInputs(Vec<Input>);

impl PassInputs {
    /// The inputs of a pass of shape `k` (`None`: the background fill, which reads the
    /// lighting parameters only): the two uniform blocks; each surface's colour and, when
    /// `k.depth()`, its depth; then the intermediate's colour and geometry, or the light map.
    /// The light-map pass binds no image.
    pub fn of(k: Option<&PassKind>) -> PassInputs {
        let Some(k) = k else {
            return PassInputs(vec![Input::Uniform(Uniform::Params)]);
        };
        let mut v = vec![Input::Uniform(Uniform::Params), Input::Uniform(Uniform::Draw)];
        if k.factor {
            return PassInputs(v);
        }
        for i in 0..k.surfaces {
            v.push(Input::Texture(Texture::Color(i)));
            if k.depth() {
                v.push(Input::Texture(Texture::Depth(i)));
            }
        }
        if k.intermediate {
            v.push(Input::Texture(Texture::IntermediateColor));
            v.push(Input::Texture(Texture::IntermediateGeometry));
        }
        if k.map {
            v.push(Input::Texture(Texture::LightMap));
        }
        PassInputs(v)
    }

    /// Every input with its binding number.
    pub fn bindings(&self) -> impl Iterator<Item = (u32, Input)> + '_ {
        self.0.iter().enumerate().map(|(n, &input)| (n as u32, input))
    }

    /// The images in binding order: the order of a draw's views.
    pub fn textures(&self) -> impl Iterator<Item = Texture> + '_ {
        self.0.iter().filter_map(|input| match input {
            Input::Texture(t) => Some(*t),
            Input::Uniform(_) => None,
        })
    }

    /// The names of those of `wanted` that the pass binds, in the order of `wanted` (a WGSL
    /// function's parameters), each after ", ": the trailing texture arguments of a call into
    /// `shaders/composite.wgsl`.
    pub fn arguments(&self, wanted: &[Texture]) -> String {
        wanted.iter().filter(|t| self.0.contains(&Input::Texture(**t))).fold(String::new(), |mut s, t| {
            let _ = write!(s, ", {}", t.name());
            s
        })
    }

    /// The WGSL declarations of every binding, one a line.
    pub fn declarations(&self) -> String {
        self.bindings().fold(String::new(), |mut s, (binding, input)| {
            let _ = writeln!(s, "{}", input.declaration(binding));
            s
        })
    }

    /// The bind group layout entries.
    pub fn layout(&self) -> Vec<wgpu::BindGroupLayoutEntry> {
        self.bindings().map(|(binding, input)| input.layout_entry(binding)).collect()
    }

    /// The bind group entries: `uniform` gives each uniform block's buffer range, and `views`
    /// are the images in the order of [`PassInputs::textures`]. `None` where `views` holds
    /// another number of images than the pass binds.
    pub fn entries<'a>(
        &self,
        uniform: impl Fn(Uniform) -> wgpu::BindingResource<'a>,
        views: &'a [wgpu::TextureView],
    ) -> Option<Vec<wgpu::BindGroupEntry<'a>>> {
        if views.len() != self.textures().count() {
            return None;
        }
        let mut views = views.iter();
        self.bindings()
            .map(|(binding, input)| {
                let resource = match input {
                    Input::Uniform(u) => uniform(u),
                    Input::Texture(_) => wgpu::BindingResource::TextureView(views.next()?),
                };
                Some(wgpu::BindGroupEntry { binding, resource })
            })
            .collect()
    }
}
