//! Sampling parameters, set and read the same way on textures (`glTexParameter*`) and sampler
//! objects (`glSamplerParameter*`): each value checked once into a [`Setting`] before the
//! object is touched, then applied to its [`SamplerState`]; what only a texture has (its
//! levels) is refused on a sampler object.

use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::limits::MAX_ANISOTROPY;
use crate::objects::texture::SamplerState;

/// `GL_TEXTURE_MIN_LOD` (ES 3.0).
pub const TEXTURE_MIN_LOD: u32 = 0x813A;
/// `GL_TEXTURE_MAX_LOD` (ES 3.0).
pub const TEXTURE_MAX_LOD: u32 = 0x813B;
/// `GL_TEXTURE_BASE_LEVEL` (ES 3.0).
pub const TEXTURE_BASE_LEVEL: u32 = 0x813C;
/// `GL_TEXTURE_COMPARE_MODE` (ES 3.0).
pub const TEXTURE_COMPARE_MODE: u32 = 0x884C;
/// `GL_TEXTURE_COMPARE_FUNC` (ES 3.0).
pub const TEXTURE_COMPARE_FUNC: u32 = 0x884D;
/// `GL_COMPARE_REF_TO_TEXTURE` (ES 3.0).
const COMPARE_REF_TO_TEXTURE: u32 = 0x884E;

/// Whose parameters are set: a texture's (which has levels) or a sampler object's.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Owner {
    /// `glTexParameter*`.
    Texture,
    /// `glSamplerParameter*`.
    Sampler,
}

/// What the context allows beyond ES 2.0's parameters.
#[derive(Clone, Copy)]
pub struct Allowed {
    /// ES 3.0's parameters (levels of detail, base level, comparison).
    pub es3: bool,
    /// `GL_CLAMP_TO_BORDER_EXT` as a wrap (`GL_EXT_texture_border_clamp`).
    pub border: bool,
}

/// One checked parameter value.
#[derive(Clone, Copy)]
pub enum Setting {
    /// `GL_TEXTURE_MIN_FILTER`.
    Min(u32),
    /// `GL_TEXTURE_MAG_FILTER`.
    Mag(u32),
    /// `GL_TEXTURE_WRAP_S`.
    WrapS(u32),
    /// `GL_TEXTURE_WRAP_T`.
    WrapT(u32),
    /// `GL_TEXTURE_WRAP_R`.
    WrapR(u32),
    /// `GL_TEXTURE_MAX_ANISOTROPY_EXT`, clamped to the largest.
    Anisotropy(f32),
    /// `GL_TEXTURE_MAX_LEVEL`.
    MaxLevel(u32),
    /// `GL_TEXTURE_BASE_LEVEL`.
    BaseLevel(u32),
    /// `GL_TEXTURE_MIN_LOD`.
    MinLod(f32),
    /// `GL_TEXTURE_MAX_LOD`.
    MaxLod(f32),
    /// `GL_TEXTURE_COMPARE_MODE`.
    CompareMode(u32),
    /// `GL_TEXTURE_COMPARE_FUNC`.
    CompareFunc(u32),
}

/// A level parameter's value, rounded as Mesa rounds a float; a negative level is
/// `GL_INVALID_VALUE`.
fn level(v: f32) -> GlResult<u32> {
    let level = v.round();
    if level.is_nan() || level < 0.0 {
        return Err(GlError::InvalidValue);
    }
    Ok(level as u32)
}

/// Checks `pname` and its value `v` for `owner`: `GL_INVALID_ENUM` for a name it does not
/// have (ES 3.0's in an ES 2.0 context, a texture's levels on a sampler object) or a value
/// a name does not take, `GL_INVALID_VALUE` for a negative level or anisotropy below 1.
pub fn setting(owner: Owner, allowed: Allowed, pname: u32, v: f32) -> GlResult<Setting> {
    let e = v as u32;
    let es3 = allowed.es3;
    let filter = |ok: bool| if ok { Ok(e) } else { Err(GlError::InvalidEnum) };
    let wrap = || {
        let ok = matches!(e, REPEAT | CLAMP_TO_EDGE | MIRRORED_REPEAT | MIRROR_CLAMP_TO_EDGE_EXT)
            || (allowed.border && e == CLAMP_TO_BORDER_EXT);
        filter(ok)
    };
    Ok(match pname {
        TEXTURE_MIN_FILTER => Setting::Min(filter(matches!(
            e,
            NEAREST
                | LINEAR
                | NEAREST_MIPMAP_NEAREST
                | LINEAR_MIPMAP_NEAREST
                | NEAREST_MIPMAP_LINEAR
                | LINEAR_MIPMAP_LINEAR
        ))?),
        TEXTURE_MAG_FILTER => Setting::Mag(filter(matches!(e, NEAREST | LINEAR))?),
        TEXTURE_WRAP_S => Setting::WrapS(wrap()?),
        TEXTURE_WRAP_T => Setting::WrapT(wrap()?),
        TEXTURE_WRAP_R_OES => Setting::WrapR(wrap()?),
        TEXTURE_MAX_ANISOTROPY_EXT => {
            // Below 1 is an error; above the largest is that, as Mesa stores it.
            if v.is_nan() || v < 1.0 {
                return Err(GlError::InvalidValue);
            }
            Setting::Anisotropy(v.min(MAX_ANISOTROPY))
        }
        TEXTURE_MAX_LEVEL_APPLE if owner == Owner::Texture => Setting::MaxLevel(level(v)?),
        TEXTURE_BASE_LEVEL if es3 && owner == Owner::Texture => Setting::BaseLevel(level(v)?),
        TEXTURE_MIN_LOD if es3 => Setting::MinLod(v),
        TEXTURE_MAX_LOD if es3 => Setting::MaxLod(v),
        TEXTURE_COMPARE_MODE if es3 => Setting::CompareMode(filter(matches!(e, 0 | COMPARE_REF_TO_TEXTURE))?),
        TEXTURE_COMPARE_FUNC if es3 => Setting::CompareFunc(filter((NEVER..=ALWAYS).contains(&e))?),
        _ => return Err(GlError::InvalidEnum),
    })
}

impl Setting {
    /// Writes the value into `s`.
    pub fn apply(self, s: &mut SamplerState) {
        match self {
            Setting::Min(v) => s.min = v,
            Setting::Mag(v) => s.mag = v,
            Setting::WrapS(v) => s.wrap_s = v,
            Setting::WrapT(v) => s.wrap_t = v,
            Setting::WrapR(v) => s.wrap_r = v,
            Setting::Anisotropy(v) => s.anisotropy = v.to_bits(),
            Setting::MaxLevel(v) => s.max_level = v,
            Setting::BaseLevel(v) => s.base_level = v,
            Setting::MinLod(v) => s.min_lod = v.to_bits(),
            Setting::MaxLod(v) => s.max_lod = v.to_bits(),
            Setting::CompareMode(v) => s.compare_mode = v,
            Setting::CompareFunc(v) => s.compare_func = v,
        }
    }
}

/// The value of `pname` in `s` for `owner`, as a float; `None` for a name it does not have.
pub fn value(owner: Owner, es3: bool, s: &SamplerState, pname: u32) -> Option<f32> {
    Some(match pname {
        TEXTURE_MIN_FILTER => s.min as f32,
        TEXTURE_MAG_FILTER => s.mag as f32,
        TEXTURE_WRAP_S => s.wrap_s as f32,
        TEXTURE_WRAP_T => s.wrap_t as f32,
        TEXTURE_WRAP_R_OES => s.wrap_r as f32,
        TEXTURE_MAX_ANISOTROPY_EXT => f32::from_bits(s.anisotropy),
        TEXTURE_MAX_LEVEL_APPLE if owner == Owner::Texture => s.max_level as f32,
        TEXTURE_BASE_LEVEL if es3 && owner == Owner::Texture => s.base_level as f32,
        TEXTURE_MIN_LOD if es3 => f32::from_bits(s.min_lod),
        TEXTURE_MAX_LOD if es3 => f32::from_bits(s.max_lod),
        TEXTURE_COMPARE_MODE if es3 => s.compare_mode as f32,
        TEXTURE_COMPARE_FUNC if es3 => s.compare_func as f32,
        _ => return None,
    })
}

/// A border colour component given as a signed integer, normalised as GL converts one (Mesa's
/// arithmetic, in f32).
pub fn normalized(i: i32) -> f32 {
    (2.0 * i as f32 + 1.0) * (1.0 / 4_294_967_294.0)
}

/// Float parameter values as `glGet*Parameteriv` answers them: a border colour as normalised
/// integers, clamped to [0, 1] first (as Mesa answers); anything else rounded to the nearest
/// integer, as GL converts a float state to an integer.
pub fn as_ints(pname: u32, v: Vec<f32>) -> Vec<i32> {
    if pname == TEXTURE_BORDER_COLOR_EXT {
        return v.into_iter().map(|x| (f64::from(x.clamp(0.0, 1.0)) * 2_147_483_647.0) as i32).collect();
    }
    v.into_iter().map(|x| x.round() as i32).collect()
}
