//! Preprocessing and parsing: GLSL ES 1.00 only, with `GL_ES` (and in fragment shaders
//! `GL_FRAGMENT_PRECISION_HIGH`) defined as Mesa defines them, `__VERSION__` 100, and the
//! `#extension` directives of GLSL ES 1.00 §3.4 checked against the extensions Strata offers.

use std::sync::LazyLock;

use glsl_lang::ast;
use glsl_lang::lexer::full::fs::PreprocessorExt;
use glsl_lang::parse::IntoParseBuilderExt;
use glsl_lang_pp::exts::{names::ExtNameAtom, ExtensionSpec, Registry};
use glsl_lang_pp::processor::nodes::{Define, DefineObject};
use glsl_lang_pp::processor::ProcessorState;

use super::Stage;

/// The shading-language extensions Strata offers; each is defined as a macro (value 1).
pub(super) const OES_STANDARD_DERIVATIVES: &str = "GL_OES_standard_derivatives";

/// The preprocessor's extension registry: only what Strata offers, so that only those
/// extension macros are defined.
static REGISTRY: LazyLock<Registry> = LazyLock::new(|| {
    let mut r = Registry::new();
    r.add(ExtensionSpec::new(ExtNameAtom::from(OES_STANDARD_DERIVATIVES), vec![]));
    r
});

/// A parsed shader with what its directives asked for.
pub(super) struct Parsed {
    /// The syntax tree.
    pub(super) tu: ast::TranslationUnit,
    /// The text the parser saw (same lines as the source), for mapping spans to lines.
    pub(super) text: String,
    /// Whether `GL_OES_standard_derivatives` is enabled at the end of the shader.
    pub(super) derivatives: bool,
    /// Warnings for the info log.
    pub(super) warnings: Vec<String>,
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
    derivatives: &mut bool,
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
                *derivatives = false;
                Ok(())
            }
            _ => Err(error_at(line, 1, &format!("cannot {behavior} all extensions"))),
        };
    }
    if name == OES_STANDARD_DERIVATIVES {
        *derivatives = behavior != "disable";
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

/// Preprocesses and parses `source`; the error is the info log.
pub(super) fn parse(stage: Stage, source: &str) -> Result<Parsed, String> {
    // `#version 100` is the only version ES 2.0 has. `#extension` directives are handled here
    // (their lines blanked, keeping line numbers) against the extensions Strata offers.
    let mut text = String::with_capacity(source.len());
    let mut derivatives = false;
    let mut warnings = Vec::new();
    for (i, line) in source.lines().enumerate() {
        let directive = line.trim_start().strip_prefix('#').map(str::trim_start);
        if let Some(v) = directive.and_then(|d| d.strip_prefix("version")) {
            let v = v.trim();
            if !(v == "100" || v.starts_with("100 ")) {
                return Err(error_at(
                    i + 1,
                    1,
                    &format!("'#version {v}' : GLSL ES 1.00 (version 100) is the only version supported"),
                ));
            }
            text.push_str("#version 100\n");
        } else if let Some(rest) = directive.and_then(|d| d.strip_prefix("extension")) {
            extension_directive(stage, i + 1, rest, &mut derivatives, &mut warnings)?;
            text.push('\n');
        } else {
            text.push_str(line);
            text.push('\n');
        }
    }
    let gl_es = "1".parse::<DefineObject>().map_err(|e| format!("internal: {e:?}"))?;
    let mut state =
        ProcessorState::builder().registry(&REGISTRY).definition(Define::object("GL_ES".into(), gl_es.clone(), true));
    if stage == Stage::Fragment {
        // Fragment shaders get real f32 precision, so highp is supported (as on Mesa).
        state = state.definition(Define::object("GL_FRAGMENT_PRECISION_HIGH".into(), gl_es, true));
    }
    let state = state.finish();
    let mut pp = glsl_lang_pp::processor::fs::StdProcessor::new();
    let parsed = pp.open_source(&text, ".").with_state(state).builder::<ast::TranslationUnit>().parse();
    match parsed {
        Ok((tu, _, _)) => Ok(Parsed { tu, text, derivatives, warnings }),
        // Mesa's form, `0:LINE(COL): error: …`, from the parser's 0-based position.
        Err(e) => Err(error_at(e.line() as usize + 1, e.col() as usize + 1, &e.inner().to_string())),
    }
}
