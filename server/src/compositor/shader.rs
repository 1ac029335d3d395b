//! Pass shapes and their WGSL: the template `shaders/composite.wgsl` specialised per shape.

/// The pass shader's template.
const TEMPLATE: &str = include_str!("../../../shaders/composite.wgsl");

/// The background fill of uncovered cells.
pub const FILL: &str = include_str!("../../../shaders/fill.wgsl");

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

    /// Binding of surface `i`'s colour image.
    pub fn color_binding(i: usize) -> u32 {
        2 + 2 * i as u32
    }

    /// Binding of surface `i`'s depth image.
    pub fn depth_binding(i: usize) -> u32 {
        3 + 2 * i as u32
    }

    /// Whether the pass has the template property `name` (`surface`: inside `//#each`).
    fn has(&self, name: &str, surface: Option<usize>) -> bool {
        match name {
            "select" => self.select(),
            "intermediate" => self.intermediate,
            "last" => self.last,
            "lit" => self.lit,
            "from_depth" => self.from_depth,
            "depth" => self.depth(),
            "base" => self.base,
            "copy" => self.copy,
            "map" => self.map,
            "factor" => self.factor,
            "first" => surface == Some(0) && !self.intermediate,
            other => unreachable!("shaders/composite.wgsl names an unknown property {other:?}"),
        }
    }
}

/// Renders template lines from `*pos` up to the matching `//#end` (or the end) into `out`,
/// keeping them when `keep`; `surface` is the surface of an enclosing `//#each surface`.
fn render(lines: &[&str], pos: &mut usize, keep: bool, surface: Option<usize>, k: &PassKind, out: &mut String) {
    while let Some(line) = lines.get(*pos) {
        *pos += 1;
        let directive = line.trim();
        if directive == "//#end" {
            return;
        }
        if let Some(cond) = directive.strip_prefix("//#if ") {
            let on = match cond.strip_prefix('!') {
                Some(name) => !k.has(name, surface),
                None => k.has(cond, surface),
            };
            render(lines, pos, keep && on, surface, k, out);
        } else if directive == "//#each surface" {
            let body = *pos;
            render(lines, pos, false, surface, k, out);
            if keep {
                for i in 0..k.surfaces {
                    let mut p = body;
                    render(lines, &mut p, true, Some(i), k, out);
                }
            }
        } else if keep && !directive.starts_with("//") {
            // Comment lines document the template; the specialised shader leaves them out.
            let mut l = line
                .replace("{{N}}", &k.surfaces.to_string())
                .replace("{{icolor_binding}}", &PassKind::color_binding(k.surfaces).to_string())
                .replace("{{igeom_binding}}", &PassKind::depth_binding(k.surfaces).to_string());
            if let Some(i) = surface {
                l = l
                    .replace("{{i}}", &i.to_string())
                    .replace("{{color_binding}}", &PassKind::color_binding(i).to_string())
                    .replace("{{depth_binding}}", &PassKind::depth_binding(i).to_string());
            }
            out.push_str(&l);
            out.push('\n');
        }
    }
}

/// WGSL for one pass shape: the template specialised.
pub fn shader(k: &PassKind) -> String {
    let lines: Vec<&str> = TEMPLATE.lines().collect();
    let mut out = String::with_capacity(TEMPLATE.len() * 2);
    render(&lines, &mut 0, true, None, k, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn validate(src: &str) {
        let module = naga::front::wgsl::parse_str(src).unwrap_or_else(|e| panic!("{}\n{src}", e.emit_to_string(src)));
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{e:?}\n{src}"));
    }

    #[test]
    fn every_pass_shape_specialises_to_valid_wgsl() {
        validate(FILL);
        let src = shader(&PassKind::light_map());
        validate(&src);
        assert!(src.contains("fn factor(") && !src.contains("textureLoad"), "{src}");
        for surfaces in 1..=4 {
            for bits in 0..128u32 {
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
                };
                // Passes that are never built: a non-last pass selects, the 2D copy is one
                // unlit surface on the background, a light map serves one lit surface with a
                // per-surface normal.
                if (!k.last && !k.select())
                    || (k.copy && (k.select() || k.lit || !k.base))
                    || (k.map && (k.select() || !k.lit || k.from_depth || !k.last))
                {
                    continue;
                }
                let src = shader(&k);
                assert!(!src.contains("{{") && !src.contains("//#"), "unfilled template:\n{src}");
                validate(&src);
                assert_eq!(src.matches("var color").count(), surfaces);
                assert_eq!(src.matches("var depth").count(), if k.depth() { surfaces } else { 0 });
                assert_eq!(src.contains("var igeom"), k.intermediate);
                assert_eq!(src.contains("fn eye("), k.select(), "eye depth where the select runs");
                assert_eq!(src.contains("var lmap"), k.map);
                assert_eq!(src.contains("light(best_c"), k.last && k.lit && !k.copy);
                assert_eq!(src.matches("fn dn").count(), if k.from_depth { surfaces } else { 0 });
                assert_eq!(src.contains("P.background.rgb"), k.last && k.base && !k.copy);
            }
        }
    }
}
