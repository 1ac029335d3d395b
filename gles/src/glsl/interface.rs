//! The global interface of one shader: attributes, varyings and uniforms (GLSL ES 3.00: vertex
//! `in`s, `out`s and `in`s between the stages, and fragment `out`s) lifted out of the AST and
//! checked against the language's rules; what remains is rewritten (`rewrite`).

use std::collections::HashMap;

use glsl_lang::ast::{self, TypeQualifierSpecData};
use glsl_lang::visitor::HostMut;

use crate::glsl::checks;
use crate::glsl::consts::{array_len, fold, Val};
use crate::glsl::preprocess::parse;
use crate::glsl::rewrite::Rewrite;
use crate::glsl::types::{Scalar, Shader, Stage, Ty, Var};
use crate::limits::MAX_VARYING_ARRAY;

/// The storage qualifier that makes a declaration part of the interface.
#[derive(Clone, Copy, PartialEq)]
enum Storage {
    Attribute,
    Varying,
    Uniform,
    /// GLSL ES 3.00 `in`.
    In,
    /// GLSL ES 3.00 `out`.
    Out,
}

fn storage_of(q: Option<&ast::TypeQualifier>) -> Option<Storage> {
    q?.qualifiers.iter().find_map(|s| match &s.content {
        TypeQualifierSpecData::Storage(st) => match st.content {
            ast::StorageQualifierData::Attribute => Some(Storage::Attribute),
            ast::StorageQualifierData::Varying => Some(Storage::Varying),
            ast::StorageQualifierData::Uniform => Some(Storage::Uniform),
            ast::StorageQualifierData::In => Some(Storage::In),
            ast::StorageQualifierData::Out => Some(Storage::Out),
            _ => None,
        },
        _ => None,
    })
}

/// Whether a declaration is interpolated `flat`.
fn is_flat(q: Option<&ast::TypeQualifier>) -> bool {
    q.is_some_and(|q| {
        q.qualifiers.iter().any(|s| {
            matches!(&s.content, TypeQualifierSpecData::Interpolation(i) if i.content == ast::InterpolationQualifierData::Flat)
        })
    })
}

/// A declaration's `layout(location = N)`, if it has one; any other layout qualifier is an
/// error here (uniform blocks are not interface variables).
fn location_of(q: Option<&ast::TypeQualifier>, consts: &HashMap<String, Val>) -> Result<Option<u32>, String> {
    let mut location = None;
    for s in q.iter().flat_map(|q| q.qualifiers.iter()) {
        let TypeQualifierSpecData::Layout(l) = &s.content else { continue };
        for id in &l.ids {
            match &id.content {
                ast::LayoutQualifierSpecData::Identifier(name, Some(e)) if name.0 == "location" => {
                    match fold(e, consts) {
                        Some(Val::Int(n)) if (0..=i64::from(i32::MAX)).contains(&n) => location = Some(n as u32),
                        _ => return Err("0: the location must be a non-negative integral constant".into()),
                    }
                }
                ast::LayoutQualifierSpecData::Identifier(name, _) => {
                    return Err(format!("0: layout qualifier `{}' is not allowed here", name.0))
                }
                _ => return Err("0: this layout qualifier is not allowed here".into()),
            }
        }
    }
    Ok(location)
}

/// Compiles a shader: parse, lift the interface, rewrite the rest.
pub(super) fn compile_inner(stage: Stage, source: &str) -> Result<Shader, String> {
    let mut parsed = parse(stage, source)?;
    let version = parsed.version;
    let facts = checks::check(stage, &parsed)?;
    let mut elements = crate::glsl::blocks::Elements::new();
    if version == 300 {
        crate::glsl::es3_rules::check(stage, &parsed.text, &parsed.tu)?;
        crate::glsl::sized_arrays::size(&mut parsed.tu);
        elements = crate::glsl::block_arrays::split(&mut parsed.tu, version)?;
        crate::glsl::struct_varyings::flatten(stage, &mut parsed.tu)?;
    }
    let (structs, struct_types) = crate::glsl::struct_uniforms::flatten(&mut parsed.tu, version)?;
    crate::glsl::operators::rewrite(&mut parsed.tu, &parsed.text)?;
    let mut shader = Shader {
        stage,
        body: ast::TranslationUnit(Vec::new()),
        attributes: vec![],
        varyings: vec![],
        outputs: vec![],
        blocks: vec![],
        version,
        uniforms: vec![],
        point_coord: false,
        frag_depth: false,
        instance_id: false,
        vertex_id: false,
        frag_data: false,
        dual: false,
        has_main: false,
        lookups: Default::default(),
        polyfills: Default::default(),
        structs,
        log: parsed.warnings.join("\n"),
        source: source.to_string(),
        facts,
        line_starts: std::iter::once(0).chain(parsed.text.match_indices('\n').map(|(i, _)| i + 1)).collect(),
    };
    let mut consts = crate::glsl::consts::seeded(version);
    // The blocks' default matrix layout (`layout(row_major) uniform;`).
    let mut row_major = false;
    for decl in parsed.tu.0 {
        let list = match &decl.content {
            ast::ExternalDeclarationData::Preprocessor(_) => continue,
            ast::ExternalDeclarationData::Declaration(d) => match &d.content {
                // Precision is dropped; invariance of built-ins is checked at link time.
                ast::DeclarationData::Precision(..) | ast::DeclarationData::Invariant(_) => continue,
                ast::DeclarationData::InitDeclaratorList(list) => Some(list.clone()),
                ast::DeclarationData::Block(b) if version == 300 => {
                    if let Some(block) = crate::glsl::blocks::lift(b, &consts, &elements, row_major, &struct_types)? {
                        shader.body.0.extend(crate::glsl::block_structs::privates(&block));
                        shader.blocks.push(block);
                        continue;
                    }
                    None
                }
                // `layout(std140) uniform;`: the default layout of later blocks, std140 here.
                ast::DeclarationData::TypeOnly(q)
                    if version == 300 && crate::glsl::blocks::default_layout(q, &mut row_major)? =>
                {
                    continue
                }
                _ => None,
            },
            ast::ExternalDeclarationData::FunctionDefinition(f) => {
                shader.has_main |= f.prototype.name.0 == "main";
                None
            }
        };
        let Some(list) = list else {
            shader.body.0.push(decl);
            continue;
        };
        if checks::is_const(list.head.ty.qualifier.as_ref()) {
            let named = list.head.name.as_ref().map(|n| (n, list.head.initializer.as_ref()));
            for (name, init) in
                named.into_iter().chain(list.tail.iter().map(|t| (&t.ident.ident, t.initializer.as_ref())))
            {
                if let Some(ast::InitializerData::Simple(e)) = init.map(|i| &i.content) {
                    if let Some(v) = fold(e, &consts) {
                        consts.insert(name.0.to_string(), v);
                    }
                }
            }
        }
        let Some(storage) = storage_of(list.head.ty.qualifier.as_ref()) else {
            shader.body.0.push(decl);
            continue;
        };
        let qualifier = list.head.ty.qualifier.as_ref();
        match (storage, version) {
            (Storage::Attribute, 300) => return Err("0: illegal use of reserved word `attribute'".into()),
            (Storage::Varying, 300) => return Err("0: illegal use of reserved word `varying'".into()),
            (Storage::In | Storage::Out, 100) => {
                return Err("0: `in' and `out' declare no global variables in GLSL ES 1.00".into())
            }
            _ => {}
        }
        let (location, flat) = (location_of(qualifier, &consts)?, is_flat(qualifier));
        let Some(ty) = Ty::from_spec(&list.head.ty.ty.ty.content) else {
            // GLSL ES 3.00's shadow, array and integer samplers are declared and linked (an
            // unused uniform is inactive, and Mesa too drops it); sampling them is still to come.
            let names = list.head.name.iter().chain(list.tail.iter().map(|t| &t.ident.ident));
            let unused = !names.into_iter().any(|n| shader.facts.used.contains(n.0.as_str()));
            let sampler = crate::glsl::precision::ES3_SAMPLERS.contains(&list.head.ty.ty.ty.content);
            if sampler && unused && storage == Storage::Uniform {
                continue;
            }
            let not = if sampler { "not supported yet" } else { "not supported" };
            return Err(format!("0: interface variables of type '{}' are {not}", type_name(&list.head.ty.ty)));
        };
        let base_array = array_len(list.head.ty.ty.array_specifier.as_ref(), &consts)?;
        let mut vars = Vec::new();
        if let Some(name) = &list.head.name {
            vars.push(Var {
                name: name.0.to_string(),
                ty,
                array: array_len(list.head.array_specifier.as_ref(), &consts)?.or(base_array),
                location,
                flat,
            });
        }
        for t in &list.tail {
            vars.push(Var {
                name: t.ident.ident.0.to_string(),
                ty,
                array: array_len(t.ident.array_spec.as_ref(), &consts)?.or(base_array),
                location,
                flat,
            });
        }
        if list.head.initializer.is_some() || list.tail.iter().any(|t| t.initializer.is_some()) {
            return Err("0: attribute, varying and uniform variables cannot be initialised".into());
        }
        // An array's `length()` is a constant expression (GLSL ES 3.00 §4.1.9).
        for v in &vars {
            if let Some(n) = v.array {
                consts.insert(format!("{}.length()", v.name), crate::glsl::consts::Val::Int(i64::from(n)));
            }
        }
        let storage = match (storage, stage) {
            (Storage::In, Stage::Vertex) => Storage::Attribute,
            (Storage::Out, Stage::Vertex) | (Storage::In, Stage::Fragment) => Storage::Varying,
            (s, _) => s,
        };
        if location.is_some() && storage != Storage::Attribute && storage != Storage::Out {
            return Err("0: a location may only be given to vertex shader inputs and fragment shader outputs".into());
        }
        if flat && storage != Storage::Varying {
            return Err("0: `flat' only qualifies vertex shader outputs and fragment shader inputs".into());
        }
        match storage {
            Storage::Out => {
                if !matches!(ty.scalar(), Scalar::Float | Scalar::Int | Scalar::UInt) || ty.columns() > 0 {
                    return Err("0: fragment outputs must be float, int or uint scalars or vectors".into());
                }
                shader.outputs.extend(vars);
            }
            Storage::In => return Err("0: internal error: an input left unmapped".into()),
            Storage::Attribute if version == 300 => {
                let scalar = matches!(ty.scalar(), Scalar::Float | Scalar::Int | Scalar::UInt);
                if !scalar || vars.iter().any(|v| v.array.is_some()) {
                    return Err("0: vertex inputs must be float, int or uint scalars, vectors or matrices (arrays are not supported yet)".into());
                }
                shader.attributes.extend(vars);
            }
            Storage::Attribute => {
                if stage == Stage::Fragment {
                    return Err("0: 'attribute' is not allowed in a fragment shader".into());
                }
                if ty.scalar() != Scalar::Float || vars.iter().any(|v| v.array.is_some()) {
                    return Err("0: attributes must be float, vec2, vec3, vec4, mat2, mat3 or mat4".into());
                }
                shader.attributes.extend(vars);
            }
            Storage::Varying if version == 300 => {
                if !matches!(ty.scalar(), Scalar::Float | Scalar::Int | Scalar::UInt) {
                    return Err("0: varyings must not be boolean".into());
                }
                // GLSL ES 3.00 §4.3.4 and §4.3.6: integer varyings are interpolated flat.
                if ty.scalar() != Scalar::Float && !flat && stage == Stage::Fragment {
                    return Err(
                        "0: if a fragment input is (or contains) an integer, then it must be qualified with 'flat'"
                            .into(),
                    );
                }
                if vars.iter().any(|v| v.array.is_some_and(|n| n > MAX_VARYING_ARRAY)) {
                    return Err(format!("0: a varying array may have at most {MAX_VARYING_ARRAY} elements"));
                }
                shader.varyings.extend(vars);
            }
            Storage::Varying => {
                if ty.scalar() != Scalar::Float {
                    return Err("0: varyings must be floats, float vectors or matrices, or arrays of them".into());
                }
                if vars.iter().any(|v| v.array.is_some_and(|n| n > MAX_VARYING_ARRAY)) {
                    return Err(format!("0: a varying array may have at most {MAX_VARYING_ARRAY} elements"));
                }
                shader.varyings.extend(vars);
            }
            Storage::Uniform => {
                shader.uniforms.extend(vars);
            }
        }
    }
    // Functions taking samplers: naga accepts no combined sampler parameters, so each becomes a
    // texture and a sampler parameter, and every call passes both halves.
    let mut sampler_fns: HashMap<String, Vec<bool>> = HashMap::new();
    let mut sampler_params: HashMap<String, Ty> = HashMap::new();
    for decl in &shader.body.0 {
        let proto = match &decl.content {
            ast::ExternalDeclarationData::FunctionDefinition(f) => &f.prototype,
            ast::ExternalDeclarationData::Declaration(d) => match &d.content {
                ast::DeclarationData::FunctionPrototype(p) => p,
                _ => continue,
            },
            _ => continue,
        };
        let flags: Vec<bool> = proto
            .parameters
            .iter()
            .map(|p| match &p.content {
                ast::FunctionParameterDeclarationData::Named(_, d) => match Ty::from_spec(&d.ty.ty.content) {
                    Some(t) if t.is_sampler() => {
                        sampler_params.insert(d.ident.ident.0.to_string(), t);
                        true
                    }
                    _ => false,
                },
                ast::FunctionParameterDeclarationData::Unnamed(_, t) => {
                    Ty::from_spec(&t.ty.content).is_some_and(Ty::is_sampler)
                }
            })
            .collect();
        if flags.iter().any(|f| *f) {
            sampler_fns.insert(proto.name.0.to_string(), flags);
        }
    }
    let mut samplers: HashMap<String, Ty> = HashMap::new();
    let mut sampler_arrays: HashMap<String, u32> = HashMap::new();
    for u in shader.uniforms.iter().filter(|u| u.ty.is_sampler()) {
        match u.array {
            Some(len) => {
                sampler_arrays.insert(u.name.clone(), len);
                samplers.extend((0..len).map(|k| (crate::glsl::rewrite::sampler_element(&u.name, k), u.ty)));
            }
            None => {
                samplers.insert(u.name.clone(), u.ty);
            }
        }
    }
    let params = sampler_params.keys().cloned().collect();
    samplers.extend(sampler_params);
    let mut rewrite = Rewrite {
        sampler_fns,
        sampler_params: params,
        lookups: Default::default(),
        samplers,
        sampler_arrays,
        bools: shader
            .uniforms
            .iter()
            .filter(|u| u.ty.scalar() == Scalar::Bool)
            .map(|u| (u.name.clone(), (u.ty, u.array)))
            .collect(),
        mat2s: shader
            .uniforms
            .iter()
            .filter(|u| u.ty.rows() == 2)
            .map(|u| (u.name.clone(), (u.ty, u.array.is_some())))
            .collect(),
        error: None,
        stage,
        version,
        vertex_id: false,
        polyfills: Default::default(),
        point_coord: false,
        frag_depth: false,
        instance_id: false,
        frag_color: false,
        frag_data: false,
        secondary_color: false,
        secondary_data: false,
    };
    crate::glsl::block_structs::rewrite(&mut shader.body, &shader.blocks, &struct_types, &consts)?;
    crate::glsl::block_members::rewrite(&mut shader.body, &shader.blocks)?;
    shader.body.visit_mut(&mut rewrite);
    crate::glsl::rewrite::hoist_global_initializers(&mut shader.body);
    shader.point_coord = rewrite.point_coord;
    shader.lookups = std::mem::take(&mut rewrite.lookups);
    shader.frag_depth = rewrite.frag_depth;
    shader.instance_id = rewrite.instance_id;
    shader.vertex_id = rewrite.vertex_id;
    shader.polyfills = std::mem::take(&mut rewrite.polyfills);
    shader.frag_data = rewrite.frag_data || rewrite.secondary_data;
    shader.dual = rewrite.secondary_color || rewrite.secondary_data;
    // Each colour output pairs with its own second colour (Mesa's messages).
    let both = |a: &str, b: &str| format!("0:0(0): error: fragment shader writes to both `{a}' and `{b}'");
    if rewrite.frag_color && rewrite.frag_data {
        return Err(both("gl_FragColor", "gl_FragData"));
    }
    if rewrite.frag_color && rewrite.secondary_data {
        return Err(both("gl_FragColor", "gl_FragSecondaryDataEXT"));
    }
    if rewrite.frag_data && rewrite.secondary_color {
        return Err(both("gl_FragData", "gl_FragSecondaryColorEXT"));
    }
    if rewrite.secondary_color && rewrite.secondary_data {
        return Err(both("gl_FragSecondaryColorEXT", "gl_FragSecondaryDataEXT"));
    }
    if let Some(e) = rewrite.error {
        return Err(e);
    }
    Ok(shader)
}

fn type_name(t: &ast::TypeSpecifier) -> String {
    let mut s = String::new();
    let _ = glsl_lang::transpiler::glsl::show_type_specifier(&mut s, t, &mut Default::default());
    s
}
