//! `GL_EXT_texture_border_clamp` / `GL_OES_texture_border_clamp` through the C entry points:
//! the colour set as floats and as normalised integers and read back both ways, and the
//! integer forms (EXT and OES names), which ES 2.0's lack of integer textures makes errors,
//! leaving what they would write untouched.

use super::*;

const BORDER_COLOR: u32 = 0x1004;
const TEXTURE_2D: u32 = 0x0DE1;

/// The integer forms: setters and getters, by name.
type Setter = unsafe extern "C" fn(u32, u32, *const i32);
type Getter = unsafe extern "C" fn(u32, u32, *mut i32);

/// The border clamp sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    // SAFETY: GL calls on the current context; every pointer has room for four values.
    unsafe {
        let mut t = 0;
        (gl.gen_textures)(1, &mut t);
        (gl.bind_texture)(TEXTURE_2D, t);
        (gl.tex_parameterfv)(TEXTURE_2D, BORDER_COLOR, [0.25f32, -0.5, 1.5, 0.75].as_ptr());
        r.note("floats");
        let mut f = [9.0f32; 4];
        (gl.get_tex_parameterfv)(TEXTURE_2D, BORDER_COLOR, f.as_mut_ptr());
        r.note(&format!("read as floats {f:?}"));
        let mut i = [9i32; 4];
        (gl.get_tex_parameteriv)(TEXTURE_2D, BORDER_COLOR, i.as_mut_ptr());
        r.note(&format!("read as integers {i:?}"));
        (gl.tex_parameteriv)(TEXTURE_2D, BORDER_COLOR, [0x7fff_ffff, 0, 0x3fff_ffff, -0x7fff_ffff].as_ptr());
        r.note("normalised integers");
        (gl.get_tex_parameterfv)(TEXTURE_2D, BORDER_COLOR, f.as_mut_ptr());
        r.note(&format!("read as floats {f:?}"));
        let setters: [(&str, Setter); 4] = [
            ("glTexParameterIivEXT", gl.tex_parameter_iiv_ext),
            ("glTexParameterIuivEXT", gl.tex_parameter_iuiv_ext),
            ("glTexParameterIivOES", gl.tex_parameter_iiv_oes),
            ("glTexParameterIuivOES", gl.tex_parameter_iuiv_oes),
        ];
        for (name, set) in setters {
            set(TEXTURE_2D, BORDER_COLOR, [1, 2, 3, 4].as_ptr());
            r.note(name);
        }
        let getters: [(&str, Getter); 4] = [
            ("glGetTexParameterIivEXT", gl.get_tex_parameter_iiv_ext),
            ("glGetTexParameterIuivEXT", gl.get_tex_parameter_iuiv_ext),
            ("glGetTexParameterIivOES", gl.get_tex_parameter_iiv_oes),
            ("glGetTexParameterIuivOES", gl.get_tex_parameter_iuiv_oes),
        ];
        for (name, get) in getters {
            let mut v = [7i32; 4];
            get(TEXTURE_2D, BORDER_COLOR, v.as_mut_ptr());
            r.note(&format!("{name} leaves {v:?}"));
        }
        (gl.get_tex_parameterfv)(TEXTURE_2D, BORDER_COLOR, f.as_mut_ptr());
        r.note(&format!("still {f:?}"));
        (gl.delete_textures)(1, &t);
    }
}
