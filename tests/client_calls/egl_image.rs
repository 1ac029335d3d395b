//! EGLImages (`EGL_KHR_image_base`, `EGL_KHR_gl_texture_2D_image`,
//! `EGL_KHR_gl_texture_cubemap_image`, `EGL_KHR_gl_renderbuffer_image`) and the textures and
//! renderbuffers made from them (`GL_OES_EGL_image`, `GL_OES_EGL_image_external`), through the
//! C entry points: images of a texture's levels and of a renderbuffer, each drawn from a
//! second context (which shares no objects with the first); writes through a sibling seen by
//! the source and the other way; a respecified sibling orphaned; an image outliving its
//! source; external textures' state, errors and `samplerExternalOES`; reads of a level above 0
//! and of a cube face through a framebuffer; and the errors of every call.

use super::*;

const TEXTURE_2D: u32 = 0x0DE1;
const TEXTURE_CUBE_MAP: u32 = 0x8513;
const CUBE_POSITIVE_X: u32 = 0x8515;
const TEXTURE_EXTERNAL: u32 = 0x8D65;
const MIN_FILTER: u32 = 0x2801;
const MAG_FILTER: u32 = 0x2800;
const WRAP_S: u32 = 0x2802;
const WRAP_T: u32 = 0x2803;
const NEAREST: i32 = 0x2600;
const REPEAT: i32 = 0x2901;
const LINEAR_MIPMAP_LINEAR: i32 = 0x2703;
const REQUIRED_UNITS: u32 = 0x8D68;
const BINDING_EXTERNAL: u32 = 0x8D67;
const RENDERBUFFER: u32 = 0x8D41;
const FRAMEBUFFER: u32 = 0x8D40;
const COLOR_ATTACHMENT0: u32 = 0x8CE0;
const RGBA: u32 = 0x1908;
const RGB565: u32 = 0x8D62;
const UNSIGNED_BYTE: u32 = 0x1401;
const FLOAT: u32 = 0x1406;
const TRIANGLE_STRIP: u32 = 0x0005;
const SCISSOR_TEST: u32 = 0x0C11;

const EGL_GL_TEXTURE_2D: u32 = 0x30B1;
const EGL_GL_CUBE_POSITIVE_Y: u32 = 0x30B5;
const EGL_GL_RENDERBUFFER: u32 = 0x30B9;
const EGL_TEXTURE_LEVEL: i32 = 0x30BC;
const EGL_IMAGE_PRESERVED: i32 = 0x30D2;

const FS_EXTERNAL: &str = "#extension GL_OES_EGL_image_external : require
    precision mediump float; uniform samplerExternalOES s; varying vec2 uv;
    void main() { gl_FragColor = texture2DProj(s, vec3(uv, 1.0)) * 0.5 + texture2D(s, uv) * 0.5; }";
const FS_EXTERNAL_UNENABLED: &str = "precision mediump float; uniform samplerExternalOES s; varying vec2 uv;
    void main() { gl_FragColor = texture2D(s, uv); }";

/// A full-window strip.
const QUAD: [f32; 8] = [-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0];

/// `w`×`h` RGBA texels, each a function of its position and `seed`.
fn texels(w: usize, h: usize, seed: u8) -> Vec<u8> {
    (0..w * h).flat_map(|i| [(i * 37) as u8 ^ seed, (i * 11 + 60) as u8, seed, 255]).collect()
}

impl Run {
    /// Creates an EGLImage of `ctx`'s `buffer`; logs whether it was made and EGL's error.
    fn image(&mut self, what: &str, ctx: Ptr, target: u32, buffer: u32, attribs: &[i32]) -> Ptr {
        let list: Vec<i32> = attribs.iter().chain(&[NONE]).copied().collect();
        // SAFETY: EGL_KHR_image_base's prototype; a NONE-terminated list.
        let (image, e) = unsafe {
            let image =
                (self.gl.egl_create_image)(self.egl.display, ctx, target, buffer as usize as Ptr, list.as_ptr());
            (image, (self.gl.egl_get_error)())
        };
        self.log.push(format!("image of {what}: made {}, EGL error {e:#x}", !image.is_null()));
        image
    }

    /// A new texture bound to `target`, filtered nearest; its name.
    fn texture(&mut self, target: u32) -> u32 {
        let gl = self.gl;
        let mut t = 0;
        // SAFETY: a context is current; room for one name.
        unsafe {
            (gl.gen_textures)(1, &mut t);
            (gl.bind_texture)(target, t);
            (gl.tex_parameteri)(target, MIN_FILTER, NEAREST);
            (gl.tex_parameteri)(target, MAG_FILTER, NEAREST);
        }
        t
    }

    /// Draws the window-filling quad with the program in use, and logs a grid of its pixels.
    fn sampled(&mut self, what: &str) {
        let gl = self.gl;
        let mut px = [0u8; 16 * 16 * 4];
        // SAFETY: a context is current; the vertex array lives through the draw; room for the
        // surface's pixels.
        unsafe {
            (gl.bind_framebuffer)(FRAMEBUFFER, 0);
            (gl.viewport)(0, 0, 16, 16);
            (gl.clear_color)(0.5, 0.5, 0.5, 0.5);
            (gl.clear)(0x4000);
            (gl.bind_buffer)(0x8892, 0);
            (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, QUAD.as_ptr().cast());
            (gl.enable_vertex_attrib_array)(0);
            (gl.draw_arrays)(TRIANGLE_STRIP, 0, 4);
            self.note(what);
            (gl.read_pixels)(0, 0, 16, 16, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
        }
        self.log.push(format!("{what}: pixels {}", grid(&px, 16)));
    }

    /// Reads the whole `w`×`h` colour attachment of the bound framebuffer and logs a grid.
    fn read_back(&mut self, what: &str, w: i32, h: i32) {
        let mut px = vec![0u8; (w * h * 4) as usize];
        // SAFETY: a context is current; room for the pixels.
        unsafe { (self.gl.read_pixels)(0, 0, w, h, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast()) };
        self.note(what);
        self.log.push(format!("{what}: pixels {}", grid(&px, w as usize)));
    }

    /// Logs an integer state of `target`'s texture.
    fn tex_param(&mut self, what: &str, target: u32, pname: u32) {
        let mut v = -1;
        // SAFETY: a context is current; room for one value.
        unsafe { (self.gl.get_tex_parameteriv)(target, pname, &mut v) };
        self.note(&format!("{what} = {v:#x}"));
    }
}

/// Every third pixel of every third row of `width`-wide RGBA rows, as hex.
fn grid(px: &[u8], width: usize) -> String {
    let rows = px.len() / 4 / width;
    (0..rows)
        .step_by(3)
        .flat_map(|y| (0..width).step_by(3).map(move |x| (y * width + x) * 4))
        .map(|i| format!("{:02x}{:02x}{:02x}{:02x}", px[i], px[i + 1], px[i + 2], px[i + 3]))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The EGLImage sequence.
pub fn sequence(r: &mut Run) {
    let (gl, egl) = (r.gl, r.egl);
    // SAFETY: EGL and GL calls with this run's handles; every pointer is valid for the call.
    unsafe {
        let ctx1 = egl.context;
        // Texture Z: one 8×8 level; A: an 8×8 mip chain; D: its first two levels only
        // (incomplete); B: one 4×4 level; C: a 4×4 cube. (Mesa's image of level 0 of a
        // mipmapped texture reads as zeros, so level 0 is taken from Z.)
        let z = r.texture(TEXTURE_2D);
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 8, 8, 0, RGBA, UNSIGNED_BYTE, texels(8, 8, 9).as_ptr().cast());
        let a = r.texture(TEXTURE_2D);
        let d = r.texture(TEXTURE_2D);
        let upload = |t: u32, level: usize, size: usize, data: &[u8]| {
            let size = size as i32;
            (gl.bind_texture)(TEXTURE_2D, t);
            let (level, format) = (level as i32, RGBA as i32);
            (gl.tex_image_2d)(TEXTURE_2D, level, format, size, size, 0, RGBA, UNSIGNED_BYTE, data.as_ptr().cast());
        };
        for (level, size) in [8, 4, 2, 1].into_iter().enumerate() {
            let data = texels(size, size, 1 + level as u8);
            upload(a, level, size, &data);
            if level < 2 {
                upload(d, level, size, &data);
            }
        }
        let b = r.texture(TEXTURE_2D);
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, texels(4, 4, 3).as_ptr().cast());
        let c = r.texture(TEXTURE_CUBE_MAP);
        for face in 0..6 {
            let data = texels(4, 4, 40 + face as u8);
            (gl.tex_image_2d)(
                CUBE_POSITIVE_X + face,
                0,
                RGBA as i32,
                4,
                4,
                0,
                RGBA,
                UNSIGNED_BYTE,
                data.as_ptr().cast(),
            );
        }
        // Renderbuffers: one RGB565 cleared to a colour, one without storage.
        let mut rbs = [0u32; 3];
        (gl.gen_renderbuffers)(3, rbs.as_mut_ptr());
        (gl.bind_renderbuffer)(RENDERBUFFER, rbs[0]);
        (gl.renderbuffer_storage)(RENDERBUFFER, RGB565, 4, 4);
        let mut fbs = [0u32; 2];
        (gl.gen_framebuffers)(2, fbs.as_mut_ptr());
        (gl.bind_framebuffer)(FRAMEBUFFER, fbs[0]);
        (gl.framebuffer_renderbuffer)(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, rbs[0]);
        // A colour RGB565 holds exactly.
        (gl.clear_color)(1.0, 0.0, 1.0, 1.0);
        (gl.clear)(0x4000);
        (gl.bind_framebuffer)(FRAMEBUFFER, 0);
        r.note("sources");

        // Images, and the errors of eglCreateImageKHR.
        let i0 = r.image("Z", ctx1, EGL_GL_TEXTURE_2D, z, &[]);
        let i1 = r.image(
            "A level 1, preserved",
            ctx1,
            EGL_GL_TEXTURE_2D,
            a,
            &[EGL_TEXTURE_LEVEL, 1, EGL_IMAGE_PRESERVED, 1],
        );
        let i2 = r.image("C face +Y", ctx1, EGL_GL_CUBE_POSITIVE_Y, c, &[]);
        let i3 = r.image("the RGB565 renderbuffer", ctx1, EGL_GL_RENDERBUFFER, rbs[0], &[]);
        // (Mesa gives a second image of the same level without EGL_BAD_ACCESS, and then
        // neither shares the texture's contents: not compared.)
        r.image("B level 1 (undefined)", ctx1, EGL_GL_TEXTURE_2D, b, &[EGL_TEXTURE_LEVEL, 1]);
        r.image("D level 1 (D is incomplete)", ctx1, EGL_GL_TEXTURE_2D, d, &[EGL_TEXTURE_LEVEL, 1]);
        r.image("texture 0", ctx1, EGL_GL_TEXTURE_2D, 0, &[]);
        r.image("texture 999 (no such)", ctx1, EGL_GL_TEXTURE_2D, 999, &[]);
        r.image("a bad target", ctx1, 0x1234, a, &[]);
        r.image("an unknown attribute", ctx1, EGL_GL_TEXTURE_2D, b, &[0x1234, 1]);
        r.image("a cube face of a 2D texture", ctx1, EGL_GL_CUBE_POSITIVE_Y, a, &[]);
        r.image("a 2D image of a cube texture", ctx1, EGL_GL_TEXTURE_2D, c, &[]);
        r.image("a renderbuffer without storage", ctx1, EGL_GL_RENDERBUFFER, rbs[1], &[]);
        r.image("renderbuffer 0", ctx1, EGL_GL_RENDERBUFFER, 0, &[]);

        // A second context, sharing nothing: its names do not reach the first's objects.
        let attribs = [0x3098, 2, NONE];
        let ctx2 = (gl.egl_create_context)(egl.display, egl.config, std::ptr::null_mut(), attribs.as_ptr());
        r.image("A in the second context", ctx2, EGL_GL_TEXTURE_2D, a, &[]);
        (gl.egl_make_current)(egl.display, egl.surface, egl.surface, ctx2);
        let p2d = r.program(TEXTURED_VS, TEXTURED_FS);
        let t0 = r.texture(TEXTURE_2D);
        (gl.egl_image_target_texture)(TEXTURE_2D, i0);
        r.note("Z as a texture of the second context");
        r.sampled("Z drawn");
        // Mesa takes a cube face's image into a renderbuffer, not into a texture.
        let _t2 = r.texture(TEXTURE_2D);
        (gl.egl_image_target_texture)(TEXTURE_2D, i2);
        r.note("C face +Y as a texture");
        let mut rb_face = 0;
        (gl.gen_renderbuffers)(1, &mut rb_face);
        (gl.bind_renderbuffer)(RENDERBUFFER, rb_face);
        (gl.egl_image_target_renderbuffer)(RENDERBUFFER, i2);
        r.note("C face +Y as a renderbuffer");
        let mut fb_face = 0;
        (gl.gen_framebuffers)(1, &mut fb_face);
        (gl.bind_framebuffer)(FRAMEBUFFER, fb_face);
        (gl.framebuffer_renderbuffer)(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, rb_face);
        r.read_back("C face +Y through its renderbuffer", 4, 4);
        let _t3 = r.texture(TEXTURE_2D);
        (gl.egl_image_target_texture)(TEXTURE_2D, i3);
        r.sampled("the renderbuffer drawn");

        // External textures: their state and errors, and samplerExternalOES.
        let mut e = 0;
        (gl.gen_textures)(1, &mut e);
        (gl.bind_texture)(TEXTURE_EXTERNAL, e);
        r.tex_param("fresh external min filter", TEXTURE_EXTERNAL, MIN_FILTER);
        r.tex_param("external wrap s", TEXTURE_EXTERNAL, WRAP_S);
        r.tex_param("external wrap t", TEXTURE_EXTERNAL, WRAP_T);
        (gl.tex_parameteri)(TEXTURE_EXTERNAL, MIN_FILTER, NEAREST);
        (gl.tex_parameteri)(TEXTURE_EXTERNAL, MAG_FILTER, NEAREST);
        r.tex_param("required units", TEXTURE_EXTERNAL, REQUIRED_UNITS);
        r.tex_param("required units of a 2D texture", TEXTURE_2D, REQUIRED_UNITS);
        let mut v = -1;
        (gl.get_integerv)(BINDING_EXTERNAL, &mut v);
        r.note(&format!("external binding is the texture: {}", v == e as i32));
        (gl.tex_parameteri)(TEXTURE_EXTERNAL, MIN_FILTER, LINEAR_MIPMAP_LINEAR);
        r.note("external min filter mipmapped");
        (gl.tex_parameteri)(TEXTURE_EXTERNAL, WRAP_S, REPEAT);
        r.note("external wrap repeat");
        (gl.tex_parameteri)(TEXTURE_EXTERNAL, WRAP_T, 0x8370);
        r.note("external wrap mirrored");
        (gl.generate_mipmap)(TEXTURE_EXTERNAL);
        r.note("external mipmaps");
        (gl.tex_image_2d)(
            TEXTURE_EXTERNAL,
            0,
            RGBA as i32,
            4,
            4,
            0,
            RGBA,
            UNSIGNED_BYTE,
            texels(4, 4, 5).as_ptr().cast(),
        );
        r.note("an upload to an external texture");
        (gl.bind_texture)(TEXTURE_2D, e);
        r.note("the external texture bound as 2D");
        (gl.bind_texture)(TEXTURE_EXTERNAL, t0);
        r.note("a 2D texture bound as external");
        (gl.bind_texture)(TEXTURE_EXTERNAL, e);
        (gl.egl_image_target_texture)(TEXTURE_EXTERNAL, i1);
        r.note("A level 1 as an external texture");
        let pe = r.program(TEXTURED_VS, FS_EXTERNAL);
        let mut status = -1;
        (gl.get_programiv)(pe, 0x8B82, &mut status);
        r.note(&format!("samplerExternalOES program linked: {status}"));
        r.sampled("A level 1 drawn through samplerExternalOES");
        (gl.tex_parameteri)(TEXTURE_EXTERNAL, MIN_FILTER, 0x2601);
        (gl.tex_parameteri)(TEXTURE_EXTERNAL, MAG_FILTER, 0x2601);
        r.sampled("filtered");
        let unenabled = (gl.create_shader)(0x8B30);
        let src = CString::new(FS_EXTERNAL_UNENABLED).expect("source");
        (gl.shader_source)(unenabled, 1, &src.as_ptr(), std::ptr::null());
        (gl.compile_shader)(unenabled);
        (gl.get_shaderiv)(unenabled, 0x8B81, &mut status);
        r.note(&format!("samplerExternalOES without the extension compiles: {status}"));

        // Errors of the GL calls.
        (gl.bind_texture)(TEXTURE_2D, t0);
        (gl.egl_image_target_texture)(TEXTURE_2D, std::ptr::null_mut());
        r.note("a null image");
        (gl.egl_image_target_texture)(0x1234, i0);
        r.note("a bad target");
        (gl.egl_image_target_texture)(TEXTURE_CUBE_MAP, i0);
        r.note("the cube map target");
        (gl.egl_image_target_renderbuffer)(0x1234, i0);
        r.note("a bad renderbuffer target");
        (gl.bind_renderbuffer)(RENDERBUFFER, 0);
        (gl.egl_image_target_renderbuffer)(RENDERBUFFER, i0);
        r.note("no renderbuffer bound");

        // A renderbuffer of Z, cleared in part: the first context sees it in Z.
        let mut rb2 = 0;
        (gl.gen_renderbuffers)(1, &mut rb2);
        (gl.bind_renderbuffer)(RENDERBUFFER, rb2);
        (gl.egl_image_target_renderbuffer)(RENDERBUFFER, i0);
        r.note("Z as a renderbuffer");
        let mut w = -1;
        (gl.get_renderbuffer_parameteriv)(RENDERBUFFER, 0x8D42, &mut w);
        r.note(&format!("its width {w}"));
        let mut fb2 = 0;
        (gl.gen_framebuffers)(1, &mut fb2);
        (gl.bind_framebuffer)(FRAMEBUFFER, fb2);
        (gl.framebuffer_renderbuffer)(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, rb2);
        let status = (gl.check_framebuffer_status)(FRAMEBUFFER);
        r.note(&format!("its framebuffer status {status:#x}"));
        (gl.enable)(SCISSOR_TEST);
        (gl.scissor)(2, 2, 3, 4);
        (gl.clear_color)(0.0, 0.0, 1.0, 1.0);
        (gl.clear)(0x4000);
        (gl.disable)(SCISSOR_TEST);
        r.read_back("the renderbuffer after a scissored clear", 8, 8);
        // An upload through the second context's texture of Z.
        (gl.bind_texture)(TEXTURE_2D, t0);
        (gl.tex_sub_image_2d)(TEXTURE_2D, 0, 5, 5, 2, 2, RGBA, UNSIGNED_BYTE, texels(2, 2, 200).as_ptr().cast());
        r.note("an upload through the second context's texture");
        // (Mesa writes an upload through a texture of A level 1 somewhere other than A level 1:
        // not compared.)
        (gl.finish)();

        // The first context reads A's levels through framebuffer attachments.
        (gl.egl_make_current)(egl.display, egl.surface, egl.surface, ctx1);
        (gl.bind_framebuffer)(FRAMEBUFFER, fbs[1]);
        (gl.framebuffer_texture_2d)(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, z, 0);
        r.read_back("Z in the first context", 8, 8);
        (gl.framebuffer_texture_2d)(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, a, 1);
        r.read_back("A level 1 read through a framebuffer", 4, 4);
        (gl.framebuffer_texture_2d)(FRAMEBUFFER, COLOR_ATTACHMENT0, CUBE_POSITIVE_X + 2, c, 0);
        r.read_back("C face +Y read through a framebuffer", 4, 4);
        // The first context writes A level 1; the second samples it through its external texture.
        (gl.bind_texture)(TEXTURE_2D, a);
        (gl.tex_sub_image_2d)(TEXTURE_2D, 1, 0, 0, 2, 2, RGBA, UNSIGNED_BYTE, texels(2, 2, 99).as_ptr().cast());
        (gl.finish)();
        (gl.egl_make_current)(egl.display, egl.surface, egl.surface, ctx2);
        (gl.use_program)(pe);
        (gl.bind_texture)(TEXTURE_EXTERNAL, e);
        (gl.tex_parameteri)(TEXTURE_EXTERNAL, MIN_FILTER, NEAREST);
        (gl.tex_parameteri)(TEXTURE_EXTERNAL, MAG_FILTER, NEAREST);
        r.sampled("A level 1 after the first context's upload");

        // Respecifying the second context's texture orphans it: A keeps its contents.
        (gl.use_program)(p2d);
        (gl.bind_texture)(TEXTURE_2D, t0);
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 8, 8, 0, RGBA, UNSIGNED_BYTE, texels(8, 8, 77).as_ptr().cast());
        r.sampled("the respecified texture");
        (gl.finish)();
        (gl.egl_make_current)(egl.display, egl.surface, egl.surface, ctx1);
        (gl.bind_framebuffer)(FRAMEBUFFER, fbs[1]);
        (gl.framebuffer_texture_2d)(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, z, 0);
        r.read_back("Z after the sibling was respecified", 8, 8);
        (gl.bind_framebuffer)(FRAMEBUFFER, 0);

        // An image outlives its source and its own destruction in its siblings.
        let ib = r.image("B", ctx1, EGL_GL_TEXTURE_2D, b, &[]);
        (gl.delete_textures)(1, &b);
        r.image("B after it was deleted", ctx1, EGL_GL_TEXTURE_2D, b, &[]);
        (gl.egl_make_current)(egl.display, egl.surface, egl.surface, ctx2);
        let _tb = r.texture(TEXTURE_2D);
        (gl.egl_image_target_texture)(TEXTURE_2D, ib);
        r.note("deleted B's image as a texture");
        let destroyed = (gl.egl_destroy_image)(egl.display, ib);
        r.log.push(format!("destroyed: {destroyed}, EGL error {:#x}", (gl.egl_get_error)()));
        r.sampled("deleted B's image drawn after the image was destroyed");
        let again = (gl.egl_destroy_image)(egl.display, ib);
        r.log.push(format!("destroyed again: {again}, EGL error {:#x}", (gl.egl_get_error)()));
        let null = (gl.egl_destroy_image)(egl.display, std::ptr::null_mut());
        r.log.push(format!("destroyed null: {null}, EGL error {:#x}", (gl.egl_get_error)()));
        for i in [i0, i1, i2, i3] {
            (gl.egl_destroy_image)(egl.display, i);
        }
        (gl.egl_make_current)(egl.display, egl.surface, egl.surface, egl.context);
        (gl.egl_destroy_context)(egl.display, ctx2);
        r.note("done");
    }
}
