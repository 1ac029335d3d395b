// Input routing's read of one surface's texel under a point: its window depth (1 without a
// depth image) and its colour's alpha, written for the CPU to decide which surface is shown
// there. One texel per candidate surface; never the whole image.

struct Params {
    texel: vec2<u32>,
    has_depth: u32,
    _pad: u32,
}

@group(0) @binding(0) var color: texture_2d<f32>;
@group(0) @binding(1) var depth: texture_depth_2d;
@group(0) @binding(2) var<uniform> params: Params;
@group(0) @binding(3) var<storage, read_write> out: vec2<f32>;

@compute @workgroup_size(1)
fn main() {
    let at = vec2<i32>(params.texel);
    var d = 1.0;
    if params.has_depth != 0u {
        d = textureLoad(depth, at, 0);
    }
    out = vec2<f32>(d, textureLoad(color, at, 0).a);
}
