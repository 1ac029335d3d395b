//! The 3D compositor (the thesis' "root surface", §4.5–4.6): every surface's colour and depth
//! are combined into one output image. Surfaces are grouped by z and the groups drawn far
//! (larger z) to near. Within a group each output fragment takes the surface with the nearest
//! depth; on equal depth the surface later in stacking order wins. Depth is compared in eye
//! space: each surface's window depth is linearised by its declared projection
//! (`Layer::projection`); an undeclared surface's eye depth is its raw depth, and a surface
//! without a depth image lies at its far plane. Outside its rectangle a surface has no
//! fragment. The selected colour (straight alpha) is lit, premultiplied, and blended over what
//! lies beneath.
//!
//! A composite costs what its region needs (`plan`): the region is cut into cells by coverage;
//! a cell no surface covers is filled with the background, a cell one surface of a group covers
//! costs one fetch of it, and only where several surfaces of a group overlap does the depth
//! select run, over those surfaces only. The farthest group at a cell is laid on the
//! background in its shader; nearer ones are blended over it.
//!
//! A pass can sample at most `m` textures; a surface needs two (colour and depth), so one pass
//! takes `p = ⌊m/2⌋` surfaces. Where more overlap, passes are chained: each further pass takes
//! the previous pass's intermediate (the selected colour, RGBA8, and its eye depth and normal,
//! f32) plus `p − 1` new surfaces. Because an intermediate holds exactly what a single pass would
//! have selected, and lighting runs only in the last pass, a chain is bit-identical to one pass.
//! `with_intermediate` can make the intermediate's colour RGBA16F instead (twice the bytes; an
//! RGBA8 texel then passes through a 16-bit float, which holds k/255 to within 2⁻¹¹ relative).
//!
//! Culling (`with_culling`, on by default): in a cell where some group's members are all opaque
//! (`Layer::opaque`: the surface's config has no alpha, so its colour has alpha 1 everywhere),
//! every farther group is left out of the cell and that group is laid on the background. Nothing
//! left out could show, and every group still drawn selects the same surface at every pixel
//! (normals from depth come from the selected surface's own depth), so the image is the same,
//! bit for bit, as without culling.
//!
//! Regions and opacity (`Layer::props`): a surface shows a source region of its image over its
//! rectangle. Where the two have the same size each pixel fetches its own texel exactly; where
//! they differ the colour is filtered bilinearly (texel centres at half-integers, clamped to the
//! region) and the depth select uses the nearest texel, both located in integer arithmetic so
//! that the f64 reference finds the same texels. Opacity multiplies the selected colour's
//! alpha; a surface with opacity below 1 is never treated as opaque by culling.
//!
//! `Mode::TwoD` is the 2D baseline: painter's order by z only, no depth, no lighting, each
//! visible part of a surface copied as it is (opacity does not apply).

#![warn(missing_docs)]

mod compositor;
mod encode;
pub mod figures;
mod inputs;
mod kind;
mod layer;
mod plan;
pub mod pointer;
pub mod reference;
mod resources;
pub mod root;
mod shader;
mod timing;
pub mod window;

pub use compositor::Compositor;
pub use layer::{CompositorError, Intermediate, Layer, Mode, Props, Source, Stats};
pub use strata_protocol::control::{Lighting, NormalSource};
