//! Every shader program glmark2's default benchmark list compiles, rebuilt from the installed
//! shader files (Debian's glmark2-data) the way glmark2's ShaderSource assembles them: headers,
//! prepended constants and `$PLACEHOLDER$` substitutions. Mesa must compile and link each pair
//! (which proves the rebuilt text is what a real driver accepts), and then Strata's GLSL ES
//! front end must translate, validate and link it.

mod support;

use strata_client::{Calls, ClientError};
use strata_gles::glsl;
use strata_protocol::Text;
use support::mesa::MesaGl;

const DIR: &str = "/usr/share/glmark2/shaders";

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Vertex,
    Fragment,
    Unknown,
}

/// A shader under assembly, mirroring glmark2's ShaderSource.
struct Source {
    text: String,
    precision_high: bool,
}

fn file(name: &str) -> String {
    let bytes = std::fs::read(format!("{DIR}/{name}")).unwrap_or_else(|e| panic!("{DIR}/{name}: {e}"));
    String::from_utf8_lossy(&bytes).into_owned()
}

impl Source {
    fn file(name: &str) -> Source {
        Source { text: file(name), precision_high: false }
    }

    fn text(text: String) -> Source {
        Source { text, precision_high: false }
    }

    /// `add_const`/`add`: after the precision statement's `#endif` if there is one, else first.
    fn add(&mut self, decl: &str) -> &mut Self {
        let at = match self.text.rfind("precision") {
            Some(p) => {
                let rest = &self.text[p..];
                let endif = rest.find("#endif");
                let next_if = rest.find("#if");
                match endif {
                    Some(e) if next_if.is_none_or(|i| e < i) => {
                        let after = p + e;
                        self.text[after..].find('\n').map_or(self.text.len(), |n| after + n + 1)
                    }
                    _ => self.text[p..].find('\n').map_or(self.text.len(), |n| p + n + 1),
                }
            }
            None => 0,
        };
        self.text.insert_str(at, decl);
        self
    }

    fn vec4(&mut self, name: &str, v: [f32; 4]) -> &mut Self {
        self.add(&format!("const vec4 {name} = vec4({:.6}, {:.6}, {:.6}, {:.6});\n", v[0], v[1], v[2], v[3]))
    }

    fn vec3(&mut self, name: &str, v: [f32; 3]) -> &mut Self {
        self.add(&format!("const vec3 {name} = vec3({:.6}, {:.6}, {:.6});\n", v[0], v[1], v[2]))
    }

    fn vec2(&mut self, name: &str, v: [f32; 2]) -> &mut Self {
        self.add(&format!("const vec2 {name} = vec2({:.6}, {:.6});\n", v[0], v[1]))
    }

    fn float(&mut self, name: &str, v: f32) -> &mut Self {
        self.add(&format!("const float {name} = {v:.6};\n"))
    }

    fn replace(&mut self, from: &str, to: &str) -> &mut Self {
        self.text = self.text.replace(from, to);
        self
    }

    /// `str()`: the macro block and the precision block, then the text.
    fn str(&self) -> String {
        let kind = if self.text.contains("gl_FragColor") {
            Kind::Fragment
        } else if self.text.contains("gl_Position") {
            Kind::Vertex
        } else {
            Kind::Unknown
        };
        header(kind, self.precision_high) + &self.text
    }
}

fn header(kind: Kind, high: bool) -> String {
    let frag = if kind == Kind::Fragment { " && defined(GL_FRAGMENT_PRECISION_HIGH)" } else { "" };
    let mut h = format!(
        "#if defined(GL_ES){frag}\n#define HIGHP_OR_DEFAULT highp\n#else\n#define HIGHP_OR_DEFAULT\n#endif\n#if defined(GL_ES)\n#define MEDIUMP_OR_DEFAULT mediump\n#else\n#define MEDIUMP_OR_DEFAULT\n#endif\n"
    );
    if kind == Kind::Fragment {
        if high {
            h.push_str("#ifdef GL_ES\n#ifdef GL_FRAGMENT_PRECISION_HIGH\nprecision highp float;\n#else\nprecision mediump float;\n#endif\n#endif\n");
        } else {
            h.push_str("#ifdef GL_ES\nprecision mediump float;\n#endif\n");
        }
    }
    h
}

const LSP: [f32; 4] = [20.0, 20.0, 10.0, 1.0];
const HALF: [f32; 3] = [0.408248, 0.408248, 0.816497];

fn light_basic_vs(diffuse: [f32; 4], lsp: [f32; 4]) -> String {
    Source::file("light-basic.vert").vec4("LightSourcePosition", lsp).vec4("MaterialDiffuse", diffuse).str()
}

fn plain(name: &str) -> String {
    Source::file(name).str()
}

/// `$MAIN$` for the step scenes: an untyped source's header, then `k` copies of a step.
fn steps(step: &str, k: usize) -> String {
    Source::text(step.repeat(k)).str()
}

/// A separable blur fragment shader as desktop and terrain build them.
fn blur(file_name: &str, kernel: &[f32], horizontal: bool, step: f32, tilt: Option<f32>) -> String {
    let r = kernel.len() as i32 - 1;
    let mut s = Source::file(file_name);
    for (i, k) in kernel.iter().enumerate() {
        s.float(&format!("Kernel{i}"), *k);
    }
    let var = if tilt.is_some() {
        if horizontal {
            "stepX"
        } else {
            "stepY"
        }
    } else if horizontal {
        "TextureStepX"
    } else {
        "TextureStepY"
    };
    let mut conv = String::new();
    if let Some(t) = tilt {
        s.float("TiltShift", t);
        let (v, c) = if horizontal { ("stepX", "TextureStepX") } else { ("stepY", "TextureStepY") };
        conv.push_str(&format!("float {v} = {c} * abs(TiltShift - TextureCoord.y) / abs(1.0 - TiltShift);\n"));
    }
    conv.push_str("result = \n");
    for o in -r..=r {
        let off = if horizontal { format!("vec2({o}.0 * {var}, 0.0)") } else { format!("vec2(0.0, {o}.0 * {var})") };
        conv.push_str(&format!("texture2D(Texture0, TextureCoord + {off}) * Kernel{} +\n", o.abs()));
    }
    conv.push_str("0.0 ;\n");
    s.replace("$CONVOLUTION$", &conv);
    s.float(if horizontal { "TextureStepX" } else { "TextureStepY" }, step);
    s.str()
}

fn effect2d(kernel: &[&[f32]]) -> String {
    let (h, w) = (kernel.len(), kernel[0].len());
    let flat: Vec<f32> = kernel.iter().flat_map(|r| r.iter().copied()).collect();
    let sum: f32 = flat.iter().sum();
    let norm = if sum != 0.0 { sum } else { flat.iter().filter(|v| **v > 0.0).sum() };
    let mut inner = Source::file("effect-2d-convolution.frag");
    inner.float("TextureStepX", 1.0 / 800.0).float("TextureStepY", 1.0 / 600.0);
    let consts: String =
        flat.iter().enumerate().map(|(i, v)| format!("const float Kernel{i} = {:.6};\n", v / norm)).collect();
    inner.add(&consts);
    let terms: Vec<String> = (0..flat.len())
        .map(|i| {
            let x = (i % w) as f32 - ((w - 1) / 2) as f32;
            let y = -((i / w) as f32 - ((h - 1) / 2) as f32);
            format!(
                "texture2D(Texture0, TextureCoord + vec2({x:.1} * TextureStepX, {y:.1} * TextureStepY)) * Kernel{i}"
            )
        })
        .collect();
    inner.replace("$CONVOLUTION$", &format!("result = {};\n", terms.join(" +\n")));
    Source::text(inner.str()).str()
}

fn phong_fs() -> String {
    let mut inner = Source::file("light-phong.frag");
    inner.vec4("LightSourcePosition0", [0.0, 1.0, 0.0, 1.0]).vec4("LightColor0", [0.8, 0.8, 0.8, 1.0]);
    inner.replace(
        "$DO_LIGHTS$",
        "    gl_FragColor = vec4(0.0, 0.0, 0.0, 0.0);\n    gl_FragColor += compute_color(LightSourcePosition0, LightColor0);\n",
    );
    let mut outer = Source::text(inner.str());
    outer.vec4("MaterialDiffuse", [0.0, 0.0, 1.0, 1.0]);
    outer.str()
}

/// (name, vertex source, fragment source) for every program of the default benchmark list.
fn corpus() -> Vec<(String, String, String)> {
    let mut v: Vec<(String, String, String)> = Vec::new();
    let mut add = |name: &str, vs: String, fs: String| v.push((name.to_string(), vs, fs));
    add("build", light_basic_vs([1.0; 4], LSP), plain("light-basic.frag"));
    add("texture", light_basic_vs([1.0; 4], LSP), plain("light-basic-tex.frag"));
    add(
        "texture:linear-shader",
        light_basic_vs([1.0; 4], LSP),
        Source::file("light-basic-tex-bilinear.frag").vec2("TextureSize", [512.0, 512.0]).str(),
    );
    add(
        "texture:texgen",
        Source::file("light-basic-texgen.vert")
            .float("PI", std::f32::consts::PI)
            .vec4("LightSourcePosition", LSP)
            .vec4("MaterialDiffuse", [1.0; 4])
            .str(),
        plain("light-basic-tex.frag"),
    );
    add("shading:gouraud", light_basic_vs([0.0, 0.0, 1.0, 1.0], LSP), plain("light-basic.frag"));
    add(
        "shading:blinn-phong-inf",
        plain("light-advanced.vert"),
        Source::file("light-advanced.frag").vec4("LightSourcePosition", LSP).vec3("LightSourceHalfVector", HALF).str(),
    );
    add("shading:phong", plain("light-phong.vert"), phong_fs());
    add("shading:cel", plain("light-phong.vert"), plain("light-cel.frag"));
    for (variant, base) in
        [("high-poly", "bump-poly"), ("normals", "bump-normals"), ("normals-tangent", "bump-normals-tangent")]
    {
        let fs = Source::file(&format!("{base}.frag"))
            .vec4("LightSourcePosition", LSP)
            .vec3("LightSourceHalfVector", HALF)
            .str();
        add(&format!("bump:{variant}"), plain(&format!("{base}.vert")), fs);
    }
    let height = Source::file("bump-height.frag")
        .vec4("LightSourcePosition", LSP)
        .vec3("LightSourceHalfVector", HALF)
        .float("TextureStepX", 1.0 / 1024.0)
        .float("TextureStepY", 1.0 / 1024.0)
        .str();
    add("bump:height", plain("bump-height.vert"), height);
    add("effect2d:edge", plain("effect-2d.vert"), effect2d(&[&[0.0, 1.0, 0.0], &[1.0, -4.0, 1.0], &[0.0, 1.0, 0.0]]));
    add("effect2d:blur", plain("effect-2d.vert"), effect2d(&[&[1.0; 5], &[1.0; 5], &[1.0; 5]]));
    add("pulsar", plain("pulsar.vert"), plain("light-basic.frag"));
    add(
        "pulsar:light",
        Source::file("pulsar-light.vert").vec4("LightSourcePosition", [-20.0, 20.0, -20.0, 1.0]).str(),
        plain("light-basic.frag"),
    );
    add("pulsar:texture", plain("pulsar.vert"), plain("light-basic-tex.frag"));
    add("text-renderer", plain("text-renderer.vert"), plain("text-renderer.frag"));
    add("desktop", plain("desktop.vert"), plain("desktop.frag"));
    let desk = [0.239365, 0.199935, 0.116512, 0.047370, 0.013437, 0.002659];
    add("desktop:blur-h", plain("desktop.vert"), blur("desktop-blur.frag", &desk, true, 1.0 / 800.0, None));
    add("desktop:blur-v", plain("desktop.vert"), blur("desktop-blur.frag", &desk, false, 1.0 / 600.0, None));
    add("buffer", plain("buffer-wireframe.vert"), plain("buffer-wireframe.frag"));
    for p in ["table", "paper", "text", "under-table", "lamp-lit", "lamp-unlit", "logo", "logo-flat", "logo-shadow"] {
        add(&format!("ideas:{p}"), plain(&format!("ideas-{p}.vert")), plain(&format!("ideas-{p}.frag")));
    }
    add("jellyfish:gradient", plain("gradient.vert"), plain("gradient.frag"));
    let mut jf = Source::file("jellyfish.frag");
    jf.precision_high = true;
    add("jellyfish", plain("jellyfish.vert"), jf.str());
    add("terrain", plain("terrain.vert"), plain("terrain.frag"));
    for f in ["noise", "normalmap", "luminance", "overlay"] {
        add(&format!("terrain:{f}"), plain("terrain-texture.vert"), plain(&format!("terrain-{f}.frag")));
    }
    let bloom = [0.212609, 0.206068, 0.187627];
    let tilt = [0.163030, 0.152223, 0.123913, 0.087939, 0.054409];
    add(
        "terrain:bloom-h",
        plain("terrain-texture.vert"),
        blur("terrain-blur.frag", &bloom, true, 1.0 / 800.0, Some(0.0)),
    );
    add(
        "terrain:bloom-v",
        plain("terrain-texture.vert"),
        blur("terrain-blur.frag", &bloom, false, 1.0 / 256.0, Some(0.0)),
    );
    add(
        "terrain:tilt-h",
        plain("terrain-texture.vert"),
        blur("terrain-blur.frag", &tilt, true, 1.0 / 800.0, Some(0.5)),
    );
    add(
        "terrain:tilt-v",
        plain("terrain-texture.vert"),
        blur("terrain-blur.frag", &tilt, false, 1.0 / 600.0, Some(0.5)),
    );
    add("shadow:depth", plain("depth.vert"), plain("depth.frag"));
    add(
        "shadow",
        Source::file("shadow.vert").vec4("MaterialDiffuse", [0.3, 0.3, 0.3, 1.0]).str(),
        plain("shadow.frag"),
    );
    add("shadow:light", light_basic_vs([1.0; 4], [0.0, 3.0, 2.0, 1.0]), plain("light-basic.frag"));
    add(
        "refract",
        plain("light-refract.vert"),
        Source::file("light-refract.frag")
            .vec4("LightColor", [0.4, 0.4, 0.4, 1.0])
            .vec4("LightSourcePosition", [1.0, 1.0, 2.0, 1.0])
            .float("RefractiveIndex", 1.2)
            .str(),
    );
    let cond = file("conditionals-step-conditional.all");
    for (vs_k, fs_k) in [(0, 0), (0, 5), (5, 0)] {
        add(
            &format!("conditionals:{vs_k}/{fs_k}"),
            Source::file("conditionals.vert").replace("$MAIN$", &steps(&cond, vs_k)).str(),
            Source::file("conditionals.frag").replace("$MAIN$", &steps(&cond, fs_k)).str(),
        );
    }
    let call = file("function-call.all");
    for level in ["low", "medium"] {
        let vs = Source::file("function.vert")
            .replace("$MAIN$", &steps(&call, 1))
            .replace("$PROCESS$", &file("function-step-low.all"))
            .str();
        let fs = Source::file("function.frag")
            .replace("$MAIN$", &steps(&call, 5))
            .replace("$PROCESS$", &file(&format!("function-step-{level}.all")))
            .str();
        add(&format!("function:{level}"), vs, fs);
    }
    let looped = file("loop-step-loop.all");
    let vs = Source::file("loop.vert").replace("$MAIN$", &steps(&looped.replace("$NLOOPS$", "VertexLoops"), 1)).str();
    for (variant, main) in [
        ("fragment-loop=false", steps(&file("loop-step-simple.all"), 5)),
        ("fragment-uniform=false", steps(&looped.replace("$NLOOPS$", "5"), 1)),
        ("fragment-uniform=true", steps(&looped.replace("$NLOOPS$", "FragmentLoops"), 1)),
    ] {
        add(&format!("loop:{variant}"), vs.clone(), Source::file("loop.frag").replace("$MAIN$", &main).str());
    }
    v
}

fn mesa_links(gl: &mut MesaGl, vs: &str, fs: &str, base: u32) -> Result<(), String> {
    let run = |gl: &mut MesaGl| -> Result<Result<(), String>, ClientError> {
        let p = base;
        gl.glCreateProgram(p)?;
        for (i, (ty, src)) in [(0x8B31u32, vs), (0x8B30, fs)].into_iter().enumerate() {
            let s = base + 1 + i as u32;
            gl.glCreateShader(ty, s)?;
            gl.glShaderSource(s, Text::borrowed(src))?;
            gl.glCompileShader(s)?;
            if gl.glGetShaderiv(s, 0x8B81)? == 0 {
                return Ok(Err(format!("Mesa rejects the rebuilt shader: {}", gl.glGetShaderInfoLog(s)?)));
            }
            gl.glAttachShader(p, s)?;
        }
        gl.glLinkProgram(p)?;
        if gl.glGetProgramiv(p, 0x8B82)? == 0 {
            return Ok(Err(format!("Mesa does not link the rebuilt program: {}", gl.glGetProgramInfoLog(p)?)));
        }
        Ok(Ok(()))
    };
    run(gl).map_err(|e| e.to_string())?
}

#[test]
fn every_glmark2_shader_translates_validates_and_links() {
    if !std::path::Path::new(DIR).is_dir() {
        if std::env::var_os("STRATA_REQUIRE_ORACLES").is_some() {
            panic!("{DIR} is missing and STRATA_REQUIRE_ORACLES is set");
        }
        eprintln!("SKIPPED: {DIR} missing; install glmark2-data to run the shader corpus");
        return;
    }
    let mut mesa = match MesaGl::open(16, 16) {
        Ok(m) => Some(m),
        Err(e) if std::env::var_os("STRATA_REQUIRE_ORACLES").is_some() => panic!("Mesa GLES2 unavailable: {e}"),
        Err(e) => {
            eprintln!("note: Mesa GLES2 unavailable ({e}); checking Strata only");
            None
        }
    };
    let corpus = corpus();
    let mut failures = Vec::new();
    for (i, (name, vs, fs)) in corpus.iter().enumerate() {
        if let Some(m) = mesa.as_mut() {
            if let Err(e) = mesa_links(m, vs, fs, 1000 + 10 * i as u32) {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        }
        let result = glsl::compile(glsl::Stage::Vertex, vs)
            .map_err(|e| format!("vertex shader does not compile:\n{e}"))
            .and_then(|v| {
                glsl::compile(glsl::Stage::Fragment, fs)
                    .map_err(|e| format!("fragment shader does not compile:\n{e}"))
                    .map(|f| (v, f))
            })
            .and_then(|(v, f)| glsl::link(&v, &f, &Default::default(), 16).map(|_| ()));
        match result {
            Ok(()) => eprintln!("ok   {name}"),
            Err(e) => failures.push(format!("{name}: {e}")),
        }
    }
    assert!(corpus.len() >= 50, "corpus has only {} programs", corpus.len());
    // Every installed shader file is part of some program: its first code line appears.
    let used: String = corpus.iter().map(|(_, v, f)| format!("{v}\n{f}")).collect();
    let mut unused = Vec::new();
    for entry in std::fs::read_dir(DIR).expect("shader dir").flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if !(name.ends_with(".vert") || name.ends_with(".frag") || name.ends_with(".all")) {
            continue;
        }
        let text = file(&name);
        let line = text.lines().map(str::trim_end).find(|l| !l.trim().is_empty() && !l.contains('$')).unwrap_or("");
        if !line.is_empty() && !used.contains(line) {
            unused.push(name);
        }
    }
    assert!(unused.is_empty(), "installed shader files no rebuilt program uses: {unused:?}");
    assert!(
        failures.is_empty(),
        "{} of {} glmark2 programs fail:\n{}",
        failures.len(),
        corpus.len(),
        failures.join("\n\n")
    );
}
