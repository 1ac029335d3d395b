//! The pure half of the piglit test: reading piglit's results, reading the exceptions file, and
//! comparing the run through Strata with the native one.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The extensions Strata is to offer (each advertised only once it works). A test that needs
/// one of them is never an exception: it has to pass.
pub const IN_SCOPE_EXTENSIONS: &[&str] = &[
    "GL_OES_vertex_array_object",
    "GL_OES_standard_derivatives",
    "GL_OES_texture_npot",
    "GL_OES_packed_depth_stencil",
    "GL_OES_depth24",
    "GL_OES_rgb8_rgba8",
    "GL_EXT_texture_format_BGRA8888",
    "GL_OES_texture_half_float",
    "GL_OES_texture_half_float_linear",
    "GL_OES_texture_float",
    "GL_OES_texture_float_linear",
    "GL_OES_compressed_ETC1_RGB8_texture",
    "GL_EXT_texture_compression_s3tc",
    "GL_EXT_discard_framebuffer",
    "GL_EXT_blend_minmax",
    "GL_KHR_debug",
    // What the executor already offers.
    "GL_OES_depth_texture",
    "GL_OES_mapbuffer",
    "GL_OES_element_index_uint",
    "GL_OES_vertex_half_float",
    "GL_EXT_frag_depth",
    "GL_EXT_polygon_offset_clamp",
    "GL_KHR_parallel_shader_compile",
    "GL_OES_required_internalformat",
    "GL_OES_draw_elements_base_vertex",
    "GL_EXT_read_format_bgra",
    "GL_EXT_draw_elements_base_vertex",
    "GL_EXT_multi_draw_arrays",
    "GL_EXT_draw_instanced",
    "GL_OES_stencil8",
    "GL_KHR_no_error",
    "GL_KHR_context_flush_control",
    "GL_EXT_texture_rg",
    "GL_EXT_debug_label",
    "GL_NV_read_buffer",
    "GL_OES_fbo_render_mipmap",
    "GL_EXT_texture_filter_anisotropic",
    "GL_EXT_texture_compression_dxt1",
    "GL_ANGLE_texture_compression_dxt3",
    "GL_ANGLE_texture_compression_dxt5",
    "GL_EXT_map_buffer_range",
    "GL_EXT_compressed_ETC1_RGB8_sub_texture",
    "GL_NV_pack_subimage",
    "GL_ANGLE_pack_reverse_row_order",
    "GL_EXT_texture_type_2_10_10_10_REV",
    "GL_EXT_depth_clamp",
    "GL_APPLE_texture_max_level",
    "GL_OES_surfaceless_context",
    "EGL_KHR_surfaceless_context",
    "GL_MESA_bgra",
    "GL_EXT_draw_buffers",
    "GL_NV_draw_buffers",
    "GL_NV_fbo_color_attachments",
    "GL_EXT_blend_func_extended",
    "GL_OES_EGL_sync",
    "GL_OES_get_program_binary",
    "GL_EXT_clip_control",
    "GL_OES_depth_texture_cube_map",
    "GL_NV_read_depth",
    "GL_NV_read_stencil",
    "GL_NV_read_depth_stencil",
    "GL_EXT_texture_compression_s3tc_srgb",
    "GL_KHR_texture_compression_astc_ldr",
    "GL_OES_EGL_image",
    "GL_OES_EGL_image_external",
    "GL_NV_pixel_buffer_object",
    "GL_EXT_separate_shader_objects",
    "GL_EXT_texture_mirror_clamp_to_edge",
    "GL_EXT_texture_border_clamp",
    "GL_OES_texture_border_clamp",
    "GL_EXT_color_buffer_half_float",
    "GL_OES_texture_3D",
    "GL_KHR_texture_compression_astc_sliced_3d",
    "GL_EXT_disjoint_timer_query",
    "EGL_KHR_image_base",
    "EGL_KHR_gl_texture_2D_image",
    "EGL_KHR_gl_texture_cubemap_image",
    "EGL_KHR_gl_renderbuffer_image",
    "GL_KHR_robust_buffer_access_behavior",
    "EGL_EXT_create_context_robustness",
    "EGL_KHR_fence_sync",
    "EGL_KHR_wait_sync",
    "EGL_KHR_reusable_sync",
    "GL_EXT_occlusion_query_boolean",
    "GL_NV_conditional_render",
    "GL_EXT_robustness",
    "GL_KHR_robustness",
    "EGL_KHR_create_context",
    "GL_EXT_unpack_subimage",
    "EGL_EXT_buffer_age",
    "EGL_EXT_pixel_format_float",
    "EGL_IMG_context_priority",
    "EGL_KHR_context_flush_control",
    "EGL_KHR_create_context_no_error",
    "EGL_KHR_get_all_proc_addresses",
    "EGL_KHR_gl_colorspace",
    "EGL_KHR_no_config_context",
    "EGL_KHR_swap_buffers_with_damage",
    "EGL_STRATA_surface_id",
    "EGL_STRATA_surface_projection",
];

/// The reasons a test of the GLES 2.0 selection may be excused, as the part of a reason before
/// its first colon. No "ES 3.x context": held to ES 2.0, Mesa cannot pass a test that needs one.
pub const EXCUSES: &[&str] = &["desktop GL context", "ES 1.x context", "extension"];

/// The reasons a test of the GLES 3.0 selection may be excused: Strata keeps a rule of the ES
/// 3.0 specification that Mesa relaxes ("ES 3.0 spec"), the test needs the image side of ES 3.0
/// (samplers, formats, texture units: not in the selection's areas), or what it needs is not
/// built yet ("not yet", which counts against the selection's 95 %).
pub const EXCUSES_ES3: &[&str] = &["ES 3.0 spec", "image side", "not yet"];

/// One test's result as piglit recorded it.
#[derive(Debug, Clone, Default)]
pub struct Outcome {
    /// pass, fail, skip, crash, warn, timeout, ...
    pub result: String,
    /// The test's standard output.
    pub out: String,
    /// The test's standard error.
    pub err: String,
    /// The command line piglit ran.
    pub command: String,
    /// The exit status, when the process exited.
    pub returncode: Option<i64>,
    /// Subtest names with results.
    pub subtests: Vec<(String, String)>,
}

/// Every test of one run, by piglit's name (`spec@glsl-es-1.00@...`).
pub type Run = BTreeMap<String, Outcome>;

/// Reads `results.json` (piglit's JSON backend, uncompressed) from a results directory.
pub fn load_run(dir: &Path) -> Result<Run, String> {
    let path = dir.join("results.json");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    parse_run(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// Parses the text of piglit's `results.json`.
pub fn parse_run(text: &str) -> Result<Run, String> {
    let v: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
    let tests = v["tests"].as_object().ok_or("no \"tests\" object")?;
    let s = |t: &serde_json::Value, k: &str| t[k].as_str().unwrap_or_default().to_string();
    let mut run = Run::new();
    for (name, t) in tests {
        let subtests = t["subtests"]
            .as_object()
            .map(|m| {
                m.iter()
                    .filter(|(k, _)| k.as_str() != "__type__")
                    .map(|(k, r)| (k.clone(), r.as_str().unwrap_or_default().to_string()))
                    .collect()
            })
            .unwrap_or_default();
        let outcome = Outcome {
            result: t["result"].as_str().ok_or_else(|| format!("{name}: no result"))?.to_string(),
            out: s(t, "out"),
            err: s(t, "err"),
            command: s(t, "command"),
            returncode: t["returncode"].as_i64(),
            subtests,
        };
        run.insert(name.clone(), outcome);
    }
    Ok(run)
}

/// How many tests of a run ended in each result.
pub fn counts(run: &Run) -> BTreeMap<&str, usize> {
    let mut c = BTreeMap::new();
    for o in run.values() {
        *c.entry(o.result.as_str()).or_insert(0) += 1;
    }
    c
}

/// `pass 50, fail 58, ...` for a run.
pub fn counts_line(run: &Run) -> String {
    let c = counts(run);
    let mut parts: Vec<String> =
        ["pass", "fail", "skip", "crash"].iter().map(|k| format!("{k} {}", c.get(k).copied().unwrap_or(0))).collect();
    parts.extend(
        c.iter().filter(|(k, _)| !["pass", "fail", "skip", "crash"].contains(k)).map(|(k, n)| format!("{k} {n}")),
    );
    format!("{} ({} tests)", parts.join(", "), run.len())
}

/// One line of the exceptions file: a test that need not pass through Strata, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Exception {
    /// The piglit test name.
    pub name: String,
    /// Why, starting with one of [`EXCUSES`] and a colon.
    pub reason: String,
    /// The 1-based line number in the file.
    pub line: usize,
}

/// Parses the exceptions file: `TEST NAME | EXCUSE: detail` per line, `#` comments, blank lines.
/// Rejects unknown excuses, duplicates, and an `extension` excuse that names an extension in scope.
pub fn parse_exceptions(text: &str) -> Result<Vec<Exception>, String> {
    parse_exceptions_with(text, EXCUSES)
}

/// [`parse_exceptions`] with the excuses `excuses` allows.
pub fn parse_exceptions_with(text: &str, excuses: &[&str]) -> Result<Vec<Exception>, String> {
    let mut seen = BTreeSet::new();
    let mut list = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let n = i + 1;
        let (name, reason) = line.split_once(" | ").ok_or_else(|| format!("line {n}: expected `TEST | REASON`"))?;
        let (name, reason) = (name.trim(), reason.trim());
        let (excuse, detail) = reason.split_once(':').ok_or_else(|| format!("line {n}: reason has no `EXCUSE:`"))?;
        if !excuses.contains(&excuse) {
            return Err(format!("line {n}: excuse {excuse:?} is not one of {excuses:?}"));
        }
        if detail.trim().is_empty() {
            return Err(format!("line {n}: the reason says nothing after {excuse:?}"));
        }
        if excuse == "extension" {
            let ext = detail.split_whitespace().next().unwrap_or_default();
            if !(ext.starts_with("GL_") || ext.starts_with("EGL_")) {
                return Err(format!("line {n}: an extension excuse starts with the extension's name, not {ext:?}"));
            }
            if IN_SCOPE_EXTENSIONS.contains(&ext) {
                return Err(format!("line {n}: {ext} is in scope, so a test that needs it is no exception"));
            }
        }
        if !seen.insert(name.to_string()) {
            return Err(format!("line {n}: {name} is listed twice"));
        }
        list.push(Exception { name: name.to_string(), reason: reason.to_string(), line: n });
    }
    Ok(list)
}

/// The comparison of the run through Strata with the native run.
#[derive(Debug, Default)]
pub struct Verdict {
    /// Pass natively, not through Strata, and not excused.
    pub regressions: Vec<String>,
    /// Excused, yet pass through Strata: the entry is stale.
    pub stale: Vec<Exception>,
    /// Excused, but not a test of the selection (misspelt, or gone from piglit).
    pub unknown: Vec<Exception>,
    /// Excused, but not passing natively either: harmless, worth a look.
    pub unused: Vec<Exception>,
    /// Pass natively, not through Strata, excused.
    pub excused: usize,
}

impl Verdict {
    /// Whether the run through Strata meets the target.
    pub fn ok(&self) -> bool {
        self.regressions.is_empty() && self.stale.is_empty() && self.unknown.is_empty()
    }
}

/// How many of the native run's passes pass in the run through Strata too, and how many there are.
pub fn shared_passes(native: &Run, strata: &Run) -> (usize, usize) {
    let passes = |run: &Run, name: &str| run.get(name).is_some_and(|o| o.result == "pass");
    let native_passes: Vec<&String> = native.keys().filter(|n| passes(native, n)).collect();
    (native_passes.iter().filter(|n| passes(strata, n)).count(), native_passes.len())
}

/// Compares the two runs under the exceptions.
pub fn judge(native: &Run, strata: &Run, exceptions: &[Exception]) -> Verdict {
    let excused: BTreeMap<&str, &Exception> = exceptions.iter().map(|e| (e.name.as_str(), e)).collect();
    let passes = |run: &Run, name: &str| run.get(name).is_some_and(|o| o.result == "pass");
    let mut v = Verdict::default();
    for (name, o) in native {
        if o.result == "pass" && !passes(strata, name) {
            if excused.contains_key(name.as_str()) {
                v.excused += 1;
            } else {
                v.regressions.push(name.clone());
            }
        }
    }
    for e in exceptions {
        if !native.contains_key(&e.name) {
            v.unknown.push(e.clone());
        } else if passes(strata, &e.name) {
            v.stale.push(e.clone());
        } else if !passes(native, &e.name) {
            v.unused.push(e.clone());
        }
    }
    v
}

/// The line of a test's output that says why it did not pass (with the two lines after a
/// probe failure: expected and observed).
pub fn key_line(o: &Outcome) -> String {
    const WORDS: &[&str] =
        &["error", "fail", "unexpected", "expected", "probe", "requires", "not supported", "assert", "abort"];
    let pick = |text: &str| -> Option<String> {
        let lines: Vec<&str> = text.lines().map(str::trim).filter(|l| !l.is_empty()).collect();
        let i = lines.iter().position(|l| {
            let l = l.to_ascii_lowercase();
            WORDS.iter().any(|w| l.contains(w))
        })?;
        let n = if lines[i].starts_with("Probe") { 3 } else { 1 };
        Some(lines[i..(i + n).min(lines.len())].join(" / "))
    };
    let last = |text: &str| text.lines().map(str::trim).rfind(|l| !l.is_empty()).map(str::to_string);
    // glslparsertest echoes the whole shader on stdout, so its stderr comes first.
    pick(&o.err)
        .or_else(|| last(&o.err))
        .or_else(|| pick(&o.out))
        .or_else(|| last(&o.out))
        .unwrap_or_else(|| format!("(no output; exit code {:?})", o.returncode))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exceptions_parse_and_refuse_what_is_in_scope() {
        let ok =
            "# c\n\nspec@a@b | desktop GL context: asks for GL 3.1\nspec@c | extension: GL_OES_texture_view (ES 3.1)\n";
        let list = parse_exceptions(ok).expect("valid");
        assert_eq!(list.len(), 2);
        assert_eq!((list[1].name.as_str(), list[1].line), ("spec@c", 4));
        for bad in [
            "spec@a",
            "spec@a | because",
            "spec@a | slow: takes long",
            "spec@a | extension: GL_OES_standard_derivatives",
            "spec@a | extension: needs derivatives",
            "spec@a | desktop GL context:  ",
            "spec@a | ES 3.x context: asks for ES 3.0",
            "spec@a | ES 1.x context: x\nspec@a | ES 1.x context: x",
        ] {
            assert!(parse_exceptions(bad).is_err(), "accepted {bad:?}");
        }
    }

    fn run(entries: &[(&str, &str)]) -> Run {
        entries.iter().map(|(n, r)| (n.to_string(), Outcome { result: r.to_string(), ..Outcome::default() })).collect()
    }

    #[test]
    fn judge_finds_regressions_and_stale_and_unknown_entries() {
        let native = run(&[("a", "pass"), ("b", "pass"), ("c", "pass"), ("d", "fail"), ("e", "pass")]);
        let strata = run(&[("a", "pass"), ("b", "fail"), ("c", "skip"), ("d", "fail"), ("e", "pass")]);
        let ex = parse_exceptions(
            "c | ES 1.x context: x\nd | ES 1.x context: x\ne | ES 1.x context: x\nz | ES 1.x context: x\n",
        )
        .expect("valid");
        let v = judge(&native, &strata, &ex);
        assert_eq!(v.regressions, ["b"]);
        assert_eq!(v.excused, 1);
        let names = |l: &[Exception]| l.iter().map(|e| e.name.clone()).collect::<Vec<_>>();
        assert_eq!(names(&v.stale), ["e"]);
        assert_eq!(names(&v.unknown), ["z"]);
        assert_eq!(names(&v.unused), ["d"]);
        assert!(!v.ok());
    }

    #[test]
    fn key_line_prefers_the_reason() {
        let o = Outcome {
            out: "Probe color at (0,0)\n  Expected: 0 1 0 1\n  Observed: 1 0 0 1\nPIGLIT: {\"result\": \"fail\" }"
                .into(),
            ..Outcome::default()
        };
        assert_eq!(key_line(&o), "Probe color at (0,0) / Expected: 0 1 0 1 / Observed: 1 0 0 1");
        let o = Outcome { err: "Failed to use program: \n".into(), out: "Test failure on line 3".into(), ..o };
        assert_eq!(key_line(&o), "Failed to use program:");
    }

    #[test]
    fn results_json_is_read() {
        let text = r#"{"tests": {"spec@x": {"result": "fail", "out": "o", "err": "e", "command": "bin -auto",
            "returncode": 1, "subtests": {"s1": "pass", "__type__": "Subtests"}}}}"#;
        let r = parse_run(text).expect("parses");
        let o = &r["spec@x"];
        assert_eq!((o.result.as_str(), o.command.as_str(), o.returncode), ("fail", "bin -auto", Some(1)));
        assert_eq!(o.subtests, [("s1".to_string(), "pass".to_string())]);
    }
}
