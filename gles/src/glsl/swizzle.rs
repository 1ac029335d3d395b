//! ES 3.0's texture swizzles (`GL_TEXTURE_SWIZZLE_*`) in the shader: wgpu 30's views have
//! none, so the rewrite wraps every lookup that returns texels in `strata_swizzle`, which
//! reads the sampler's swizzle from the uniform block (`NAME__z`, written at each draw from
//! the bound texture).

/// A texture's swizzle (ES 3.0's `GL_TEXTURE_SWIZZLE_*`), applied to what every lookup but
/// the size query returns: `z` holds each channel's source (1 to 4 red to alpha, 5 zero, 6
/// one), or is all 0 where the swizzle keeps every channel, which a uniform branch skips.
pub(super) const SWIZZLE_FNS: &str = "float strata_pick(vec4 v, float i) {\n\
     \x20   return i < 2.5 ? (i < 1.5 ? v.x : v.y) : i < 4.5 ? (i < 3.5 ? v.z : v.w) : (i < 5.5 ? 0.0 : 1.0);\n}\n\
     vec4 strata_swizzle(vec4 v, vec4 z) {\n\
     \x20   if (z.x == 0.0) { return v; }\n\
     \x20   return vec4(strata_pick(v, z.x), strata_pick(v, z.y), strata_pick(v, z.z), strata_pick(v, z.w));\n}\n";

/// Whether `function` is a lookup that returns texels, which a texture's swizzle rearranges
/// (every lookup but the size query).
pub(super) fn returns_texels(function: &str) -> bool {
    (function.starts_with("texture") || function.starts_with("texel")) && function != "textureSize"
}
