//! GLSL ES 3.00 rules the parser and the translation do not enforce, checked on the parsed
//! shader: the sequence operator is no constant expression (§4.3.3: array sizes, `const` and
//! global initializers), built-in functions cannot be redefined or overloaded (§6.1), an
//! instance-named uniform block's members are reached only through the instance name (§4.3.7),
//! `#pragma STDGL invariant(all)` is an error in a fragment shader (§4.6.1), and an undefined
//! identifier in `#if` or `#elif` is an error (§3.4).

use std::collections::HashSet;

use glsl_lang::ast::{self, ExprData};
use glsl_lang::visitor::{Host, Visit, Visitor};

use crate::glsl::checks::is_const;
use crate::glsl::preprocess::{self, error_at};
use crate::glsl::types::Stage;

/// GLSL ES 3.00's built-in functions (chapter 8), which a shader may not redefine or overload.
const BUILTINS: &[&str] = &[
    "radians",
    "degrees",
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "sinh",
    "cosh",
    "tanh",
    "asinh",
    "acosh",
    "atanh",
    "pow",
    "exp",
    "log",
    "exp2",
    "log2",
    "sqrt",
    "inversesqrt",
    "abs",
    "sign",
    "floor",
    "trunc",
    "round",
    "roundEven",
    "ceil",
    "fract",
    "mod",
    "modf",
    "min",
    "max",
    "clamp",
    "mix",
    "step",
    "smoothstep",
    "isnan",
    "isinf",
    "floatBitsToInt",
    "floatBitsToUint",
    "intBitsToFloat",
    "uintBitsToFloat",
    "packSnorm2x16",
    "unpackSnorm2x16",
    "packUnorm2x16",
    "unpackUnorm2x16",
    "packHalf2x16",
    "unpackHalf2x16",
    "length",
    "distance",
    "dot",
    "cross",
    "normalize",
    "faceforward",
    "reflect",
    "refract",
    "matrixCompMult",
    "outerProduct",
    "transpose",
    "determinant",
    "inverse",
    "lessThan",
    "lessThanEqual",
    "greaterThan",
    "greaterThanEqual",
    "equal",
    "notEqual",
    "any",
    "all",
    "not",
    "textureSize",
    "texture",
    "textureProj",
    "textureLod",
    "textureOffset",
    "texelFetch",
    "texelFetchOffset",
    "textureProjOffset",
    "textureLodOffset",
    "textureProjLod",
    "textureProjLodOffset",
    "textureGrad",
    "textureGradOffset",
    "textureProjGrad",
    "textureProjGradOffset",
    "dFdx",
    "dFdy",
    "fwidth",
];

/// The macros every GLSL ES 3.00 shader has: the language's and the extensions'.
const PREDEFINED: &[&str] = &[
    "GL_ES",
    "__VERSION__",
    "__LINE__",
    "__FILE__",
    "GL_FRAGMENT_PRECISION_HIGH",
    preprocess::OES_STANDARD_DERIVATIVES,
    preprocess::EXT_FRAG_DEPTH,
    preprocess::EXT_DRAW_INSTANCED,
    preprocess::EXT_DRAW_BUFFERS,
    preprocess::EXT_BLEND_FUNC_EXTENDED,
    preprocess::OES_EGL_IMAGE_EXTERNAL,
    preprocess::OES_TEXTURE_3D,
    preprocess::EXT_SEPARATE_SHADER_OBJECTS,
];

/// Whether `e` holds the sequence operator anywhere.
fn has_sequence(e: &ast::Expr) -> bool {
    struct Find(bool);
    impl Visitor for Find {
        fn visit_expr(&mut self, e: &ast::Expr) -> Visit {
            if matches!(e.content, ExprData::Comma(..)) {
                self.0 = true;
            }
            Visit::Children
        }
    }
    let mut f = Find(false);
    e.visit(&mut f);
    f.0
}

/// The expressions of an initializer.
fn initializer_has_sequence(i: &ast::Initializer) -> bool {
    match &i.content {
        ast::InitializerData::Simple(e) => has_sequence(e),
        ast::InitializerData::List(l) => l.iter().any(initializer_has_sequence),
    }
}

/// What the walk finds: the first error's place and message, declared names, names used.
#[derive(Default)]
struct Walk {
    error: Option<(Option<ast::NodeSpan>, String)>,
    declared: HashSet<String>,
    used: Vec<(String, Option<ast::NodeSpan>)>,
}

impl Walk {
    fn fail(&mut self, span: Option<ast::NodeSpan>, msg: &str) {
        if self.error.is_none() {
            self.error = Some((span, msg.to_string()));
        }
    }
}

const SEQUENCE: &str = "the sequence operator is not allowed in a constant expression";

impl Visitor for Walk {
    fn visit_array_specifier_dimension(&mut self, d: &ast::ArraySpecifierDimension) -> Visit {
        if let ast::ArraySpecifierDimensionData::ExplicitlySized(e) = &d.content {
            if has_sequence(e) {
                self.fail(e.span, SEQUENCE);
            }
        }
        Visit::Children
    }

    fn visit_init_declarator_list(&mut self, list: &ast::InitDeclaratorList) -> Visit {
        let head = &list.head;
        if let Some(n) = &head.name {
            self.declared.insert(n.0.to_string());
        }
        for t in &list.tail {
            self.declared.insert(t.ident.ident.0.to_string());
        }
        if is_const(head.ty.qualifier.as_ref()) {
            let inits = head.initializer.iter().chain(list.tail.iter().filter_map(|t| t.initializer.as_ref()));
            for i in inits {
                if initializer_has_sequence(i) {
                    self.fail(i.span, SEQUENCE);
                }
            }
        }
        Visit::Children
    }

    fn visit_function_prototype(&mut self, p: &ast::FunctionPrototype) -> Visit {
        if BUILTINS.contains(&p.name.0.as_str()) {
            self.fail(p.span, &format!("a shader cannot redefine or overload the built-in function `{}'", p.name.0));
        }
        for param in &p.parameters {
            if let ast::FunctionParameterDeclarationData::Named(_, d) = &param.content {
                self.declared.insert(d.ident.ident.0.to_string());
            }
        }
        Visit::Children
    }

    fn visit_expr(&mut self, e: &ast::Expr) -> Visit {
        if let ExprData::Variable(id) = &e.content {
            self.used.push((id.0.to_string(), e.span));
        }
        Visit::Children
    }
}

/// Checks the rules above on a GLSL ES 3.00 shader of `stage`: `text` its source, `tu` its
/// parse. The error names the line, Mesa-style.
pub(super) fn check(stage: Stage, text: &str, tu: &ast::TranslationUnit) -> Result<(), String> {
    let at = |span: Option<ast::NodeSpan>, msg: &str| {
        let (line, col) = span.map_or((1, 1), |s| preprocess::line_col(text, usize::from(s.range().start())));
        error_at(line, col, msg)
    };
    directives(stage, text)?;
    // Global initializers are constant expressions in GLSL ES 3.00.
    for decl in &tu.0 {
        if let ast::ExternalDeclarationData::Declaration(d) = &decl.content {
            if let ast::DeclarationData::InitDeclaratorList(list) = &d.content {
                let inits = list.head.initializer.iter().chain(list.tail.iter().filter_map(|t| t.initializer.as_ref()));
                for i in inits {
                    if initializer_has_sequence(i) {
                        return Err(at(i.span, SEQUENCE));
                    }
                }
            }
        }
    }
    let mut walk = Walk::default();
    tu.visit(&mut walk);
    if let Some((span, msg)) = walk.error {
        return Err(at(span, &msg));
    }
    // An instance-named block's members are no names of their own (a block without an
    // instance name declares its members' names, though, and a block its name).
    let (mut members, mut bare, mut blocks) = (HashSet::new(), HashSet::new(), HashSet::new());
    for decl in &tu.0 {
        if let ast::ExternalDeclarationData::Declaration(d) = &decl.content {
            if let ast::DeclarationData::Block(b) = &d.content {
                // A shader declares a block of a name once.
                if !blocks.insert(b.name.0.to_string()) {
                    return Err(at(d.span, &format!("`{}' redeclared", b.name.0)));
                }
                let names = b.fields.iter().flat_map(|f| f.identifiers.iter().map(|i| i.ident.0.to_string()));
                match b.identifier {
                    Some(_) => members.extend(names),
                    None => {
                        for name in names {
                            // Two blocks without instance names cannot both declare a name.
                            if !bare.insert(name.clone()) {
                                return Err(at(d.span, &format!("`{name}' redeclared")));
                            }
                        }
                    }
                }
            }
        }
    }
    for (name, span) in &walk.used {
        if members.contains(name) && !walk.declared.contains(name) && !bare.contains(name) {
            return Err(at(*span, &format!("`{name}' undeclared")));
        }
    }
    Ok(())
}

/// The directive rules: `#pragma STDGL invariant(all)` only outside fragment shaders, and no
/// undefined identifier in `#if` or `#elif` but after `defined`. Macros are followed through
/// `#define` and `#undef` in source order.
fn directives(stage: Stage, text: &str) -> Result<(), String> {
    let mut defined: HashSet<String> = PREDEFINED.iter().map(|s| s.to_string()).collect();
    for (i, line) in text.lines().enumerate() {
        let Some(d) = line.trim_start().strip_prefix('#').map(str::trim_start) else { continue };
        let words: Vec<&str> = d.split_whitespace().collect();
        match words.as_slice() {
            ["pragma", rest @ ..] if stage == Stage::Fragment => {
                let joined: String = rest.concat();
                if joined.starts_with("STDGLinvariant(all)") {
                    return Err(error_at(i + 1, 1, "#pragma STDGL invariant(all) cannot be used in a fragment shader"));
                }
            }
            ["define", name, ..] => {
                let name = name.split('(').next().unwrap_or(name);
                defined.insert(name.to_string());
            }
            ["undef", name, ..] => {
                defined.remove(*name);
            }
            ["extension", name, ..] => {
                defined.insert(name.trim_end_matches(':').to_string());
            }
            [kw, ..] if *kw == "if" || *kw == "elif" => {
                let expr = d[kw.len()..].split("//").next().unwrap_or("");
                if let Some(name) = undefined_identifier(expr, &defined) {
                    return Err(error_at(i + 1, 1, &format!("undefined identifier `{name}' in #{kw}")));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// The first identifier of a `#if` expression that is not a defined macro nor the operand of
/// `defined`.
fn undefined_identifier(expr: &str, defined: &HashSet<String>) -> Option<String> {
    let mut after_defined = false;
    let mut chars = expr.char_indices().peekable();
    while let Some((start, c)) = chars.next() {
        if c.is_ascii_alphabetic() || c == '_' {
            let mut end = start + c.len_utf8();
            while let Some(&(j, n)) = chars.peek() {
                if n.is_ascii_alphanumeric() || n == '_' {
                    end = j + n.len_utf8();
                    chars.next();
                } else {
                    break;
                }
            }
            let word = &expr[start..end];
            if word == "defined" {
                after_defined = true;
                continue;
            }
            if !after_defined && !defined.contains(word) {
                return Some(word.to_string());
            }
            after_defined = false;
        } else if c.is_ascii_digit() {
            // A number, with any suffix letters.
            while chars.peek().is_some_and(|&(_, n)| n.is_ascii_alphanumeric()) {
                chars.next();
            }
        }
    }
    None
}
