//! piglit's GLES 2.0 and GLES 3.0 selections, read from piglit's own metadata rather than from
//! test names:
//! - a shader_runner or glslparsertest test carries its API, GLSL version and API version in
//!   the profile; it is selected where the API is `gles2` (`gles3`), the GLSL version at most
//!   1.00 (3.00) and the API version, where given, at most 2.0 (3.0);
//! - a C test carries only its command, and its API is the piglit utility library its binary
//!   was linked against: it is selected where the binary needs `libpiglitutil_gles2.so` (the
//!   GLES 2 build; the GLES 3 build links `libpiglitutil_gles3.so`, GLES 1 and desktop GL
//!   their own). Such a test may still ask for an ES 3 context at run time; held to ES 2.0,
//!   the native side then skips it.
//!
//! The GLES 3.0 selection is further held to ES 3.0's own tests (`!opengl es 3.0`, the
//! language, transform feedback) and NV_read_depth's ES 3.0 reads; the GLES 3 build's tests of
//! other extensions (texture views, blend_func_extended, base instance, framebuffer fetch, …)
//! are left out.

use std::collections::HashMap;
use std::io::Read;
use std::path::Path;

use object::read::elf::{Dyn as _, ElfFile64, FileHeader, SectionHeader as _};
use object::Endianness;

/// Which of piglit's builds and language versions a selection takes.
pub struct Api {
    /// The library a binary of the build needs (its soname, without the version).
    pub util: &'static [u8],
    /// The API a shader test names.
    pub api: &'static str,
    /// The highest GLSL ES version.
    pub shader_max: f64,
    /// The highest API version.
    pub api_max: f64,
    /// Where given, the name prefixes of the tests taken (the areas).
    pub areas: Option<&'static [&'static str]>,
}

/// piglit's GLES 2.0 build and GLSL ES 1.00.
pub const GLES2: Api =
    Api { util: b"libpiglitutil_gles2.so", api: "gles2", shader_max: 1.0, api_max: 2.0, areas: None };

/// piglit's GLES 3.0 build and GLSL ES 3.00, in the areas of ES 3.0's language and buffer and
/// draw side.
pub const GLES3: Api = Api {
    util: b"libpiglitutil_gles3.so",
    api: "gles3",
    shader_max: 3.0,
    api_max: 3.0,
    areas: Some(&[
        "spec@glsl-es-3.00@",
        // Every test of ES 3.0's own: both sides', the image side's (ETC2, compressed arrays,
        // immutable levels) included.
        "spec@!opengl es 3.0@",
        "spec@ext_transform_feedback@",
        "spec@arb_transform_feedback2@",
        // The depth reads ES 3.0 gives GL_NV_read_depth.
        "spec@nv_read_depth@",
    ]),
};

/// A value as piglit writes it in a profile: a Python literal (`'gles2'`, `1.0`, `['cmd', …]`).
/// The first quoted string in it, or the text itself where it has none.
fn first_string(value: &str) -> &str {
    let Some(start) = value.find(['\'', '"']) else { return value.trim() };
    let quote = value[start..].chars().next().unwrap_or('\'');
    let rest = &value[start + 1..];
    rest.find(quote).map_or(rest, |end| &rest[..end])
}

/// Whether `version` (a profile's number, such as `1.0` or `3.1`) is at most `max`.
fn at_most(version: &str, max: f64) -> bool {
    version.trim().parse::<f64>().is_ok_and(|v| v <= max + 1e-9)
}

/// The shared libraries an ELF binary needs (its `DT_NEEDED` entries).
fn needed(path: &Path) -> Result<Vec<Vec<u8>>, String> {
    let data = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let elf = ElfFile64::<Endianness>::parse(&*data).map_err(|e| format!("{}: {e}", path.display()))?;
    let endian = elf.endian();
    let header = elf.elf_header();
    let sections = header.sections(endian, &*data).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut out = Vec::new();
    for section in sections.iter() {
        let Some((entries, link)) = section.dynamic(endian, &*data).map_err(|e| format!("{}: {e}", path.display()))?
        else {
            continue;
        };
        let strings = sections.strings(endian, &*data, link).map_err(|e| format!("{}: {e}", path.display()))?;
        for d in entries {
            if d.tag32(endian) == Some(object::elf::DT_NEEDED) {
                let offset = d.d_val(endian) as u32;
                out.push(strings.get(offset).map_err(|()| format!("{}: a bad DT_NEEDED", path.display()))?.to_vec());
            }
        }
    }
    Ok(out)
}

/// One selected test: its name, and its `<Test>` element as the profile has it.
pub struct Selected {
    /// The test's name.
    pub name: String,
    /// Its element, verbatim.
    pub xml: String,
}

/// Writes `tests` as one gzipped piglit profile at `path` (an absolute path: piglit then reads it
/// as an XML profile; it forces a test list only onto a single profile).
pub fn write_profile(path: &Path, tests: &[Selected]) -> Result<(), String> {
    use std::io::Write;
    let file = std::fs::File::create(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut gz = flate2::write::GzEncoder::new(file, flate2::Compression::fast());
    let mut text = format!(
        "<?xml version='1.0' encoding='utf-8'?>\n<PiglitTestList count=\"{}\" name=\"strata-gles\">",
        tests.len()
    );
    for t in tests {
        text.push_str(&t.xml);
    }
    text.push_str("</PiglitTestList>\n");
    gz.write_all(text.as_bytes()).and_then(|()| gz.finish().map(drop)).map_err(|e| format!("{}: {e}", path.display()))
}

/// The tests of the gzipped profiles `profiles` (in `tests_dir`) that `api` takes, in profile
/// order; C tests' binaries are looked up in `bin_dir`.
pub fn select(tests_dir: &Path, bin_dir: &Path, profiles: &[&str], api: &Api) -> Result<Vec<Selected>, String> {
    let mut chosen = Vec::new();
    let mut gles2_binary: HashMap<String, bool> = HashMap::new();
    for profile in profiles {
        let path = tests_dir.join(profile);
        let file = std::fs::File::open(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut xml = String::new();
        flate2::read::GzDecoder::new(file).read_to_string(&mut xml).map_err(|e| format!("{}: {e}", path.display()))?;
        let doc = roxmltree::Document::parse(&xml).map_err(|e| format!("{}: {e}", path.display()))?;
        for test in doc.root_element().children().filter(|n| n.has_tag_name("Test")) {
            let Some(name) = test.attribute("name") else { continue };
            if api.areas.is_some_and(|areas| !areas.iter().any(|a| name.starts_with(a))) {
                continue;
            }
            let options: HashMap<&str, &str> = test
                .children()
                .filter(|n| n.has_tag_name("option"))
                .filter_map(|o| Some((o.attribute("name")?, o.attribute("value")?)))
                .collect();
            let selected = match options.get("api") {
                Some(named) => {
                    first_string(named) == api.api
                        && options.get("shader_version").is_none_or(|v| at_most(v, api.shader_max))
                        && options.get("api_version").is_none_or(|v| at_most(v, api.api_max))
                }
                None => {
                    let Some(command) = options.get("command") else { continue };
                    let program = first_string(command).to_string();
                    match gles2_binary.get(&program) {
                        Some(&b) => b,
                        None => {
                            let binary = bin_dir.join(&program);
                            // A command that is no binary of piglit's (a script) is no GLES test.
                            let b = binary.is_file() && needed(&binary)?.iter().any(|n| n.starts_with(api.util));
                            gles2_binary.insert(program, b);
                            b
                        }
                    }
                }
            };
            if selected {
                chosen.push(Selected { name: name.to_string(), xml: xml[test.range()].to_string() });
            }
        }
    }
    Ok(chosen)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profile_values_read_as_python_writes_them() {
        assert_eq!(first_string("'gles2'"), "gles2");
        assert_eq!(first_string("['shader_runner_gles2', 'tests/x.shader_test']"), "shader_runner_gles2");
        assert_eq!(first_string("[\"it's\", 'b']"), "it's");
        assert_eq!(first_string("1.0"), "1.0");
        assert!(at_most("1.0", 1.0) && !at_most("1.10", 1.0) && at_most("2.0", 2.0) && !at_most("3.0", 2.0));
    }
}
