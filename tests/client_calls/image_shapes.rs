//! The one image path's order of checks, shape against shape: texture images of each shape
//! (a 2D image, a cube face, a 3D image) and their attachments, each call given two faults at
//! once, so that which error wins shows the order the path checks in (the texture, the target
//! named against the texture's, the slice, the level, the data's size), as Mesa orders them
//! for every dimension.

use super::*;

const TEXTURE_2D: u32 = 0x0DE1;
const TEXTURE_3D: u32 = 0x806F;
const CUBE_POSITIVE_X: u32 = 0x8515;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;
const DEPTH_COMPONENT: u32 = 0x1902;
const UNSIGNED_SHORT: u32 = 0x1403;
const FRAMEBUFFER: u32 = 0x8D40;
const COLOR_ATTACHMENT0: u32 = 0x8CE0;
const ASTC_4X4: u32 = 0x93B0;
/// A name no call made.
const NO_TEXTURE: u32 = 4242;

/// The sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    // SAFETY: GL calls with a current context; every pointer holds at least the bytes the call
    // reads (a null pointer makes a blank image).
    unsafe {
        let mut names = [0u32; 4];
        (gl.gen_textures)(4, names.as_mut_ptr());
        let [flat, volume, never_bound, cube] = names;
        (gl.bind_texture)(TEXTURE_2D, flat);
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, std::ptr::null());
        (gl.bind_texture)(TEXTURE_3D, volume);
        (gl.tex_image_3d)(TEXTURE_3D, 0, RGBA, 4, 4, 4, 0, RGBA, UNSIGNED_BYTE, std::ptr::null());
        (gl.bind_texture)(0x8513, cube);
        r.note("images of each shape");
        // A 3D image of a depth format, and one whose level is past the last.
        (gl.tex_image_3d)(
            TEXTURE_3D,
            0,
            DEPTH_COMPONENT,
            4,
            4,
            4,
            0,
            DEPTH_COMPONENT,
            UNSIGNED_SHORT,
            std::ptr::null(),
        );
        r.note("a 3D depth image");
        (gl.tex_image_3d)(TEXTURE_3D, 12, RGBA, 1, 1, 1, 0, RGBA, UNSIGNED_BYTE, std::ptr::null());
        r.note("a 3D level past the last");

        let mut fb = 0;
        (gl.gen_framebuffers)(1, &mut fb);
        (gl.bind_framebuffer)(FRAMEBUFFER, fb);
        let attach_2d = |textarget, texture, level| {
            (gl.framebuffer_texture_2d)(FRAMEBUFFER, COLOR_ATTACHMENT0, textarget, texture, level);
        };
        let attach_3d = |textarget, texture, level, z| {
            (gl.framebuffer_texture_3d)(FRAMEBUFFER, COLOR_ATTACHMENT0, textarget, texture, level, z);
        };
        for (what, textarget, texture, level) in [
            ("2D: detach naming an unknown target", 0x1234, 0, 0),
            ("2D: detach at a bad level", TEXTURE_2D, 0, -1),
            ("2D: no such texture, a bad level", TEXTURE_2D, NO_TEXTURE, 99),
            ("2D: no such texture, an unknown target", 0x1234, NO_TEXTURE, 0),
            ("2D: an unknown target, a bad level", 0x1234, flat, 99),
            ("2D: a 3D texture, a bad level", TEXTURE_2D, volume, 99),
            ("2D: a 2D texture as a cube face", CUBE_POSITIVE_X, flat, 0),
            ("2D: a name never bound", TEXTURE_2D, never_bound, 0),
            ("2D: a cube map as a 2D image", TEXTURE_2D, cube, 0),
            ("2D: the 3D target", TEXTURE_3D, volume, 0),
        ] {
            attach_2d(textarget, texture, level);
            r.note(what);
        }
        for (what, textarget, texture, level, z) in [
            ("3D: detach naming an unknown target", 0x1234, 0, 0, 0),
            ("3D: detach at a bad slice", TEXTURE_3D, 0, 0, -1),
            ("3D: no such texture, a bad slice", TEXTURE_3D, NO_TEXTURE, 0, -1),
            ("3D: no such texture, an unknown target", 0x1234, NO_TEXTURE, 0, 0),
            ("3D: an unknown target, a bad slice", 0x1234, volume, 0, 9999),
            ("3D: a bad slice and a bad level", TEXTURE_3D, volume, 99, 9999),
            ("3D: a 2D texture, a bad level", TEXTURE_3D, flat, 99, 0),
            ("3D: a name never bound", TEXTURE_3D, never_bound, 0, 0),
            ("3D: a slice of the 3D image", TEXTURE_3D, volume, 0, 3),
        ] {
            attach_3d(textarget, texture, level, z);
            r.note(what);
        }
        (gl.bind_framebuffer)(FRAMEBUFFER, 0);

        // Compressed updates whose data does not fit their box, with another fault.
        let blocks = [0u8; 64];
        (gl.bind_texture)(TEXTURE_2D, flat);
        (gl.compressed_tex_sub_image_2d)(TEXTURE_2D, 0, 0, 0, -4, 4, ASTC_4X4, 16, blocks.as_ptr().cast());
        r.note("2D: a negative width, data for none, an uncompressed image");
        (gl.compressed_tex_sub_image_2d)(TEXTURE_2D, 7, 0, 0, 4, 4, ASTC_4X4, 8, blocks.as_ptr().cast());
        r.note("2D: an undefined level, data short of the box");
        (gl.bind_texture)(TEXTURE_3D, volume);
        (gl.compressed_tex_sub_image_3d)(TEXTURE_3D, 0, 0, 0, 0, 4, 4, -1, ASTC_4X4, 16, blocks.as_ptr().cast());
        r.note("3D: a negative depth, data for none, an uncompressed image");
        (gl.compressed_tex_sub_image_3d)(TEXTURE_3D, 7, 0, 0, 0, 4, 4, 1, ASTC_4X4, 8, blocks.as_ptr().cast());
        r.note("3D: an undefined level, data short of the box");
        (gl.delete_textures)(4, names.as_ptr());
    }
}
