//! Uniforms: locations, active-uniform queries, the `glUniform*` family writing the program's
//! std140 block (or a sampler's texture unit), and reading values back.

use strata_protocol::{Slice, Text};

use crate::context::Context;

use crate::error::{GlError, GlResult};
use crate::glsl::types::Scalar;
use crate::limits::MAX_UNITS;
use crate::objects::program::LinkedProgram;
use crate::GlesExecutor;

/// The values of one `glUniform*` call.
enum Vals<'a> {
    F(&'a [f32]),
    I(&'a [i32]),
    U(&'a [u32]),
}

impl Vals<'_> {
    fn len(&self) -> usize {
        match self {
            Vals::F(v) => v.len(),
            Vals::I(v) => v.len(),
            Vals::U(v) => v.len(),
        }
    }

    /// Value `i` as the four bytes a uniform of kind `scalar` stores (booleans as 0 or 1).
    fn bytes(&self, i: usize, scalar: Scalar) -> [u8; 4] {
        match (self, scalar) {
            (Vals::F(v), Scalar::Bool) => i32::from(v[i] != 0.0).to_ne_bytes(),
            (Vals::I(v), Scalar::Bool) => i32::from(v[i] != 0).to_ne_bytes(),
            (Vals::U(v), Scalar::Bool) => i32::from(v[i] != 0).to_ne_bytes(),
            (Vals::F(v), _) => v[i].to_ne_bytes(),
            (Vals::I(v), _) => v[i].to_ne_bytes(),
            (Vals::U(v), _) => v[i].to_ne_bytes(),
        }
    }
}

/// What a `glUniform*` call writes per element: `n` components, or a matrix of `columns`
/// columns of `rows` (0 columns for vectors).
#[derive(Clone, Copy)]
struct Shape {
    n: usize,
    columns: usize,
    rows: usize,
}

impl Shape {
    const fn vector(n: usize) -> Shape {
        Shape { n, columns: 0, rows: 0 }
    }

    const fn matrix(columns: usize, rows: usize) -> Shape {
        Shape { n: columns * rows, columns, rows }
    }
}

/// The location of uniform `name` (`name` or `name[i]`; a structure's leaf by its GL name,
/// `u[1].a`), -1 if the program has none.
fn uniform_location(l: &LinkedProgram, name: &str) -> i32 {
    let (base, index) = match name.strip_suffix(']').and_then(|n| n.rsplit_once('[')) {
        Some((b, i)) => match i.parse::<u32>() {
            Ok(i) => (b, i),
            Err(_) => return -1,
        },
        None => (name, 0),
    };
    let Some(u) = l.info.uniforms.iter().position(|u| u.gl_name == base) else { return -1 };
    if index >= l.info.uniforms[u].len || (index > 0 && !l.info.uniforms[u].is_array) {
        return -1;
    }
    l.locations.iter().position(|&(i, e)| i == u && e == index).map_or(-1, |p| p as i32)
}

/// Byte offset of scalar `c` of a uniform element at `base`: a matrix's columns (of `rows`
/// scalars each) are 16 bytes apart in std140; vectors are packed.
fn scalar_offset(base: usize, c: usize, rows: usize) -> usize {
    match c.checked_div(rows) {
        Some(col) => base + col * 16 + (c % rows) * 4,
        None => base + c * 4,
    }
}

/// Writes `vals` (elements of `shape`; matrices row by row where `transpose`) to `program`'s
/// uniform at `location`.
fn set_uniform(
    ctx: &mut Context,
    program: u32,
    location: i32,
    shape: Shape,
    transpose: bool,
    vals: Vals<'_>,
) -> GlResult {
    if location == -1 {
        return Ok(());
    }
    let p = ctx.objects.programs.get_mut(&program).ok_or(GlError::InvalidOperation)?;
    let l = p.linked.clone().ok_or(GlError::InvalidOperation)?;
    let &(ui, element) =
        usize::try_from(location).ok().and_then(|i| l.locations.get(i)).ok_or(GlError::InvalidOperation)?;
    let u = &l.info.uniforms[ui];
    let len = vals.len();
    let per = shape.n;
    if (shape.columns, shape.rows) != (u.ty.columns(), u.ty.rows()) || u.ty.components() != per {
        return Err(GlError::InvalidOperation);
    }
    let ok_kind = matches!(
        (&vals, u.ty.scalar()),
        (_, Scalar::Bool) | (Vals::F(_), Scalar::Float) | (Vals::I(_), Scalar::Int) | (Vals::U(_), Scalar::UInt)
    );
    if !ok_kind || !len.is_multiple_of(per) || len == 0 {
        return Err(if len == 0 { GlError::InvalidValue } else { GlError::InvalidOperation });
    }
    let count = len / per;
    if count > 1 && !u.is_array {
        return Err(GlError::InvalidOperation);
    }
    let count = count.min((u.len - element) as usize);
    if let Some(si) = u.sampler {
        let Vals::I(v) = vals else { return Err(GlError::InvalidOperation) };
        let v = &v[..count];
        if v.iter().any(|&unit| unit < 0 || unit as usize >= MAX_UNITS) {
            return Err(GlError::InvalidValue);
        }
        // A sampler array's elements are consecutive samplers.
        let first = si + element as usize;
        for (slot, &unit) in p.units.iter_mut().skip(first).zip(v) {
            *slot = unit as u32;
        }
        return Ok(());
    }
    for e in 0..count {
        let base = (u.offset + (element + e as u32) * u.stride) as usize;
        for c in 0..per {
            // Scalar c (column-major) comes from the values' row-major position when transposed.
            let from = match transpose {
                true => (c % shape.rows) * shape.columns + c / shape.rows,
                false => c,
            };
            let at = scalar_offset(base, c, shape.rows);
            if let Some(dst) = p.data.get_mut(at..at + 4) {
                dst.copy_from_slice(&vals.bytes(e * per + from, u.ty.scalar()));
            }
        }
    }
    Ok(())
}

/// `glUniformMatrix*fv`: ES 2.0 requires `transpose` to be false; ES 3.0 transposes.
fn set_matrix(ctx: &mut Context, program: u32, location: i32, transpose: bool, shape: Shape, v: &[f32]) -> GlResult {
    if transpose && !ctx.es3() {
        return Err(GlError::InvalidValue);
    }
    set_uniform(ctx, program, location, shape, transpose, Vals::F(v))
}

/// The program a `glProgramUniform*EXT` names: GL's usual error for a bad name.
fn named(ctx: &Context, program: u32) -> GlResult<u32> {
    match ctx.objects.programs.contains_key(&program) {
        true => Ok(program),
        false => Err(ctx.objects.shader_or_program_error(program)),
    }
}

/// The value at `location` of `program`: its kind, and each scalar's four bytes as stored (a
/// sampler's unit as an integer).
fn get_uniform(ctx: &Context, program: u32, location: i32) -> GlResult<(Scalar, Vec<[u8; 4]>)> {
    let p = ctx.objects.programs.get(&program).ok_or_else(|| ctx.objects.shader_or_program_error(program))?;
    let l = p.linked.as_ref().ok_or(GlError::InvalidOperation)?;
    let &(ui, element) =
        usize::try_from(location).ok().and_then(|i| l.locations.get(i)).ok_or(GlError::InvalidOperation)?;
    let u = &l.info.uniforms[ui];
    if let Some(si) = u.sampler {
        let unit = p.units.get(si + element as usize).ok_or(GlError::InvalidOperation)?;
        return Ok((Scalar::Int, vec![(*unit as i32).to_ne_bytes()]));
    }
    let base = (u.offset + element * u.stride) as usize;
    let words = (0..u.ty.components())
        .map(|c| {
            let at = scalar_offset(base, c, u.ty.rows());
            [p.data[at], p.data[at + 1], p.data[at + 2], p.data[at + 3]]
        })
        .collect();
    Ok((u.ty.scalar(), words))
}

/// A stored scalar of kind `scalar` as a float (what `glGetUniformfv` converts it to).
fn as_float(scalar: Scalar, b: [u8; 4]) -> f32 {
    match scalar {
        Scalar::Float => f32::from_ne_bytes(b),
        Scalar::UInt => u32::from_ne_bytes(b) as f32,
        Scalar::Int | Scalar::Bool => i32::from_ne_bytes(b) as f32,
    }
}

/// `glUniform{1,2,3,4}{f,i,ui}`, their `v` forms and `glUniformMatrix*fv` (writing the program
/// in use, or the bound pipeline's active program), and the `v` and matrix forms of
/// `glProgramUniform*EXT` (writing the program named): one body each, by shape and type.
macro_rules! uniform_setters {
    (
        scalars { $( $sgl:ident: $sn:literal, $sty:ty, $svals:ident ( $( $c:ident ),+ ); )* }
        vectors { $( $vgl:ident $( / $pvgl:ident )?: $vn:literal, $vty:ty, $vvals:ident; )* }
        matrices { $( $mgl:ident $( / $pmgl:ident )?: $mc:literal x $mr:literal; )* }
    ) => {
        #[allow(non_snake_case)]
        impl GlesExecutor {
            $( pub(super) fn $sgl(&mut self, ctx: &mut Context, location: i32, $( $c: $sty ),+) -> GlResult {
                let program = ctx.uniform_program();
                set_uniform(ctx, program, location, Shape::vector($sn), false, Vals::$svals(&[$( $c ),+]))
            } )*
            $( pub(super) fn $vgl(&mut self, ctx: &mut Context, location: i32, values: Slice<'_, $vty>) -> GlResult {
                let program = ctx.uniform_program();
                set_uniform(ctx, program, location, Shape::vector($vn), false, Vals::$vvals(&values.to_vec()))
            }
            $( pub(super) fn $pvgl(&mut self, ctx: &mut Context, program: u32, location: i32, values: Slice<'_, $vty>) -> GlResult {
                let program = named(ctx, program)?;
                set_uniform(ctx, program, location, Shape::vector($vn), false, Vals::$vvals(&values.to_vec()))
            } )? )*
            $( pub(super) fn $mgl(&mut self, ctx: &mut Context, location: i32, transpose: bool, values: Slice<'_, f32>) -> GlResult {
                let program = ctx.uniform_program();
                set_matrix(ctx, program, location, transpose, Shape::matrix($mc, $mr), &values.to_vec())
            }
            $( pub(super) fn $pmgl(&mut self, ctx: &mut Context, program: u32, location: i32, transpose: bool, values: Slice<'_, f32>) -> GlResult {
                let program = named(ctx, program)?;
                set_matrix(ctx, program, location, transpose, Shape::matrix($mc, $mr), &values.to_vec())
            } )? )*
        }
    };
}

uniform_setters! {
    scalars {
        glUniform1f: 1, f32, F(x);
        glUniform2f: 2, f32, F(x, y);
        glUniform3f: 3, f32, F(x, y, z);
        glUniform4f: 4, f32, F(x, y, z, w);
        glUniform1i: 1, i32, I(x);
        glUniform2i: 2, i32, I(x, y);
        glUniform3i: 3, i32, I(x, y, z);
        glUniform4i: 4, i32, I(x, y, z, w);
        glUniform1ui: 1, u32, U(x);
        glUniform2ui: 2, u32, U(x, y);
        glUniform3ui: 3, u32, U(x, y, z);
        glUniform4ui: 4, u32, U(x, y, z, w);
    }
    vectors {
        glUniform1fv / glProgramUniform1fvEXT: 1, f32, F;
        glUniform2fv / glProgramUniform2fvEXT: 2, f32, F;
        glUniform3fv / glProgramUniform3fvEXT: 3, f32, F;
        glUniform4fv / glProgramUniform4fvEXT: 4, f32, F;
        glUniform1iv / glProgramUniform1ivEXT: 1, i32, I;
        glUniform2iv / glProgramUniform2ivEXT: 2, i32, I;
        glUniform3iv / glProgramUniform3ivEXT: 3, i32, I;
        glUniform4iv / glProgramUniform4ivEXT: 4, i32, I;
        glUniform1uiv: 1, u32, U;
        glUniform2uiv: 2, u32, U;
        glUniform3uiv: 3, u32, U;
        glUniform4uiv: 4, u32, U;
    }
    matrices {
        glUniformMatrix2fv / glProgramUniformMatrix2fvEXT: 2 x 2;
        glUniformMatrix3fv / glProgramUniformMatrix3fvEXT: 3 x 3;
        glUniformMatrix4fv / glProgramUniformMatrix4fvEXT: 4 x 4;
        glUniformMatrix2x3fv: 2 x 3;
        glUniformMatrix3x2fv: 3 x 2;
        glUniformMatrix2x4fv: 2 x 4;
        glUniformMatrix4x2fv: 4 x 2;
        glUniformMatrix3x4fv: 3 x 4;
        glUniformMatrix4x3fv: 4 x 3;
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glGetUniformLocation(&mut self, ctx: &mut Context, program: u32, name: Text<'_>) -> i32 {
        let v = match ctx.objects.programs.get(&program) {
            Some(p) => match &p.linked {
                Some(l) => Ok(uniform_location(l, name.as_str())),
                None => Err(GlError::InvalidOperation),
            },
            None => Err(ctx.objects.shader_or_program_error(program)),
        };
        v.unwrap_or_else(|e| {
            ctx.record(e);
            -1
        })
    }

    pub(super) fn glGetUniformfv(&mut self, ctx: &mut Context, program: u32, location: i32) -> Vec<f32> {
        match get_uniform(ctx, program, location) {
            Ok((scalar, words)) => words.into_iter().map(|b| as_float(scalar, b)).collect(),
            Err(e) => {
                ctx.record(e);
                vec![]
            }
        }
    }

    pub(super) fn glGetUniformiv(&mut self, ctx: &mut Context, program: u32, location: i32) -> Vec<i32> {
        match get_uniform(ctx, program, location) {
            // A float uniform read as integers is rounded to the nearest, as GL converts (and
            // Mesa does); integer and boolean uniforms are whole already.
            Ok((Scalar::Float, words)) => words.into_iter().map(|b| f32::from_ne_bytes(b).round() as i32).collect(),
            Ok((_, words)) => words.into_iter().map(i32::from_ne_bytes).collect(),
            Err(e) => {
                ctx.record(e);
                vec![]
            }
        }
    }

    /// ES 3.0: a uniform's values as unsigned integers (floats rounded, as `glGetUniformiv`).
    pub(super) fn glGetUniformuiv(&mut self, ctx: &mut Context, program: u32, location: i32) -> Vec<u32> {
        match get_uniform(ctx, program, location) {
            Ok((Scalar::Float, words)) => words.into_iter().map(|b| f32::from_ne_bytes(b).round() as u32).collect(),
            Ok((_, words)) => words.into_iter().map(u32::from_ne_bytes).collect(),
            Err(e) => {
                ctx.record(e);
                vec![]
            }
        }
    }
}
