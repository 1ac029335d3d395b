//! Linking: one std140 uniform block for both stages, attribute and varying locations, the
//! generated `main`s that apply Strata's conventions (y negated, clip z mapped from [-1, 1] to
//! [0, 1]; see `conv`), the points variant of the vertex stage, the reversed-Z variants (see
//! `docs/projection.md`), and validation by naga.

use std::collections::HashMap;
use std::fmt::Write as _;

use crate::glsl::linked::{
    array_suffix, Linked, LinkedBlock, UniformSlot, CONVENTIONS, FRAG_DEPTH_OUT, POINT_SIZE_STEP, VERTEX_ID_STEP,
};
use crate::glsl::translate::{naga_module, transpile, Body, Placed};
use crate::glsl::types::{Scalar, Shader, Stage, Ty, Var};
use crate::limits::{MAX_BLOCK, MAX_SAMPLERS, MAX_VARYING_VECTORS};
use crate::limits::{MAX_DRAW_BUFFERS, MAX_POINT_SIZE};

/// The vectors a matrix or array varying crosses stages as: (name suffix, access from the
/// variable, GLSL type), one per location.
fn varying_slots(v: &Var) -> Vec<(String, String, &'static str)> {
    let column_ty = match v.ty.rows() {
        2 => "vec2",
        3 => "vec3",
        4 => "vec4",
        _ => v.ty.glsl(false),
    };
    let mut slots = Vec::new();
    for e in 0..v.array.unwrap_or(1) {
        let elem = if v.array.is_some() { format!("[{e}]") } else { String::new() };
        match v.ty.columns() {
            0 => slots.push((format!("__e{e}"), elem, column_ty)),
            cols => {
                for c in 0..cols {
                    slots.push((format!("__e{e}c{c}"), format!("{elem}[{c}]"), column_ty));
                }
            }
        }
    }
    slots
}

/// Parses and validates the points vertex stage of a linked program (`Linked::points_source`).
pub fn points_vertex(linked: &Linked) -> Result<naga::Module, String> {
    let none = Body { text: String::new(), lines: Vec::new() };
    std::panic::catch_unwind(|| {
        naga_module(Stage::Vertex, &linked.points_source, &Placed { first_line: usize::MAX, body: &none })
    })
    .unwrap_or_else(|_| Err("internal error: translating the points stage failed".into()))
}

/// Links a vertex and a fragment shader. `bindings` are `glBindAttribLocation` requests;
/// `max_attribs` bounds locations. The error is the program info log.
pub fn link(vs: &Shader, fs: &Shader, bindings: &HashMap<String, u32>, max_attribs: u32) -> Result<Linked, String> {
    std::panic::catch_unwind(|| link_inner(vs, fs, bindings, max_attribs))
        .unwrap_or_else(|_| Err("error: internal error: translating this program failed".into()))
}

fn link_inner(vs: &Shader, fs: &Shader, bindings: &HashMap<String, u32>, max_attribs: u32) -> Result<Linked, String> {
    let g = generate(vs, fs, bindings, max_attribs)?;
    let placed = |first_line, body| Placed { first_line, body };
    let vertex = naga_module(Stage::Vertex, &g.vsrc, &placed(g.vs_first_line, &g.vs_body))
        .map_err(|e| format!("vertex shader:\n{e}"))?;
    let fragment = naga_module(Stage::Fragment, &g.fsrc, &placed(g.fs_first_line, &g.fs_body))
        .map_err(|e| format!("fragment shader:\n{e}"))?;
    let reversed_fragment_source = crate::glsl::variants::reversed_fragment_source(&g.fsrc, g.fs_first_line);
    let Generated {
        vsrc: vertex_source,
        attributes,
        uniforms,
        block_size,
        samplers,
        wrap_offsets,
        points_source,
        point_input,
        blocks,
        ..
    } = g;
    Ok(Linked {
        vertex,
        fragment,
        attributes,
        uniforms,
        block_size,
        samplers,
        wrap_offsets,
        points_source,
        vertex_source,
        reversed_fragment_source,
        point_input,
        dual: fs.dual,
        blocks,
        // GLSL ES 3.00's outputs; the link placed a lone one without a location at 0; an
        // array's elements are at the locations after its first.
        outputs: fs
            .outputs
            .iter()
            .flat_map(|o| {
                let loc = o.location.unwrap_or(0);
                let elements = (0..o.array.unwrap_or(0)).map(move |i| (format!("{}[{i}]", o.name), loc + i));
                std::iter::once((o.name.clone(), loc)).chain(elements)
            })
            .collect(),
        output_kinds: crate::glsl::linked::output_kinds(fs),
        flat: fs.varyings.iter().any(|v| interpolation(v) == "flat "),
        capture: None,
    })
}

/// A compiled shader translated once against `other`, a stand-in for the other stage (which
/// declares the same varyings and nothing else): the errors only naga finds, such as types, fail the
/// compile with the shader's line. What only a real link can judge is left to the link.
pub(super) fn check_stage(s: Shader, other: &Shader) -> Result<Shader, String> {
    let (vs, fs) = if s.stage == Stage::Vertex { (&s, other) } else { (other, &s) };
    let Ok(g) = generate(vs, fs, &HashMap::new(), 1024) else { return Ok(s) };
    let (src, placed) = match s.stage {
        Stage::Vertex => (&g.vsrc, Placed { first_line: g.vs_first_line, body: &g.vs_body }),
        Stage::Fragment => (&g.fsrc, Placed { first_line: g.fs_first_line, body: &g.fs_body }),
    };
    naga_module(s.stage, src, &placed)?;
    Ok(s)
}

/// A program's generated stage sources, before naga.
struct Generated {
    vsrc: String,
    fsrc: String,
    /// The vertex shader's own code and the line of `vsrc` where it starts.
    vs_body: Body,
    vs_first_line: usize,
    /// The fragment shader's own code and the line of `fsrc` where it starts.
    fs_body: Body,
    fs_first_line: usize,
    attributes: Vec<(Var, u32)>,
    uniforms: Vec<UniformSlot>,
    block_size: u32,
    samplers: Vec<(Ty, u32)>,
    wrap_offsets: Vec<u32>,
    points_source: String,
    point_input: u32,
    blocks: Vec<LinkedBlock>,
}

/// The uniform block, locations and both stages' sources of a program.
fn generate(vs: &Shader, fs: &Shader, bindings: &HashMap<String, u32>, max_attribs: u32) -> Result<Generated, String> {
    // GLSL ES 1.00 §2.10: a missing `main` is a link error.
    for (s, name) in [(vs, "vertex"), (fs, "fragment")] {
        if !s.has_main {
            return Err(format!("error: {name} shader lacks `main'"));
        }
    }
    // GLSL ES 1.00 §4.6.4: gl_FragCoord and gl_PointCoord may be invariant only if gl_Position
    // and gl_PointSize are.
    for (frag, vert) in [("gl_FragCoord", "gl_Position"), ("gl_PointCoord", "gl_PointSize")] {
        if fs.facts.invariants.contains(frag) && !vs.facts.invariants.contains(vert) {
            return Err(format!("error: {frag} can be invariant only if {vert} is invariant in the vertex shader"));
        }
    }
    // §4.5.3: a uniform both stages use has the same precision in both.
    for (name, p) in &vs.facts.uniform_precisions {
        if let Some(q) = fs.facts.uniform_precisions.get(name) {
            if p != q && vs.facts.used.contains(name) && fs.facts.used.contains(name) {
                return Err(format!("error: uniform `{name}' has different precisions in the two stages"));
            }
        }
    }
    crate::glsl::struct_uniforms::check_link(vs, fs)?;
    // Uniforms: one program-wide namespace.
    let mut uniforms: Vec<UniformSlot> = Vec::new();
    let mut samplers = Vec::new();
    let mut offset = 0u32;
    // Array sizes are the shader's: the block is bounded before anything is allocated for it.
    let too_big = || format!("error: the uniforms need more than the {MAX_BLOCK} bytes a uniform block can bind");
    for u in vs.uniforms.iter().chain(&fs.uniforms) {
        if let Some(prev) = uniforms.iter().find(|p| p.name == u.name) {
            if prev.ty != u.ty || prev.len != u.array.unwrap_or(1) {
                return Err(format!("error: uniform '{}' is declared with different types in the two stages", u.name));
            }
            continue;
        }
        let len = u.array.unwrap_or(1);
        let (size, align, stride, sampler) = if u.ty.is_sampler() {
            // A sampler array is `len` consecutive samplers, one binding pair each.
            let first = samplers.len();
            for _ in 0..len.min(MAX_SAMPLERS as u32 + 1) {
                samplers.push((u.ty, 1 + 3 * samplers.len() as u32));
            }
            (0, 1, 0, Some(first))
        } else {
            let (size, align) = u.ty.std140();
            if u.array.is_some() {
                let stride = size.div_ceil(16) * 16;
                (stride.checked_mul(len).ok_or_else(too_big)?, 16, stride, None)
            } else {
                (size, align, size, None)
            }
        };
        offset = offset.div_ceil(align) * align;
        let names = vs.structs.names.get(&u.name).or_else(|| fs.structs.names.get(&u.name));
        uniforms.push(UniformSlot {
            gl_name: names.unwrap_or(&u.name).clone(),
            name: u.name.clone(),
            ty: u.ty,
            len,
            is_array: u.array.is_some(),
            offset,
            stride,
            sampler,
        });
        offset = offset.checked_add(size).filter(|&o| o <= MAX_BLOCK).ok_or_else(too_big)?;
    }
    if samplers.len() > MAX_SAMPLERS {
        return Err(format!("error: more than {MAX_SAMPLERS} samplers declared"));
    }
    // Each sampler's wrap flags, border colour, swizzle and comparison, after the uniforms.
    let mut wrap_offsets = Vec::with_capacity(samplers.len());
    for _ in &samplers {
        offset = offset.div_ceil(16) * 16;
        wrap_offsets.push(offset);
        offset = offset.checked_add(64).filter(|&o| o <= MAX_BLOCK).ok_or_else(too_big)?;
    }
    let block_size = offset.div_ceil(16) * 16;
    let blocks = crate::glsl::blocks::link_blocks(vs, fs)?;

    let (attributes, used) = crate::glsl::attributes::place(vs, bindings, max_attribs)?;

    // Varyings: every fragment input must be a vertex output of the same type, and (GLSL ES
    // 3.00 §4.3.9) the same interpolation.
    for v in &fs.varyings {
        match vs.varyings.iter().find(|o| o.name == v.name) {
            Some(o) if o.ty == v.ty && o.array == v.array && o.flat != v.flat && fs.version == 300 => {
                return Err(format!("error: interpolation qualifier mismatch for varying '{}'", v.name))
            }
            Some(o) if o.ty == v.ty && o.array == v.array => {}
            Some(_) => return Err(format!("error: varying '{}' has different types in the two stages", v.name)),
            None => return Err(format!("error: fragment varying '{}' is not written by the vertex shader", v.name)),
        }
    }

    let mut common = String::from("#version 450\n");
    if block_size > 0 {
        common.push_str("layout(std140, set = 0, binding = 0) uniform StrataUniforms {\n");
        for u in uniforms.iter().filter(|u| !u.ty.is_sampler()) {
            if u.ty.rows() == 2 {
                // naga lays out no `matCx2` in std140: each column is a vec4 (`rewrite::mat2_of`).
                let _ = writeln!(common, "    vec4 strata_m2_{}[{}];", u.name, u.ty.columns() as u32 * u.len);
                continue;
            }
            let name = if u.ty.scalar() == Scalar::Bool { format!("strata_b_{}", u.name) } else { u.name.clone() };
            let arr = if u.is_array { format!("[{}]", u.len) } else { String::new() };
            let _ = writeln!(common, "    {} {name}{arr};", u.ty.glsl(true));
        }
        for name in sampler_names(&uniforms) {
            let _ =
                writeln!(common, "    vec4 {name}__w;\n    vec4 {name}__c;\n    vec4 {name}__z;\n    vec4 {name}__d;");
        }
        common.push_str("};\n");
    }
    if !samplers.is_empty() {
        common.push_str(WRAP_FNS);
        common.push_str(crate::glsl::swizzle::SWIZZLE_FNS);
        if samplers.iter().any(|(t, _)| t.is_shadow()) {
            common.push_str(crate::glsl::shadow::SHADOW_FNS);
        }
        if samplers.iter().any(|(t, _)| t.int_sampler().is_some()) {
            common.push_str(&crate::glsl::int_samplers::helpers());
        }
    }
    for ((ty, binding), name) in samplers.iter().zip(sampler_names(&uniforms)) {
        let _ = writeln!(common, "layout(set = 0, binding = {binding}) uniform {} {name}__t;", ty.glsl(true));
        let _ = writeln!(common, "layout(set = 0, binding = {}) uniform sampler {name}__s;", binding + 1);
        let _ = writeln!(common, "layout(set = 0, binding = {}) uniform sampler {name}__b;", binding + 2);
    }

    let declared = |stage_blocks: &[crate::glsl::types::Block]| -> String {
        blocks
            .iter()
            .filter(|b| stage_blocks.iter().any(|s| s.name == b.block.name))
            .map(|b| crate::glsl::blocks::declaration(&b.block, b.binding))
            .collect()
    };
    let (vs_blocks, fs_blocks) = (declared(&vs.blocks), declared(&fs.blocks));
    let mut vsrc = common.clone();
    vsrc.push_str(&vs_blocks);
    vsrc.push_str(&lookup_helpers(&vs.lookups));
    vsrc.push_str(&crate::glsl::polyfill::definitions(&vs.polyfills));
    let attribute_copy = crate::glsl::attributes::declare(&attributes, &mut vsrc);
    // Varying locations: one per vector, one per column of a matrix, per array element.
    // Matrices and arrays cannot cross stages in naga, so such a varying is a private global in
    // each stage, copied through vectors in the generated `main`s.
    let mut locations: HashMap<&str, u32> = HashMap::new();
    let mut next = 0u32;
    for v in &vs.varyings {
        locations.insert(v.name.as_str(), next);
        next += varying_slots(v).len() as u32;
    }
    // GL_MAX_VARYING_VECTORS (one more location stays free for gl_PointCoord).
    if next > MAX_VARYING_VECTORS {
        return Err(format!("error: the varyings need {next} vectors; at most {MAX_VARYING_VECTORS} are supported"));
    }
    let mut vs_copy = String::new();
    for v in &vs.varyings {
        let loc = locations[v.name.as_str()];
        let flat = interpolation(v);
        if v.ty.columns() == 0 && v.array.is_none() {
            let _ = writeln!(vsrc, "layout(location = {loc}) {flat}out {} {};", v.ty.glsl(false), v.name);
            continue;
        }
        let _ = writeln!(vsrc, "{} {}{};", v.ty.glsl(false), v.name, array_suffix(v));
        for (i, (suffix, access, ty)) in varying_slots(v).into_iter().enumerate() {
            let _ = writeln!(vsrc, "layout(location = {}) {flat}out {ty} {}{suffix};", loc + i as u32, v.name);
            let _ = writeln!(vs_copy, "    {}{suffix} = {}{access};", v.name, v.name);
        }
    }
    // gl_PointCoord: one more varying, a square's corner in the points stage.
    let mut pc_default = String::new();
    let mut pc_corner = String::new();
    if fs.point_coord {
        let _ = writeln!(vsrc, "layout(location = {next}) out vec2 strata_PointCoord;");
        pc_default.push_str("    strata_PointCoord = vec2(0.0);\n");
        // GL's point sprite origin is the upper left: t grows downwards (ES 2.0 §3.3).
        pc_corner.push_str("    strata_PointCoord = vec2(strata_corner.x, 1.0 - strata_corner.y);\n");
    }
    vsrc.push_str("float strata_PointSize;\n");
    // gl_InstanceIDEXT: the instance's number, which the points stage is told per draw.
    let (instance, point_instance) = if vs.instance_id {
        vsrc.push_str("int strata_InstanceID;\n");
        ("    strata_InstanceID = int(gl_InstanceIndex);\n", "    strata_InstanceID = int(strata_point.z);\n")
    } else {
        ("", "")
    };
    // gl_VertexID (GLSL ES 3.00): the vertex's number; in the points stage, whose vertices are
    // a square's corners, the point's instance (the vertex of a non-indexed draw).
    let (vertex_id, point_vertex_id) = if vs.vertex_id {
        vsrc.push_str("int strata_VertexID;\n");
        (VERTEX_ID_STEP, "    strata_VertexID = int(gl_InstanceIndex);\n")
    } else {
        ("", "")
    };
    let (instance, point_instance) = (
        format!("{attribute_copy}{instance}{vertex_id}"),
        format!("{attribute_copy}{point_instance}{point_vertex_id}"),
    );
    let point_input = used.iter().position(|u| !u).unwrap_or(used.len()) as u32;
    let vs_body = transpile(vs)?;
    let body = &vs_body.text;
    let points_source = format!(
        "{vsrc}layout(location = {point_input}) in vec4 strata_point;\n{body}\nvoid main() {{\n    strata_PointSize = 1.0;\n{point_instance}    strata_main();\n{vs_copy}\
{POINT_SIZE_STEP} = clamp(strata_PointSize, 1.0, {MAX_POINT_SIZE:.1});\n\
    vec2 strata_corner = vec2(float(gl_VertexIndex & 1), float((gl_VertexIndex >> 1) & 1));\n{pc_corner}\
    gl_Position.xy += (strata_corner * 2.0 - 1.0) * (strata_size * gl_Position.w) * strata_point.xy;\n{CONVENTIONS}}}\n"
    );
    let vs_first_line = vsrc.matches('\n').count();
    vsrc.push_str(body);
    vsrc.push_str(&format!(
        "\nvoid main() {{\n    strata_PointSize = 1.0;\n{instance}    strata_main();\n{vs_copy}{pc_default}{CONVENTIONS}}}\n"
    ));

    let mut fsrc = common;
    if samplers.iter().any(|(t, _)| t.is_shadow()) {
        fsrc.push_str(crate::glsl::shadow::SHADOW_IMPLICIT_FNS);
    }
    if samplers.iter().any(|(t, _)| t.int_sampler().is_some()) {
        fsrc.push_str(&crate::glsl::int_samplers::implicit_helpers());
    }
    fsrc.push_str(&fs_blocks);
    fsrc.push_str(&lookup_helpers(&fs.lookups));
    fsrc.push_str(&crate::glsl::polyfill::definitions(&fs.polyfills));
    let mut fs_copy = String::new();
    for v in &fs.varyings {
        let loc = locations.get(v.name.as_str()).copied().unwrap_or(0);
        let flat = interpolation(v);
        if v.ty.columns() == 0 && v.array.is_none() {
            let _ = writeln!(fsrc, "layout(location = {loc}) {flat}in {} {};", v.ty.glsl(false), v.name);
            continue;
        }
        let _ = writeln!(fsrc, "{} {}{};", v.ty.glsl(false), v.name, array_suffix(v));
        let slots = varying_slots(v);
        let cols = v.ty.columns();
        for (i, (suffix, access, ty)) in slots.iter().enumerate() {
            let _ = writeln!(fsrc, "layout(location = {}) {flat}in {ty} {}{suffix};", loc + i as u32, v.name);
            if cols == 0 {
                let _ = writeln!(fs_copy, "    {}{access} = {}{suffix};", v.name, v.name);
            }
        }
        if cols > 0 {
            for (e, chunk) in slots.chunks(cols).enumerate() {
                let parts: Vec<String> = chunk.iter().map(|(suffix, _, _)| format!("{}{suffix}", v.name)).collect();
                let elem = if v.array.is_some() { format!("[{e}]") } else { String::new() };
                let _ = writeln!(fs_copy, "    {}{elem} = {}({});", v.name, v.ty.glsl(false), parts.join(", "));
            }
        }
    }
    if fs.point_coord {
        let _ = writeln!(fsrc, "layout(location = {next}) in vec2 strata_PointCoord;");
    }
    // One output per draw buffer (`GL_EXT_draw_buffers`): `gl_FragData[i]` writes output `i`,
    // and `gl_FragColor` writes every output, as the extension specifies.
    let mut color_out = String::new();
    if fs.dual {
        // Dual-source blending (`GL_EXT_blend_func_extended`): location 0's two sources are
        // the only outputs, as one draw buffer is all it allows.
        let (first, second) = if fs.frag_data {
            let _ = writeln!(fsrc, "vec4 strata_FragData[{MAX_DRAW_BUFFERS}];\nvec4 strata_SecondaryFragData[1];");
            ("strata_FragData[0]", "strata_SecondaryFragData[0]")
        } else {
            fsrc.push_str("vec4 strata_FragColor;\nvec4 strata_SecondaryFragColor;\n");
            ("strata_FragColor", "strata_SecondaryFragColor")
        };
        fsrc.push_str("layout(location = 0, index = 0) out vec4 strata_FragOut0;\n");
        fsrc.push_str("layout(location = 0, index = 1) out vec4 strata_FragOut0b;\n");
        let _ = writeln!(color_out, "    strata_FragOut0 = {first};\n    strata_FragOut0b = {second};");
    } else if fs.version == 300 {
        // GLSL ES 3.00's own outputs (§4.3.8.2): each at its location, a lone one without a
        // location at 0; each a private variable the generated `main` copies out.
        let lone = fs.outputs.len() == 1;
        let mut taken = [false; MAX_DRAW_BUFFERS];
        for o in &fs.outputs {
            // An array takes a location per element.
            let len = o.array.unwrap_or(1) as usize;
            let loc = match (o.location, lone) {
                (Some(l), _) => l as usize,
                (None, true) => 0,
                (None, false) => {
                    return Err(format!(
                        "error: fragment shader output '{}' needs a location: the shader has more than one output",
                        o.name
                    ))
                }
            };
            if loc + len > MAX_DRAW_BUFFERS {
                return Err(format!(
                    "error: fragment output '{}' at location {loc} is past GL_MAX_DRAW_BUFFERS",
                    o.name
                ));
            }
            if taken[loc..loc + len].iter().any(|&t| t) {
                return Err(format!("error: fragment outputs share location {loc}"));
            }
            taken[loc..loc + len].iter_mut().for_each(|t| *t = true);
            let suffix = o.array.map(|n| format!("[{n}]")).unwrap_or_default();
            let _ = writeln!(fsrc, "{} {}{suffix};", o.ty.glsl(false), o.name);
            for i in 0..len {
                let at = loc + i;
                let element = if o.array.is_some() { format!("{}[{i}]", o.name) } else { o.name.clone() };
                // Integer outputs stay integers, for integer colour buffers.
                let (v4, zero, one) = match o.ty.scalar() {
                    Scalar::Int => ("ivec4", "0", "1"),
                    Scalar::UInt => ("uvec4", "0u", "1u"),
                    _ => ("vec4", "0.0", "1.0"),
                };
                let _ = writeln!(fsrc, "layout(location = {at}) out {v4} strata_FragOut{at};");
                let value = match o.ty.components() {
                    1 => format!("{v4}({element}, {zero}, {zero}, {one})"),
                    2 => format!("{v4}({element}, {zero}, {one})"),
                    3 => format!("{v4}({element}, {one})"),
                    _ => element,
                };
                let _ = writeln!(color_out, "    strata_FragOut{at} = {value};");
            }
        }
    } else if fs.frag_data {
        let _ = writeln!(fsrc, "vec4 strata_FragData[{MAX_DRAW_BUFFERS}];");
        for i in 0..MAX_DRAW_BUFFERS {
            let _ = writeln!(fsrc, "layout(location = {i}) out vec4 strata_FragOut{i};");
            let _ = writeln!(color_out, "    strata_FragOut{i} = strata_FragData[{i}];");
        }
    } else {
        fsrc.push_str("layout(location = 0) out vec4 strata_FragColor;\n");
        for i in 1..MAX_DRAW_BUFFERS {
            let _ = writeln!(fsrc, "layout(location = {i}) out vec4 strata_FragOut{i};");
            let _ = writeln!(color_out, "    strata_FragOut{i} = strata_FragColor;");
        }
    }
    let depth_out = if fs.frag_depth {
        fsrc.push_str("float strata_FragDepth;\n");
        FRAG_DEPTH_OUT
    } else {
        ""
    };
    let fs_body = transpile(fs)?;
    let fs_first_line = fsrc.matches('\n').count();
    fsrc.push_str(&fs_body.text);
    fsrc.push_str(&format!("\nvoid main() {{\n{fs_copy}    strata_main();\n{color_out}{depth_out}}}\n"));
    Ok(Generated {
        vsrc,
        fsrc,
        vs_body,
        vs_first_line,
        fs_body,
        fs_first_line,
        attributes,
        uniforms,
        block_size,
        samplers,
        wrap_offsets,
        points_source,
        point_input,
        blocks,
    })
}

/// The interpolation qualifier a varying crosses stages with: `flat ` where the shader says so,
/// and for integers, which are never interpolated.
fn interpolation(v: &Var) -> &'static str {
    if v.flat || matches!(v.ty.scalar(), Scalar::Int | Scalar::UInt) {
        "flat "
    } else {
        ""
    }
}

/// The name of each sampler, in the order of the program's sampler list: an array's elements
/// one by one.
fn sampler_names(uniforms: &[UniformSlot]) -> Vec<String> {
    let mut names = Vec::new();
    for u in uniforms.iter().filter(|u| u.ty.is_sampler()) {
        for k in 0..u.len {
            names.push(if u.is_array { crate::glsl::rewrite::sampler_element(&u.name, k) } else { u.name.clone() });
        }
    }
    names
}

/// The coordinate wrap of `GL_EXT_texture_mirror_clamp_to_edge` for a sampler's flags `w` (and a 2D
/// array's layer as GL rounds it, `polyfill::array_layer`):
/// where x or y (and for a 3D image, w) is set, the sampler clamps to the edge and the
/// coordinate is its magnitude, which mirrors it once exactly, filtering included.
pub(super) const WRAP_FNS: &str =
    "vec2 strata_wrap(vec2 c, vec4 w) { return mix(c, abs(c), greaterThan(w.xy, vec2(0.5))); }\n\
     vec3 strata_wrap(vec3 c, vec4 w) { return mix(c, abs(c), greaterThan(w.xyw, vec3(0.5))); }\n\
     vec3 strata_layer(vec3 c) { return vec3(c.xy, floor(c.z + 0.5)); }\n";

/// The helpers the rewrite turns 2D and 3D lookups into (`Shader::lookups`), one per sampler
/// uniform and function, and one per function for sampler parameters. Each wraps the
/// coordinate (`WRAP_FNS`), samples, and where a wrap is `GL_CLAMP_TO_BORDER_EXT` (flag z)
/// adds the border colour `c` weighted by how much of the filter fell outside the image: the
/// sampler reads a transparent black border and the border sampler an opaque white one, so the
/// difference of their alphas is that weight, exactly, for any filter. A uniform's helper
/// branches on its flags (uniform control flow, so implicit derivatives stay defined), and a
/// projective lookup with no flag set stays projective; a parameter's helper always samples
/// twice and projects first.
pub(super) fn lookup_helpers(lookups: &std::collections::BTreeSet<(String, String, bool)>) -> String {
    let mut out = String::new();
    for (sampler, function, three_d) in lookups {
        let base = function.replace("Proj", "");
        let (vec, texture, combined, prefix) = if *three_d {
            ("vec3", "texture3D", "sampler3D", "strata_p3_")
        } else {
            ("vec2", "texture2D", "sampler2D", "strata_p_")
        };
        let coords: &[(&str, &str)] = match (function.contains("Proj"), three_d) {
            (true, false) => &[("vec3", "c.xy / c.z"), ("vec4", "c.xy / c.w")],
            (true, true) => &[("vec4", "c.xyz / c.w")],
            (false, _) => &[(vec, "c")],
        };
        // The optional bias of the implicit-level functions, or the level of the Lod ones.
        let extras: &[(&str, &str)] =
            if function.contains("Lod") { &[(", float e", ", e")] } else { &[("", ""), (", float e", ", e")] };
        for (ty, projected) in coords {
            for (param, arg) in extras {
                if sampler.is_empty() {
                    let _ = writeln!(
                        out,
                        "vec4 {prefix}{function}({texture} t, sampler s, sampler b, vec4 w, vec4 border, vec4 z, vec4 d, {ty} c{param}) {{\n\
                         \x20   {vec} p = strata_wrap({projected}, w);\n\
                         \x20   vec4 v = {base}({combined}(t, s), p{arg});\n\
                         \x20   return v + border * ((({base}({combined}(t, b), p{arg})).a - v.a) * w.z);\n}}"
                    );
                    continue;
                }
                let (t, s, b, w, c) = (
                    format!("{sampler}__t"),
                    format!("{sampler}__s"),
                    format!("{sampler}__b"),
                    format!("{sampler}__w"),
                    format!("{sampler}__c"),
                );
                let keep = if function.contains("Proj") {
                    format!(
                        "    if ({w}.x + {w}.y + {w}.z + {w}.w == 0.0) {{ return {function}({combined}({t}, {s}), c{arg}); }}\n"
                    )
                } else {
                    String::new()
                };
                let _ = writeln!(
                    out,
                    "vec4 {sampler}__{function}({ty} c{param}) {{\n{keep}\
                     \x20   {vec} p = strata_wrap({projected}, {w});\n\
                     \x20   vec4 v = {base}({combined}({t}, {s}), p{arg});\n\
                     \x20   if ({w}.z > 0.5) {{ v += {c} * ({base}({combined}({t}, {b}), p{arg}).a - v.a); }}\n\
                     \x20   return v;\n}}"
                );
            }
        }
    }
    out
}
