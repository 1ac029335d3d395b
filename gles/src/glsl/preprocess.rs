//! Preprocessing and parsing: GLSL ES 1.00 and 3.00 (`#version 300 es`), with `GL_ES` (and in
//! fragment shaders `GL_FRAGMENT_PRECISION_HIGH`) defined as Mesa defines them, `__VERSION__`
//! the shader's, and the `#extension` directives of GLSL ES 1.00 §3.4 checked against the
//! extensions Strata offers. As Mesa held to ES 2.0 does, either version compiles in either
//! context.

use std::sync::LazyLock;

use glsl_lang::ast;
use glsl_lang::lexer::full::fs::PreprocessorExt;
use glsl_lang_pp::exts::{names::ExtNameAtom, ExtensionSpec, Registry};
use glsl_lang_pp::processor::nodes::{Define, DefineObject};
use glsl_lang_pp::processor::ProcessorState;

use crate::glsl::types::Stage;

/// The shading-language extensions Strata offers; each is defined as a macro (value 1).
pub(super) const OES_STANDARD_DERIVATIVES: &str = "GL_OES_standard_derivatives";
/// `gl_FragDepthEXT` in fragment shaders.
pub(super) const EXT_FRAG_DEPTH: &str = "GL_EXT_frag_depth";
/// `gl_InstanceIDEXT` in vertex shaders.
pub(super) const EXT_DRAW_INSTANCED: &str = "GL_EXT_draw_instanced";
/// `gl_FragData[i]` for every draw buffer. As on Mesa, the array is there whether or not a
/// shader enables the extension; the directive is accepted and the macro defined.
pub(super) const EXT_DRAW_BUFFERS: &str = "GL_EXT_draw_buffers";
/// `gl_SecondaryFragColorEXT` and `gl_SecondaryFragDataEXT`, the second colour dual-source
/// blending reads, in fragment shaders.
pub(super) const EXT_BLEND_FUNC_EXTENDED: &str = "GL_EXT_blend_func_extended";
/// `samplerExternalOES`, sampled with `texture2D` and `texture2DProj`.
pub(super) const OES_EGL_IMAGE_EXTERNAL: &str = "GL_OES_EGL_image_external";

/// `sampler3D` lookups (`texture3D` and its forms) in shaders that enable it. As on Mesa, the
/// macro is defined and the type known whether or not a shader enables it.
pub(super) const OES_TEXTURE_3D: &str = "GL_OES_texture_3D";

/// Program pipelines. GLSL ES 1.00 gains nothing from it: the directive is accepted and the
/// macro defined.
pub(super) const EXT_SEPARATE_SHADER_OBJECTS: &str = "GL_EXT_separate_shader_objects";

/// How the parser is shown `samplerExternalOES`, which it does not know: as a sampler type
/// GLSL ES 1.00 reserves (so no ES 1.00 shader names it itself), padded to the same length so
/// that every column stays where it was.
const EXTERNAL_SPELLING: &str = "sampler2DRect     ";

/// Which of the offered extensions a shader's directives leave enabled.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Enabled {
    /// `GL_OES_standard_derivatives`.
    pub(super) derivatives: bool,
    /// `GL_EXT_frag_depth`.
    pub(super) frag_depth: bool,
    /// `GL_EXT_draw_instanced`.
    pub(super) draw_instanced: bool,
    /// `GL_EXT_blend_func_extended`.
    pub(super) blend_func_extended: bool,
    /// `GL_OES_EGL_image_external`.
    pub(super) image_external: bool,
    /// `GL_OES_texture_3D`.
    pub(super) texture_3d: bool,
}

/// The preprocessor's extension registry: only what Strata offers, so that only those
/// extension macros are defined.
static REGISTRY: LazyLock<Registry> = LazyLock::new(|| {
    let mut r = Registry::new();
    r.add(ExtensionSpec::new(ExtNameAtom::from(OES_STANDARD_DERIVATIVES), vec![]));
    r.add(ExtensionSpec::new(ExtNameAtom::from(EXT_FRAG_DEPTH), vec![]));
    r.add(ExtensionSpec::new(ExtNameAtom::from(EXT_DRAW_INSTANCED), vec![]));
    r.add(ExtensionSpec::new(ExtNameAtom::from(EXT_DRAW_BUFFERS), vec![]));
    r.add(ExtensionSpec::new(ExtNameAtom::from(EXT_BLEND_FUNC_EXTENDED), vec![]));
    r.add(ExtensionSpec::new(ExtNameAtom::from(OES_EGL_IMAGE_EXTERNAL), vec![]));
    r.add(ExtensionSpec::new(ExtNameAtom::from(EXT_SEPARATE_SHADER_OBJECTS), vec![]));
    r.add(ExtensionSpec::new(ExtNameAtom::from(OES_TEXTURE_3D), vec![]));
    r
});

/// A parsed shader with what its directives asked for.
pub(super) struct Parsed {
    /// The syntax tree.
    pub(super) tu: ast::TranslationUnit,
    /// The text the parser saw (same lines as the source), for mapping spans to lines.
    pub(super) text: String,
    /// The offered extensions enabled at the end of the shader.
    pub(super) enabled: Enabled,
    /// Warnings for the info log.
    pub(super) warnings: Vec<String>,
    /// The language version: 100 or 300.
    pub(super) version: u16,
}

/// Identifiers GLSL ES 3.00 allows that the parser (whose grammar is GLSL 4.x's) takes for
/// keywords, each with the name it is parsed under: as long, and with two underscores in a row,
/// which GLSL ES reserves, so that it names nothing of the shader's.
const KEYWORDS_NOT_IN_ES3: [(&str, &str); 3] = [("buffer", "buff__"), ("shared", "shar__"), ("precise", "preci__")];

/// The signed integer an unsuffixed integer literal `word` (decimal, octal or hexadecimal)
/// names where its bit pattern needs all 32 bits (GLSL ES 3.00 §4.1.3: `0xFFFFFFFF` is -1),
/// spelled so that the parser (which takes only values up to 2³¹ − 1) reads it.
fn wrapped_int(word: &str) -> Option<String> {
    let (digits, radix) = match word.strip_prefix("0x").or_else(|| word.strip_prefix("0X")) {
        Some(hex) => (hex, 16),
        None if word.len() > 1 && word.starts_with('0') => (&word[1..], 8),
        None => (word, 10),
    };
    let v = u32::from_str_radix(digits, radix).ok().filter(|&v| v > i32::MAX as u32)?;
    Some(match v as i32 {
        i32::MIN => "(-2147483647 - 1)".to_string(),
        n => format!("({n})"),
    })
}

/// `text` with each of [`KEYWORDS_NOT_IN_ES3`] renamed where it stands as a word (in GLSL ES
/// 3.00, `es3`), and each integer literal of 32 significant bits written as its signed value.
fn rewrite_words(text: &str, es3: bool) -> String {
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut out = String::with_capacity(text.len());
    let mut word = String::new();
    // The characters around a word: a literal beside a '.' is part of a float.
    let mut before = ' ';
    let flush = |word: &mut String, out: &mut String, before: char, after: char| {
        let literal = word.starts_with(|c: char| c.is_ascii_digit()) && before != '.' && after != '.';
        if let Some(n) = wrapped_int(word).filter(|_| literal) {
            out.push_str(&n);
        } else if es3 {
            let renamed = KEYWORDS_NOT_IN_ES3.iter().find(|(k, _)| k == word).map_or(word.as_str(), |(_, r)| r);
            out.push_str(renamed);
        } else {
            out.push_str(word);
        }
        word.clear();
    };
    for c in text.chars() {
        if ident(c) {
            word.push(c);
        } else {
            flush(&mut word, &mut out, before, c);
            out.push(c);
            before = c;
        }
    }
    flush(&mut word, &mut out, before, ' ');
    out
}

/// `(line, column)`, both 1-based, of byte `offset` in `text`.
pub(super) fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    (line, col)
}

/// A Mesa-style info log line: `0:LINE(COL): error: MESSAGE`.
pub(super) fn error_at(line: usize, col: usize, msg: &str) -> String {
    format!("0:{line}({col}): error: {msg}")
}

fn stage_name(stage: Stage) -> &'static str {
    match stage {
        Stage::Vertex => "vertex",
        Stage::Fragment => "fragment",
    }
}

/// Handles one `#extension` directive (its text after `#extension`) found on `line`.
fn extension_directive(
    stage: Stage,
    line: usize,
    rest: &str,
    enabled: &mut Enabled,
    warnings: &mut Vec<String>,
) -> Result<(), String> {
    let (name, behavior) = match rest.split_once(':') {
        Some((n, b)) => (n.trim(), b.trim()),
        None => return Err(error_at(line, 1, "syntax error in #extension directive")),
    };
    if !matches!(behavior, "require" | "enable" | "warn" | "disable") {
        return Err(error_at(line, 1, &format!("unknown extension behavior `{behavior}'")));
    }
    if name == "all" {
        // §3.4: `all` may only be used with `warn` and `disable`.
        return match behavior {
            "warn" => Ok(()),
            "disable" => {
                *enabled = Enabled::default();
                Ok(())
            }
            _ => Err(error_at(line, 1, &format!("cannot {behavior} all extensions"))),
        };
    }
    if name == OES_STANDARD_DERIVATIVES {
        enabled.derivatives = behavior != "disable";
        return Ok(());
    }
    if name == EXT_FRAG_DEPTH {
        enabled.frag_depth = behavior != "disable";
        return Ok(());
    }
    if name == EXT_DRAW_INSTANCED {
        enabled.draw_instanced = behavior != "disable";
        return Ok(());
    }
    if name == EXT_DRAW_BUFFERS || name == EXT_SEPARATE_SHADER_OBJECTS {
        return Ok(());
    }
    if name == EXT_BLEND_FUNC_EXTENDED {
        enabled.blend_func_extended = behavior != "disable";
        return Ok(());
    }
    if name == OES_EGL_IMAGE_EXTERNAL {
        enabled.image_external = behavior != "disable";
        return Ok(());
    }
    if name == OES_TEXTURE_3D {
        enabled.texture_3d = behavior != "disable";
        return Ok(());
    }
    let msg = format!("extension `{name}' unsupported in {} shader", stage_name(stage));
    if behavior == "require" {
        Err(error_at(line, 1, &msg))
    } else {
        warnings.push(format!("0:{line}(1): warning: {msg}"));
        Ok(())
    }
}

/// The error for a comment or quoted string that `text` leaves open at its end, if any.
///
/// glsl-lang-pp 0.8.1 never returns from a `##` whose directive reaches the end of the input
/// without a new-line token, and a block comment or a `"` string (GLSL ES has none; the
/// preprocessor lexes one for `#include`) swallows every new-line up to the end. So such
/// sources are refused before preprocessing; `parse` also ends the text with an empty line,
/// against a `\` continuation on the last line.
fn unterminated(text: &str) -> Option<String> {
    #[derive(PartialEq)]
    enum In {
        Code,
        LineComment,
        BlockComment,
        Quote,
    }
    let mut state = In::Code;
    let mut start = 0;
    let mut chars = text.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        let next = chars.peek().map(|&(_, n)| n);
        match state {
            In::Code => match (c, next) {
                ('/', Some('/')) => state = In::LineComment,
                ('/', Some('*')) => {
                    chars.next();
                    (state, start) = (In::BlockComment, i);
                }
                ('"', _) => (state, start) = (In::Quote, i),
                _ => {}
            },
            In::LineComment => match (c, next) {
                // A continuation carries the comment onto the next line.
                ('\\', Some('\n')) => {
                    chars.next();
                }
                ('\n', _) => state = In::Code,
                _ => {}
            },
            In::BlockComment => {
                if (c, next) == ('*', Some('/')) {
                    chars.next();
                    state = In::Code;
                }
            }
            In::Quote => {
                if c == '"' {
                    state = In::Code;
                }
            }
        }
    }
    let (line, col) = line_col(text, start);
    match state {
        In::BlockComment => Some(error_at(line, col, "unterminated comment")),
        In::Quote => Some(error_at(line, col, "syntax error, unexpected '\"'")),
        In::Code | In::LineComment => None,
    }
}

/// The preprocessor's state at the start of a `stage` shader: `GL_ES`, and in fragment shaders
/// `GL_FRAGMENT_PRECISION_HIGH`, defined as Mesa defines them.
fn initial_state(stage: Stage) -> Result<ProcessorState, String> {
    let gl_es = "1".parse::<DefineObject>().map_err(|e| format!("internal: {e:?}"))?;
    let mut state =
        ProcessorState::builder().registry(&REGISTRY).definition(Define::object("GL_ES".into(), gl_es.clone(), true));
    if stage == Stage::Fragment {
        // Fragment shaders get real f32 precision, so highp is supported (as on Mesa).
        state = state.definition(Define::object("GL_FRAGMENT_PRECISION_HIGH".into(), gl_es, true));
    }
    Ok(state.finish())
}

/// The 0-based lines of `text` whose `#extension` directive lies in a section conditional
/// compilation skips: the preprocessor evaluates each `#if` with its macros as defined at that
/// point, and a skipped section's directives are ignored (GLSL ES 1.00 §3.4, as in C).
fn skipped_extension_lines(stage: Stage, text: &str) -> Result<std::collections::HashSet<usize>, String> {
    use glsl_lang_pp::processor::event::{DirectiveKind, ErrorKind, Event, ProcessingErrorKind};
    let mut skipped = std::collections::HashSet::new();
    let mut pp = glsl_lang_pp::processor::fs::StdProcessor::new();
    let events = pp.parse_source(text, std::path::Path::new(".")).process(initial_state(stage)?);
    for event in events.flatten() {
        match event {
            Event::Directive { directive, masked: true } if matches!(directive.kind(), DirectiveKind::Extension(_)) => {
                skipped.insert(line_col(text, directive.text_range().start().offset.into()).0 - 1);
            }
            // A malformed `#extension` in a skipped section is ignored too.
            Event::Error { error, masked: true }
                if matches!(error.inner(), ErrorKind::Processing(ProcessingErrorKind::DirectiveExtension(_))) =>
            {
                skipped.insert(error.line() as usize);
            }
            _ => {}
        }
    }
    Ok(skipped)
}

/// Preprocesses and parses `source`; the error is the info log.
pub(super) fn parse(stage: Stage, source: &str) -> Result<Parsed, String> {
    // `#version 100` and `#version 300 es`. `#extension` directives outside skipped sections
    // are handled here (their lines then blanked, keeping line numbers) against the extensions
    // Strata offers.
    let mut text = String::with_capacity(source.len());
    let mut extensions = Vec::new();
    let mut version = 100;
    for (i, line) in source.lines().enumerate() {
        let directive = line.trim_start().strip_prefix('#').map(str::trim_start);
        if let Some(v) = directive.and_then(|d| d.strip_prefix("version")) {
            let words: Vec<&str> = v.split("//").next().unwrap_or("").split_whitespace().collect();
            version = match words.as_slice() {
                ["100"] => 100,
                ["300", "es"] => 300,
                _ => {
                    let v = v.trim();
                    return Err(error_at(
                        i + 1,
                        1,
                        &format!(
                            "'#version {v}' : only GLSL ES 1.00 (version 100) and 3.00 (version 300 es) are supported"
                        ),
                    ));
                }
            };
            text.push_str(if version == 300 { "#version 300 es\n" } else { "#version 100\n" });
            continue;
        }
        if let Some(rest) = directive.and_then(|d| d.strip_prefix("extension")) {
            extensions.push((i, rest, text.len()));
        }
        text.push_str(line);
        text.push('\n');
    }
    if let Some(e) = unterminated(&text) {
        return Err(e);
    }
    // Ends a `\` continuation on the last line before the input does (see `unterminated`).
    text.push('\n');
    let (mut enabled, mut warnings) = (Enabled::default(), Vec::new());
    if !extensions.is_empty() {
        let skipped = skipped_extension_lines(stage, &text)?;
        for &(i, rest, _) in &extensions {
            if !skipped.contains(&i) {
                extension_directive(stage, i + 1, rest, &mut enabled, &mut warnings)?;
            }
        }
        // The parse sees blank lines in their place: spaces keep every offset.
        let mut bytes = text.into_bytes();
        for &(_, _, start) in &extensions {
            let end = bytes[start..].iter().position(|&b| b == b'\n').map_or(bytes.len(), |n| start + n);
            bytes[start..end].fill(b' ');
        }
        text = String::from_utf8(bytes).map_err(|e| format!("internal: {e}"))?;
    }
    if enabled.image_external {
        text = spell_external(&text);
    }
    text = rewrite_words(&text, version == 300);
    let state = initial_state(stage)?;
    let mut pp = glsl_lang_pp::processor::fs::StdProcessor::new();
    let parsed = crate::glsl::fields::parse(pp.open_source(&text, ".").with_state(state));
    match parsed {
        Ok(tu) => Ok(Parsed { tu, text, enabled, warnings, version }),
        // Mesa's form, `0:LINE(COL): error: …`, from the parser's 0-based position.
        Err(e) => Err(error_at(e.line() as usize + 1, e.col() as usize + 1, &e.inner().to_string())),
    }
}

/// `text` with every `samplerExternalOES` identifier spelled as [`EXTERNAL_SPELLING`].
fn spell_external(text: &str) -> String {
    const NAME: &str = "samplerExternalOES";
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find(NAME) {
        let before = rest[..i].chars().next_back();
        let after = rest[i + NAME.len()..].chars().next();
        out.push_str(&rest[..i]);
        if before.is_some_and(ident) || after.is_some_and(ident) {
            out.push_str(NAME);
        } else {
            out.push_str(EXTERNAL_SPELLING);
        }
        rest = &rest[i + NAME.len()..];
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn external_samplers_keep_their_columns() {
        let text = "uniform samplerExternalOES s; xsamplerExternalOES samplerExternalOES_x\n";
        let spelled = spell_external(text);
        assert_eq!(spelled.len(), text.len());
        assert_eq!(spelled, "uniform sampler2DRect      s; xsamplerExternalOES samplerExternalOES_x\n");
    }

    /// A `##` whose directive runs to the end of the source (through an open string, an open
    /// comment or a continuation) once made the preprocessor loop forever: now each returns,
    /// the open string or comment as an error.
    #[test]
    fn concat_running_to_the_end_of_the_source_returns() {
        for source in
            ["#pragma ##\"\n", "#define A(x) x##\"", "#define A x ## /*\n", "#define A x##\\", "#define A x##\\\n"]
        {
            let (tx, rx) = std::sync::mpsc::channel();
            std::thread::spawn(move || {
                let _ = tx.send(parse(Stage::Fragment, source).map(|_| ()));
            });
            match rx.recv_timeout(std::time::Duration::from_secs(20)) {
                Ok(r) => assert!(r.is_err() || !source.contains(['"', '*']), "{source:?} parsed"),
                Err(_) => panic!("{source:?}: the preprocessor did not return"),
            }
        }
    }

    #[test]
    fn closed_comments_and_strings_still_parse() {
        let source =
            "/* a \"quote\" */\n// \"\n#define A(x) x ## 1 /* c */\nvoid main() { gl_FragColor = vec4(A(0)); }";
        parse(Stage::Fragment, source).expect("parses");
    }
}
