//! The generated GLSL 450 of a shader's own code, one line per global declaration, function
//! head and top-level statement, remembering each line's source line; and naga's parse and
//! validation of a whole stage, whose errors are reported at the shader's line in Mesa's form.

use glsl_lang::ast::{self, ExternalDeclarationData};
use glsl_lang::transpiler::glsl::{
    show_external_declaration, show_function_prototype, show_statement, FormattingSettings, FormattingState,
};
use tracing::debug;

use crate::glsl::preprocess::error_at;
use crate::glsl::types::{Shader, Stage};

/// A shader's generated code: the text and the source line of each of its lines.
pub(super) struct Body {
    /// GLSL 450 text.
    pub(super) text: String,
    /// For each line of `text`, the 1-based source line it came from.
    pub(super) lines: Vec<u32>,
}

/// Where a shader's generated code sits in a stage's whole source.
pub(super) struct Placed<'a> {
    /// The 0-based line of the stage source at which the code starts.
    pub(super) first_line: usize,
    /// The code.
    pub(super) body: &'a Body,
}

/// The source line of a node, if the parser recorded its span.
fn node_line(s: &Shader, span: Option<ast::NodeSpan>) -> Option<u32> {
    span.map(|sp| s.line_of(u32::from(sp.start().offset) as usize))
}

/// Appends what `show` writes, recording `line` for every line it takes.
fn emit(
    out: &mut Body,
    line: u32,
    show: impl FnOnce(&mut String, &mut FormattingState<'_>) -> std::fmt::Result,
) -> Result<(), String> {
    // Spaces around binary operators: `a - -1` written `a--1` would read as a decrement; a
    // block of one statement keeps its braces, which scope what it declares.
    let settings = FormattingSettings {
        spaces_around_binary_ops: true,
        collapse_single_item_compound_statements: false,
        ..FormattingSettings::minifying()
    };
    let mut state = FormattingState::from(&settings);
    let start = out.text.len();
    show(&mut out.text, &mut state).map_err(|e| format!("internal: transpiling failed: {e}"))?;
    out.text.push('\n');
    let added = out.text[start..].matches('\n').count();
    out.lines.extend(std::iter::repeat_n(line, added));
    Ok(())
}

/// The generated code of shader `s` (its rewritten syntax tree).
pub(super) fn transpile(s: &Shader) -> Result<Body, String> {
    let mut out = Body { text: String::new(), lines: Vec::new() };
    for decl in &s.body.0 {
        let line = node_line(s, decl.span).unwrap_or(1);
        match &decl.content {
            ExternalDeclarationData::FunctionDefinition(f) => {
                emit(&mut out, line, |w, st| {
                    show_function_prototype(w, &f.prototype, st)?;
                    w.push('{');
                    Ok(())
                })?;
                for statement in &f.statement.statement_list {
                    let at = node_line(s, statement.span).unwrap_or(line);
                    emit(&mut out, at, |w, st| show_statement(w, statement, st))?;
                }
                emit(&mut out, line, |w, _| {
                    w.push('}');
                    Ok(())
                })?;
            }
            _ => emit(&mut out, line, |w, st| show_external_declaration(w, decl, st))?,
        }
    }
    Ok(out)
}

/// The shader line of byte `offset` of a stage source, if it lies in the shader's own code.
fn source_line(src: &str, placed: &Placed<'_>, offset: usize) -> Option<u32> {
    let line = src.get(..offset)?.matches('\n').count();
    placed.body.lines.get(line.checked_sub(placed.first_line)?).copied()
}

/// One info log line for an error naga found at `offset` of a stage source.
fn log_line(src: &str, placed: &Placed<'_>, offset: Option<usize>, msg: &str) -> String {
    // The shader's `main` is `strata_main` in the generated code.
    let msg = &msg.replace("'strata_main'", "'main'");
    match offset.and_then(|o| source_line(src, placed, o)) {
        Some(line) => error_at(line as usize, 1, msg),
        None => format!("error: {msg}"),
    }
}

/// Parses and validates a stage's whole source with naga; errors name the shader's line.
pub(super) fn naga_module(stage: Stage, src: &str, placed: &Placed<'_>) -> Result<naga::Module, String> {
    let naga_stage = match stage {
        Stage::Vertex => naga::ShaderStage::Vertex,
        Stage::Fragment => naga::ShaderStage::Fragment,
    };
    let mut fe = naga::front::glsl::Frontend::default();
    let module = fe.parse(&naga::front::glsl::Options::from(naga_stage), src).map_err(|e| {
        debug!(target: "strata_gles::glsl", "naga refused:\n{}", e.emit_to_string(src));
        let lines: Vec<String> = e
            .errors
            .iter()
            .map(|err| log_line(src, placed, err.meta.to_range().map(|r| r.start), &err.kind.to_string()))
            .collect();
        lines.join("\n")
    })?;
    // GLSL ES 3.00's packHalf2x16 and unpackHalf2x16 need f16 conversions, which wgpu's Vulkan
    // back end always has (`DownlevelFlags::SHADER_F16_IN_F32`).
    let capabilities =
        naga::valid::Capabilities::DUAL_SOURCE_BLENDING | naga::valid::Capabilities::SHADER_FLOAT16_IN_FLOAT32;
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), capabilities).validate(&module).map_err(|e| {
        debug!(target: "strata_gles::glsl", "naga refused:\n{}", e.emit_to_string(src));
        // The innermost span: the expression or statement, not the enclosing function.
        let offset = e.spans().filter_map(|(span, _)| span.to_range()).min_by_key(|r| r.len()).map(|r| r.start);
        let mut msg = e.as_inner().to_string();
        let mut source = std::error::Error::source(e.as_inner());
        while let Some(inner) = source {
            msg.push_str(": ");
            msg.push_str(&inner.to_string());
            source = inner.source();
        }
        log_line(src, placed, offset, &msg)
    })?;
    Ok(module)
}
