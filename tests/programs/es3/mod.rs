//! OpenGL ES 3.0 programs, run by `gles3_oracle.rs` in ES 3.0 contexts through both Strata
//! (started with `--es3`) and Mesa held to ES 3.0.

use super::{Case, DEFAULT};

mod arrays;
mod attrib_types;
mod blit;
mod blocks;
mod color_buffer_float;
mod depth_mipmaps;
mod depth_textures;
mod divisors;
mod etc2;
mod expressions;
mod float_textures;
mod int_attributes;
mod int_samplers;
mod integers;
mod language;
mod matrix_inputs;
mod multisample;
mod packed_floats;
mod renderbuffers;
mod restart;
mod samplers;
mod shadow;
mod snorm;
mod srgb;
mod structs;
mod swizzles;
mod tex_storage;
mod uniforms;
mod xfb;

/// Every ES 3.0 program.
pub fn all() -> Vec<Case> {
    let c = |name, run| Case { name, run, tol: DEFAULT, expects_error: false };
    vec![
        c("es3_interface", language::interface),
        c("es3_integers", language::integers),
        c("es3_builtins", language::builtins),
        c("es3_lookups", language::lookups),
        c("es3_vertex_ids", language::vertex_ids),
        c("es3_outputs", language::outputs),
        c("es3_frag_depth", language::frag_depth),
        c("es3_expressions", expressions::expressions),
        c("es3_uniforms", uniforms::uniforms),
        c("es3_uniform_blocks", blocks::uniform_blocks),
        c("es3_uniform_block_arrays", blocks::uniform_block_arrays),
        c("es3_uniform_block_types", blocks::uniform_block_types),
        c("es3_divisors", divisors::divisors),
        c("es3_int_attributes", int_attributes::int_attributes),
        c("es3_attrib_types", attrib_types::attrib_types),
        c("es3_primitive_restart", restart::primitive_restart),
        c("es3_provoking_vertex", restart::provoking_vertex),
        c("es3_transform_feedback", xfb::transform_feedback),
        c("es3_tex_storage", tex_storage::tex_storage),
        c("es3_samplers", samplers::samplers),
        c("es3_texture_arrays", arrays::texture_arrays),
        c("es3_float_textures", float_textures::float_textures),
        c("es3_srgb", srgb::srgb),
        c("es3_blit", blit::blit),
        c("es3_snorm", snorm::snorm),
        c("es3_renderbuffers", renderbuffers::renderbuffers),
        c("es3_depth_textures", depth_textures::depth_textures),
        c("es3_etc2", etc2::etc2),
        c("es3_swizzles", swizzles::swizzles),
        c("es3_shadow", shadow::shadow),
        c("es3_depth_mipmaps", depth_mipmaps::depth_mipmaps),
        c("es3_filter_choice", super::filter_choice::filter_choice_es3),
        c("es3_matrix_inputs", matrix_inputs::matrix_inputs),
        c("es3_integer_formats", integers::integers),
        c("es3_int_samplers", int_samplers::int_samplers),
        c("es3_packed_floats", packed_floats::packed_floats),
        c("es3_struct_uniforms", structs::struct_uniforms),
        c("es3_block_structs", structs::block_structs),
        c("es3_color_buffer_float", color_buffer_float::color_buffer_float),
        c("es3_color_buffer_float_images", color_buffer_float::color_buffer_float_images),
        c("es3_multisample", multisample::multisample),
    ]
}
