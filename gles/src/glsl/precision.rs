//! Precision rules of GLSL ES 1.00 §4.5: the fragment language has no default precision for
//! floating-point types, so every float declaration needs a qualifier or a `precision`
//! statement in scope; a function's definition must return the precision its prototype does.

use std::collections::HashMap;

use glsl_lang::ast::{self, PrecisionQualifierData as P, TypeQualifierSpecData, TypeSpecifierNonArrayData as T};

use crate::glsl::types::Stage;

/// Reports an error at a span.
type At<'a> = &'a dyn Fn(Option<ast::NodeSpan>, &str) -> String;

fn is_float(t: &T) -> bool {
    matches!(
        t,
        T::Float
            | T::Vec2
            | T::Vec3
            | T::Vec4
            | T::Mat2
            | T::Mat3
            | T::Mat4
            | T::Mat22
            | T::Mat23
            | T::Mat24
            | T::Mat32
            | T::Mat33
            | T::Mat34
            | T::Mat42
            | T::Mat43
            | T::Mat44
    )
}

/// GLSL ES 3.00's sampler types beyond `sampler2D`, `samplerCube` and `sampler3D` (§4.1.7);
/// like `sampler3D`, none has a default precision (§4.5.4).
pub(super) const ES3_SAMPLERS: [T; 12] = [
    T::Sampler2DShadow,
    T::SamplerCubeShadow,
    T::Sampler2DArray,
    T::Sampler2DArrayShadow,
    T::ISampler2D,
    T::ISampler3D,
    T::ISamplerCube,
    T::ISampler2DArray,
    T::USampler2D,
    T::USampler3D,
    T::USamplerCube,
    T::USampler2DArray,
];

/// Whether a type may carry a precision qualifier (§4.5.2) in a shader of GLSL ES 3.00
/// (`es3`) or 1.00.
fn takes_precision(t: &T, es3: bool) -> bool {
    is_float(t)
        || is_int(t)
        || matches!(t, T::Sampler2D | T::SamplerCube | T::Sampler2DRect | T::Sampler3D)
        || (es3 && ES3_SAMPLERS.contains(t))
}

fn explicit(q: Option<&ast::TypeQualifier>) -> Option<P> {
    q?.qualifiers.iter().find_map(|s| match &s.content {
        TypeQualifierSpecData::Precision(p) => Some(p.content.clone()),
        _ => None,
    })
}

struct Walk<'a> {
    /// Default float precision per open scope (innermost last).
    scopes: Vec<Option<P>>,
    /// The sampler types given a default precision by a `precision` statement, with the
    /// depth of its scope: `sampler3D` (`GL_OES_texture_3D`) and GLSL ES 3.00's other sampler
    /// types have none of their own.
    sampler_defaults: Vec<(T, usize)>,
    at: At<'a>,
    /// The stage checked.
    stage: Stage,
    /// Whether the shader enables `GL_OES_texture_3D` (only then does a `precision`
    /// statement take `sampler3D`, as on Mesa).
    texture_3d: bool,
    /// Whether the shader is GLSL ES 3.00 (with its sampler types).
    es3: bool,
    /// Precision of each float or int uniform.
    uniforms: HashMap<String, P>,
    varyings: HashMap<String, P>,
}

fn is_int(t: &T) -> bool {
    matches!(t, T::Int | T::IVec2 | T::IVec3 | T::IVec4 | T::UInt | T::UVec2 | T::UVec3 | T::UVec4)
}

fn is_storage(q: Option<&ast::TypeQualifier>, storage: &ast::StorageQualifierData) -> bool {
    q.is_some_and(|q| {
        q.qualifiers.iter().any(|s| matches!(&s.content, TypeQualifierSpecData::Storage(st) if st.content == *storage))
    })
}

fn is_uniform(q: Option<&ast::TypeQualifier>) -> bool {
    is_storage(q, &ast::StorageQualifierData::Uniform)
}

impl Walk<'_> {
    /// Closes the innermost scope, with the defaults it set.
    fn pop_scope(&mut self) {
        self.scopes.pop();
        let depth = self.scopes.len();
        self.sampler_defaults.retain(|(_, d)| *d <= depth);
    }

    fn default_float(&self) -> Option<P> {
        self.scopes.iter().rev().find_map(|p| p.clone())
    }

    /// The precision a declaration of `ty` with qualifier `q` gets; an error if it needs one
    /// and none is in scope.
    fn precision_of(
        &self,
        q: Option<&ast::TypeQualifier>,
        ty: &ast::TypeSpecifier,
        span: Option<ast::NodeSpan>,
    ) -> Result<Option<P>, String> {
        let t = &ty.ty.content;
        if explicit(q).is_some() && !takes_precision(t, self.es3) {
            return Err((self.at)(span, "precision qualifiers apply only to float, int and sampler types"));
        }
        let undefaulted = *t == T::Sampler3D || ES3_SAMPLERS.contains(t);
        if undefaulted && explicit(q).is_none() && !self.sampler_defaults.iter().any(|(d, _)| d == t) {
            let name = ast::TypeSpecifierNonArray::from(t.clone());
            let mut spelled = String::new();
            glsl_lang::transpiler::glsl::show_type_specifier_non_array(
                &mut spelled,
                &name,
                &mut glsl_lang::transpiler::glsl::FormattingState::default(),
            )
            .map_err(|e| e.to_string())?;
            return Err((self.at)(span, &format!("No precision specified in this scope for type `{spelled}'")));
        }
        if !is_float(&ty.ty.content) {
            return Ok(None);
        }
        match explicit(q).or_else(|| self.default_float()) {
            Some(p) => Ok(Some(p)),
            None => Err((self.at)(span, "no precision specified this scope for type `float'")),
        }
    }

    fn declaration(&mut self, d: &ast::Declaration) -> Result<(), String> {
        match &d.content {
            ast::DeclarationData::Precision(p, ty) => {
                let t = &ty.ty.content;
                let sampler_3d = *t == T::Sampler3D && self.texture_3d;
                let es3_sampler = self.es3 && ES3_SAMPLERS.contains(t);
                if !(matches!(t, T::Float | T::Int | T::Sampler2D | T::SamplerCube | T::Sampler2DRect)
                    || sampler_3d
                    || es3_sampler)
                    || ty.array_specifier.is_some()
                {
                    return Err((self.at)(
                        d.span,
                        "default precision statements apply only to float, int and sampler types",
                    ));
                }
                if *t == T::Float {
                    if let Some(top) = self.scopes.last_mut() {
                        *top = Some(p.content.clone());
                    }
                }
                if *t == T::Sampler3D || es3_sampler {
                    self.sampler_defaults.push((t.clone(), self.scopes.len()));
                }
            }
            ast::DeclarationData::InitDeclaratorList(list) => {
                let h = &list.head;
                let q = h.ty.qualifier.as_ref();
                let float = self.precision_of(q, &h.ty.ty, h.span)?;
                if is_storage(q, &ast::StorageQualifierData::Varying) {
                    if let Some(prec) = &float {
                        let names = h.name.iter().chain(list.tail.iter().map(|t| &t.ident.ident));
                        for n in names {
                            self.varyings.insert(n.0.to_string(), prec.clone());
                        }
                    }
                }
                if is_uniform(q) {
                    let int_default = if self.stage == Stage::Vertex { P::High } else { P::Medium };
                    let prec =
                        float.or_else(|| is_int(&h.ty.ty.ty.content).then(|| explicit(q).unwrap_or(int_default)));
                    if let Some(prec) = prec {
                        let names = h.name.iter().chain(list.tail.iter().map(|t| &t.ident.ident));
                        for n in names {
                            self.uniforms.insert(n.0.to_string(), prec.clone());
                        }
                    }
                }
            }
            ast::DeclarationData::FunctionPrototype(p) => {
                self.prototype(p)?;
            }
            _ => {}
        }
        Ok(())
    }

    /// Checks a prototype's return and parameter types; returns the return precision.
    fn prototype(&self, p: &ast::FunctionPrototype) -> Result<Option<P>, String> {
        let ret = self.precision_of(p.ty.qualifier.as_ref(), &p.ty.ty, p.span)?;
        for param in &p.parameters {
            let (q, ty) = match &param.content {
                ast::FunctionParameterDeclarationData::Named(q, d) => (q, &d.ty),
                ast::FunctionParameterDeclarationData::Unnamed(q, t) => (q, t),
            };
            self.precision_of(q.as_ref(), ty, param.span)?;
        }
        Ok(ret)
    }

    fn statement(&mut self, s: &ast::Statement) -> Result<(), String> {
        match &s.content {
            ast::StatementData::Declaration(d) => self.declaration(d)?,
            ast::StatementData::Compound(c) => self.compound(c)?,
            ast::StatementData::Selection(sel) => match &sel.rest.content {
                ast::SelectionRestStatementData::Statement(a) => self.scoped(a)?,
                ast::SelectionRestStatementData::Else(a, b) => {
                    self.scoped(a)?;
                    self.scoped(b)?;
                }
            },
            ast::StatementData::Iteration(it) => {
                self.scopes.push(None);
                let r = match &it.content {
                    ast::IterationStatementData::For(init, _, body) => {
                        if let ast::ForInitStatementData::Declaration(d) = &init.content {
                            self.declaration(d)?;
                        }
                        self.statement(body)
                    }
                    ast::IterationStatementData::While(_, body) | ast::IterationStatementData::DoWhile(body, _) => {
                        self.statement(body)
                    }
                };
                self.pop_scope();
                r?;
            }
            _ => {}
        }
        Ok(())
    }

    fn scoped(&mut self, s: &ast::Statement) -> Result<(), String> {
        self.scopes.push(None);
        let r = self.statement(s);
        self.pop_scope();
        r
    }

    fn compound(&mut self, c: &ast::CompoundStatement) -> Result<(), String> {
        self.scopes.push(None);
        let r = c.statement_list.iter().try_for_each(|s| self.statement(s));
        self.pop_scope();
        r
    }
}

/// The precisions linking compares across stages.
pub(crate) struct Precisions {
    /// Of each float or int uniform (a uniform both stages use must have the same precision
    /// in both).
    pub(super) uniforms: HashMap<String, P>,
    /// Of each varying (`GL_EXT_separate_shader_objects` matches them across programs).
    pub(super) varyings: HashMap<String, P>,
}

/// Checks the precision rules of one shader; returns the precisions linking compares.
pub(crate) fn check(
    stage: Stage,
    tu: &ast::TranslationUnit,
    texture_3d: bool,
    es3: bool,
    at: At<'_>,
) -> Result<Precisions, String> {
    // The vertex language's default float precision is highp.
    let global = if stage == Stage::Vertex { Some(P::High) } else { None };
    let mut w = Walk {
        scopes: vec![global],
        sampler_defaults: Vec::new(),
        at,
        stage,
        texture_3d,
        es3,
        uniforms: HashMap::new(),
        varyings: HashMap::new(),
    };
    let mut prototypes: HashMap<String, Option<P>> = HashMap::new();
    for decl in &tu.0 {
        match &decl.content {
            ast::ExternalDeclarationData::Declaration(d) => {
                if let ast::DeclarationData::FunctionPrototype(p) = &d.content {
                    prototypes.insert(signature(p), w.prototype(p)?);
                } else {
                    w.declaration(d)?;
                }
            }
            ast::ExternalDeclarationData::FunctionDefinition(f) => {
                let ret = w.prototype(&f.prototype)?;
                if let Some(proto) = prototypes.get(&signature(&f.prototype)) {
                    if *proto != ret {
                        let name = &f.prototype.name.0;
                        return Err(at(
                            f.prototype.span,
                            &format!("function `{name}' return type precision doesn't match its prototype"),
                        ));
                    }
                }
                w.compound(&f.statement)?;
            }
            _ => {}
        }
    }
    Ok(Precisions { uniforms: w.uniforms, varyings: w.varyings })
}

/// A function's signature for redeclaration checks: its name and parameter types.
pub(crate) fn signature(p: &ast::FunctionPrototype) -> String {
    let mut s = p.name.0.to_string();
    for param in &p.parameters {
        let ty = match &param.content {
            ast::FunctionParameterDeclarationData::Named(_, d) => &d.ty,
            ast::FunctionParameterDeclarationData::Unnamed(_, t) => t,
        };
        s.push('|');
        let _ = glsl_lang::transpiler::glsl::show_type_specifier(&mut s, ty, &mut Default::default());
    }
    s
}
