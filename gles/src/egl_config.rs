//! The EGL configs the daemon offers, their attributes, and their matching as
//! `eglChooseConfig` specifies it (EGL 1.4 §3.4.1).

use crate::enums::*;

/// `EGL_PIXMAP_BIT`: pixmap surfaces are the library's (a pbuffer here, copied to the X pixmap).
const EGL_PIXMAP_BIT: i32 = 0x0002;
/// `EGL_OPENGL_ES3_BIT_KHR` (`EGL_KHR_create_context`).
const EGL_OPENGL_ES3_BIT_KHR: i32 = 0x0040;

/// One framebuffer configuration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Config {
    /// `EGL_CONFIG_ID`, also its handle.
    pub id: u32,
    /// Red, green, blue, alpha bits.
    pub rgba: [i32; 4],
    /// Depth bits.
    pub depth: i32,
    /// Stencil bits.
    pub stencil: i32,
}

/// Every config the daemon offers. All are window-, pixmap- and pbuffer-capable, and ES 2 and ES 3
/// renderable as Mesa's are (held to ES 2.0, Mesa keeps the ES 3 bit and refuses ES 3 contexts
/// with `EGL_BAD_MATCH`, as the daemon does until it has ES 3 contexts).
pub const CONFIGS: &[Config] = &[
    Config { id: 1, rgba: [8, 8, 8, 8], depth: 24, stencil: 8 },
    Config { id: 2, rgba: [8, 8, 8, 8], depth: 0, stencil: 0 },
    Config { id: 3, rgba: [8, 8, 8, 8], depth: 16, stencil: 0 },
    Config { id: 4, rgba: [8, 8, 8, 0], depth: 24, stencil: 8 },
    Config { id: 5, rgba: [8, 8, 8, 0], depth: 0, stencil: 0 },
    Config { id: 6, rgba: [8, 8, 8, 8], depth: 32, stencil: 0 },
    Config { id: 7, rgba: [8, 8, 8, 0], depth: 32, stencil: 0 },
];

impl Config {
    /// Looks a config up by handle.
    pub fn get(id: u32) -> Option<Config> {
        CONFIGS.iter().copied().find(|c| c.id == id)
    }

    /// The value of one `EGL_*` attribute, or `None` if the attribute is unknown.
    pub fn attrib(&self, a: i32) -> Option<i32> {
        Some(match a {
            EGL_RED_SIZE => self.rgba[0],
            EGL_GREEN_SIZE => self.rgba[1],
            EGL_BLUE_SIZE => self.rgba[2],
            EGL_ALPHA_SIZE => self.rgba[3],
            EGL_BUFFER_SIZE => self.rgba.iter().sum(),
            EGL_DEPTH_SIZE => self.depth,
            EGL_STENCIL_SIZE => self.stencil,
            EGL_CONFIG_ID => self.id as i32,
            // Pixmap surfaces are the library's: a pbuffer here, copied to the X pixmap.
            EGL_SURFACE_TYPE => EGL_WINDOW_BIT | EGL_PIXMAP_BIT | EGL_PBUFFER_BIT,
            EGL_RENDERABLE_TYPE | EGL_CONFORMANT => EGL_OPENGL_ES2_BIT | EGL_OPENGL_ES3_BIT_KHR,
            EGL_COLOR_BUFFER_TYPE => EGL_RGB_BUFFER,
            // EGL_EXT_pixel_format_float: every config is fixed-point, as Mesa's on X11 are.
            EGL_COLOR_COMPONENT_TYPE_EXT => EGL_COLOR_COMPONENT_TYPE_FIXED_EXT,
            EGL_CONFIG_CAVEAT | EGL_TRANSPARENT_TYPE | EGL_NATIVE_VISUAL_TYPE => EGL_NONE,
            EGL_MAX_PBUFFER_WIDTH | EGL_MAX_PBUFFER_HEIGHT => 8192,
            EGL_MAX_PBUFFER_PIXELS => 8192 * 8192,
            EGL_MIN_SWAP_INTERVAL => 0,
            EGL_MAX_SWAP_INTERVAL => 1,
            EGL_LEVEL
            | EGL_SAMPLES
            | EGL_SAMPLE_BUFFERS
            | EGL_LUMINANCE_SIZE
            | EGL_ALPHA_MASK_SIZE
            | EGL_NATIVE_VISUAL_ID
            | EGL_BIND_TO_TEXTURE_RGB
            | EGL_BIND_TO_TEXTURE_RGBA => 0,
            EGL_NATIVE_RENDERABLE => 0,
            // Meaningful only with a transparent type, which no config has (EGL 1.4 §3.4).
            EGL_TRANSPARENT_RED_VALUE | EGL_TRANSPARENT_GREEN_VALUE | EGL_TRANSPARENT_BLUE_VALUE => 0,
            _ => return None,
        })
    }
}

/// `eglChooseConfig`: the configs matching `attribs` (a NONE-terminated list), best first.
pub fn choose(attribs: &[i32]) -> Result<Vec<u32>, i32> {
    let mut wanted: Vec<(i32, i32)> = Vec::new();
    let mut it = attribs.chunks(2);
    for pair in &mut it {
        match *pair {
            [EGL_NONE, ..] => break,
            // A component type that is neither (nor EGL_DONT_CARE) is an error, as on Mesa.
            [EGL_COLOR_COMPONENT_TYPE_EXT, v]
                if !matches!(
                    v,
                    EGL_COLOR_COMPONENT_TYPE_FIXED_EXT | EGL_COLOR_COMPONENT_TYPE_FLOAT_EXT | EGL_DONT_CARE
                ) =>
            {
                return Err(EGL_BAD_ATTRIBUTE)
            }
            [a, v] => wanted.push((a, v)),
            _ => return Err(EGL_BAD_ATTRIBUTE),
        }
    }
    let mut out: Vec<Config> = Vec::new();
    'configs: for c in CONFIGS {
        for &(a, v) in &wanted {
            if v == EGL_DONT_CARE {
                continue;
            }
            let have = c.attrib(a).ok_or(EGL_BAD_ATTRIBUTE)?;
            let ok = match a {
                EGL_SURFACE_TYPE | EGL_RENDERABLE_TYPE | EGL_CONFORMANT => have & v == v,
                EGL_CONFIG_ID
                | EGL_COLOR_BUFFER_TYPE
                | EGL_CONFIG_CAVEAT
                | EGL_TRANSPARENT_TYPE
                | EGL_TRANSPARENT_RED_VALUE
                | EGL_TRANSPARENT_GREEN_VALUE
                | EGL_TRANSPARENT_BLUE_VALUE
                | EGL_LEVEL
                | EGL_COLOR_COMPONENT_TYPE_EXT
                | EGL_NATIVE_VISUAL_TYPE => have == v,
                EGL_NATIVE_VISUAL_ID | EGL_MAX_PBUFFER_WIDTH | EGL_MAX_PBUFFER_HEIGHT | EGL_MAX_PBUFFER_PIXELS => true,
                _ => have >= v,
            };
            if !ok {
                continue 'configs;
            }
        }
        out.push(*c);
    }
    // EGL 1.4 §3.4.1.2: more colour bits (of the requested channels) first, then smaller
    // buffers, then smaller depth and stencil, then config id.
    let requested = |a: i32| wanted.iter().any(|&(k, v)| k == a && v != 0 && v != EGL_DONT_CARE);
    let color_bits = |c: &Config| {
        [EGL_RED_SIZE, EGL_GREEN_SIZE, EGL_BLUE_SIZE, EGL_ALPHA_SIZE]
            .iter()
            .zip(c.rgba)
            .filter(|(a, _)| requested(**a))
            .map(|(_, b)| b)
            .sum::<i32>()
    };
    out.sort_by_key(|c| (-color_bits(c), c.rgba.iter().sum::<i32>(), c.depth, c.stencil, c.id));
    Ok(out.into_iter().map(|c| c.id).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_32_configs_never_displace_a_first_choice() {
        assert_eq!(choose(&[EGL_DEPTH_SIZE, 32, EGL_NONE]).expect("depth 32"), vec![7, 6]);
        assert_eq!(choose(&[EGL_DEPTH_SIZE, 25, EGL_ALPHA_SIZE, 1, EGL_NONE]).expect("alpha"), vec![6]);
        // Without configs 6 and 7 every request got what the older configs give, in the same
        // order: its first choice must stay among them.
        for depth in [EGL_DONT_CARE, 0, 1, 16, 24] {
            for stencil in [EGL_DONT_CARE, 0, 1, 8] {
                for alpha in [EGL_DONT_CARE, 0, 8] {
                    for red in [EGL_DONT_CARE, 0, 1, 8] {
                        let req = [
                            EGL_DEPTH_SIZE,
                            depth,
                            EGL_STENCIL_SIZE,
                            stencil,
                            EGL_ALPHA_SIZE,
                            alpha,
                            EGL_RED_SIZE,
                            red,
                            EGL_NONE,
                        ];
                        let got = choose(&req).expect("valid");
                        let old: Vec<u32> = got.iter().copied().filter(|&id| id <= 5).collect();
                        if let Some(first) = old.first() {
                            assert_eq!(got.first(), Some(first), "{req:?}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn choose_filters_and_orders() {
        let all = choose(&[EGL_NONE]).expect("all");
        assert_eq!(all.len(), CONFIGS.len());
        let d = choose(&[EGL_DEPTH_SIZE, 1, EGL_ALPHA_SIZE, 8, EGL_NONE]).expect("depth");
        assert_eq!(d, vec![3, 1, 6], "smallest sufficient depth first");
        assert_eq!(choose(&[EGL_STENCIL_SIZE, 16, EGL_NONE]).expect("none"), Vec::<u32>::new());
        assert_eq!(choose(&[0x7777, 1, EGL_NONE]), Err(EGL_BAD_ATTRIBUTE));
    }
}
