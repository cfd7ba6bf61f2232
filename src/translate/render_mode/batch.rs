//! The vertex pipeline's side of selection and feedback: a batch of vertices about to enter
//! the frame (`Context::emit_batch`) is converted to a [`CpuPrimitive`] in the program's vertex
//! order, with the rasterization state that decides what selection and feedback see (culling,
//! front face, polygon mode, shade model; section 3.5) and the enabled user clip planes in
//! eye coordinates (section 2.11.2).

use super::{CpuPrimitive, CpuVertex, RasterRules};
use crate::frame::state::ShadeModel;
use crate::translate::Context;
use glam::Vec4;

use crate::translate::enums::{FACE, POLYGON_MODE, WINDING};
use crate::translate::gl::GLenum;
use crate::translate::immediate::Batch;

impl Context {
    /// Hands the primitive `mode` made of `batch` (vertex `order[k]`, or `k`, is its `k`-th
    /// vertex) to selection or feedback. Returns `true` when it was consumed (selection or
    /// feedback mode: nothing may be drawn), `false` in `GL_RENDER` mode.
    pub(crate) fn render_mode_batch(&mut self, mode: GLenum, batch: &Batch, order: Option<&[u32]>) -> bool {
        if !self.render_mode_active() {
            return false;
        }
        let v = &batch.vertices;
        let current = *self.immediate.current();
        // Feedback reports lit colours and generated texture coordinates (section 5.3), so each
        // vertex goes through the CPU vertex stage; the pipeline applies the texture matrix.
        let vertex = |i: u32| {
            let k = i as usize;
            let position = *v.position.get(k)?;
            let mut attribs = current;
            attribs.color = v.color.get(k).unwrap_or(current.color);
            attribs.secondary_color = v.secondary_color.get(k).unwrap_or(current.secondary_color);
            attribs.normal = v.normal.get(k).unwrap_or(current.normal);
            for (unit, t) in v.texcoords.iter().enumerate().take(attribs.texcoords.len()) {
                attribs.texcoords[unit] = t.get(k).unwrap_or(current.texcoords[unit]);
            }
            let obj = Vec4::from_array(position);
            let fixed = self.fixed_vertex(obj, &attribs);
            let normal = self.eye_normal(attribs.normal);
            Some(CpuVertex {
                position,
                color: fixed.colors.front.primary,
                back_color: fixed.colors.back.primary,
                texcoord: self.generated_texcoord(0, obj, fixed.eye, normal, attribs.texcoords[0]),
                edge_flag: batch.edge_flag(i),
            })
        };
        let vertices: Vec<CpuVertex> = match order {
            Some(order) => order.iter().filter_map(|&i| vertex(i)).collect(),
            None => (0..v.position.len() as u32).filter_map(vertex).collect(),
        };
        let state = self.raster_snapshot();
        let rules = RasterRules {
            cull: state.cull.map(|f| FACE.gl_enum(f)),
            front_face: WINDING.gl_enum(state.front_face),
            mode: state.polygon_mode.map(|m| POLYGON_MODE.gl_enum(m)),
            flat_shading: state.shade_model == ShadeModel::Flat,
        };
        let planes: Vec<[f32; 4]> = state.clip_planes.iter().map(|(_, p)| p.map(|c| c as f32)).collect();
        self.render_mode_primitive(&CpuPrimitive { mode, vertices: &vertices }, &rules, &planes)
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::gl::{GL_2D, GL_3D};
    use crate::translate::render_mode::select::depth_to_uint;
    use crate::translate::{Context, dispatch, gl};

    /// A 100 × 100 window, identity matrices: window x = (x + 1) · 50, z = (z + 1) / 2.
    fn ctx() -> Context {
        let (mut c, _) = Context::with_recording();
        c.bind_drawable(100, 100);
        c
    }

    fn tok(t: gl::GLenum) -> f32 {
        t as f32
    }

    #[test]
    fn begin_end_in_select_mode_gives_hits_and_no_draws() {
        let mut c = ctx();
        let mut buf = [0u32; 16];
        unsafe {
            dispatch::glSelectBuffer(&mut c, 16, buf.as_mut_ptr());
            dispatch::glRenderMode(&mut c, gl::GL_SELECT);
            dispatch::glInitNames(&mut c);
            dispatch::glPushName(&mut c, 5);
            dispatch::glBegin(&mut c, gl::GL_TRIANGLES);
            dispatch::glVertex3f(&mut c, 0.0, 0.0, -0.5);
            dispatch::glVertex3f(&mut c, 0.5, 0.0, 0.5);
            dispatch::glVertex3f(&mut c, 0.0, 0.5, 0.0);
            dispatch::glEnd(&mut c);
            dispatch::glLoadName(&mut c, 6);
            dispatch::glRectf(&mut c, 2.0, 2.0, 3.0, 3.0); // outside the view volume
        }
        assert!(c.frame.draws.is_empty(), "selected primitives are not drawn");
        let mut pointer = std::ptr::null_mut();
        unsafe { c.glGetPointerv(gl::GL_SELECTION_BUFFER_POINTER, &raw mut pointer) };
        assert_eq!(pointer, buf.as_mut_ptr().cast());
        assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 1);
        assert_eq!(&buf[..5], &[1, depth_to_uint(0.25), depth_to_uint(0.75), 5, 0]);
        unsafe { dispatch::glRectf(&mut c, 0.0, 0.0, 0.5, 0.5) };
        assert_eq!(c.frame.draws.len(), 1, "render mode draws again");
        assert_eq!(c.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn draw_arrays_in_feedback_mode_gives_window_polygons() {
        let mut c = ctx();
        let mut buf = [0.0f32; 32];
        let positions: [f32; 9] = [0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.5, 0.0];
        unsafe {
            dispatch::glFeedbackBuffer(&mut c, 32, GL_3D, buf.as_mut_ptr());
            dispatch::glRenderMode(&mut c, gl::GL_FEEDBACK);
            dispatch::glVertexPointer(&mut c, 3, gl::GL_FLOAT, 0, positions.as_ptr().cast());
            dispatch::glEnableClientState(&mut c, gl::GL_VERTEX_ARRAY);
            dispatch::glDrawArrays(&mut c, gl::GL_TRIANGLES, 0, 3);
            let mut pointer = std::ptr::null_mut();
            c.glGetPointerv(gl::GL_FEEDBACK_BUFFER_POINTER, &raw mut pointer);
            assert_eq!(pointer, buf.as_mut_ptr().cast());
        }
        assert!(c.frame.draws.is_empty());
        assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 11);
        let expected = [tok(gl::GL_POLYGON_TOKEN), 3.0, 50.0, 50.0, 0.5, 75.0, 50.0, 0.5, 50.0, 75.0, 0.5];
        assert_eq!(&buf[..11], &expected);
    }

    #[test]
    fn feedback_reports_lit_colours() {
        let mut c = ctx();
        let mut buf = [0.0f32; 16];
        unsafe {
            dispatch::glFeedbackBuffer(&mut c, 16, gl::GL_3D_COLOR, buf.as_mut_ptr());
            dispatch::glRenderMode(&mut c, gl::GL_FEEDBACK);
            dispatch::glEnable(&mut c, gl::GL_LIGHTING);
            dispatch::glEnable(&mut c, gl::GL_LIGHT0);
            dispatch::glBegin(&mut c, gl::GL_POINTS);
            dispatch::glVertex2f(&mut c, 0.0, 0.0);
            dispatch::glEnd(&mut c);
        }
        assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 8);
        // Scene ambient 0.04 + light 0 diffuse 1 × material diffuse 0.8 (normal and light on +z).
        assert_eq!(buf[0], tok(gl::GL_POINT_TOKEN));
        for (got, want) in buf[4..8].iter().zip([0.84, 0.84, 0.84, 1.0]) {
            assert!((got - want).abs() < 1e-6, "{:?}", &buf[..8]);
        }
    }

    #[test]
    fn two_sided_lighting_feeds_back_the_colour_of_the_visible_face() {
        let mut c = ctx();
        let mut buf = [0.0f32; 128];
        let tri = |c: &mut Context, cw: bool| unsafe {
            let (b, d) = if cw { (0.0, 0.5) } else { (0.5, 0.0) };
            dispatch::glBegin(c, gl::GL_TRIANGLES);
            dispatch::glVertex2f(c, 0.0, 0.0);
            dispatch::glVertex2f(c, b, d);
            dispatch::glVertex2f(c, d, b);
            dispatch::glEnd(c);
        };
        let red = [1.0f32, 0.0, 0.0, 1.0];
        let blue = [0.0f32, 0.0, 1.0, 1.0];
        unsafe {
            dispatch::glFeedbackBuffer(&mut c, 128, gl::GL_3D_COLOR, buf.as_mut_ptr());
            dispatch::glRenderMode(&mut c, gl::GL_FEEDBACK);
            dispatch::glEnable(&mut c, gl::GL_LIGHTING);
            dispatch::glLightModeli(&mut c, gl::GL_LIGHT_MODEL_TWO_SIDE, 1);
            let black = [0.0f32, 0.0, 0.0, 1.0];
            dispatch::glLightModelfv(&mut c, gl::GL_LIGHT_MODEL_AMBIENT, black.as_ptr());
            // No light is on: each face's colour is its material emission.
            dispatch::glMaterialfv(&mut c, gl::GL_FRONT, gl::GL_EMISSION, red.as_ptr());
            dispatch::glMaterialfv(&mut c, gl::GL_BACK, gl::GL_EMISSION, blue.as_ptr());
        }
        tri(&mut c, false); // counter-clockwise: front face
        tri(&mut c, true); // clockwise: back face
        unsafe { dispatch::glFrontFace(&mut c, gl::GL_CW) };
        tri(&mut c, true); // clockwise is now the front face
        unsafe { dispatch::glLightModeli(&mut c, gl::GL_LIGHT_MODEL_TWO_SIDE, 0) };
        tri(&mut c, false); // a back face, but one-sided lighting: front colours
        assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 4 * 23);
        let colours: Vec<&[f32]> = buf[..4 * 23].chunks(23).map(|p| &p[2 + 3..2 + 7]).collect();
        for (polygon, want) in buf[..4 * 23].chunks(23).zip([red, blue, red, red]) {
            assert_eq!(polygon[..2], [tok(gl::GL_POLYGON_TOKEN), 3.0]);
            for corner in polygon[2..].chunks(7) {
                assert_eq!(corner[3..], want, "{colours:?}");
            }
        }
    }

    #[test]
    fn feedback_sees_culling_polygon_mode_and_clip_planes() {
        let mut c = ctx();
        let mut buf = [0.0f32; 64];
        let tri = |c: &mut Context, cw: bool| unsafe {
            let (b, d) = if cw { (0.0, 0.5) } else { (0.5, 0.0) };
            dispatch::glBegin(c, gl::GL_TRIANGLES);
            dispatch::glVertex2f(c, 0.0, 0.0);
            dispatch::glVertex2f(c, b, d);
            dispatch::glVertex2f(c, d, b);
            dispatch::glEnd(c);
        };
        unsafe {
            dispatch::glFeedbackBuffer(&mut c, 64, GL_2D, buf.as_mut_ptr());
            dispatch::glRenderMode(&mut c, gl::GL_FEEDBACK);
            dispatch::glEnable(&mut c, gl::GL_CULL_FACE);
        }
        tri(&mut c, true); // clockwise: a back face, culled
        unsafe { dispatch::glPolygonMode(&mut c, gl::GL_FRONT_AND_BACK, gl::GL_POINT) };
        tri(&mut c, false); // three points
        unsafe {
            dispatch::glPolygonMode(&mut c, gl::GL_FRONT_AND_BACK, gl::GL_FILL);
            dispatch::glClipPlane(&mut c, gl::GL_CLIP_PLANE0, [-1.0, 0.0, 0.0, 0.25].as_ptr());
            dispatch::glEnable(&mut c, gl::GL_CLIP_PLANE0); // keeps x ≤ 0.25
        }
        tri(&mut c, false);
        let n = unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) };
        let points = [tok(gl::GL_POINT_TOKEN), 50.0, 50.0, tok(gl::GL_POINT_TOKEN), 75.0, 50.0, tok(gl::GL_POINT_TOKEN), 50.0, 75.0];
        assert_eq!(&buf[..9], &points);
        assert_eq!(&buf[9..11], &[tok(gl::GL_POLYGON_TOKEN), 4.0], "clipped to a quadrilateral");
        assert_eq!(n, 11 + 8);
        assert!(buf[11..19].chunks(2).all(|p| p[0] <= 62.5 + 1e-3), "{:?}", &buf[11..19]);
    }

    #[test]
    fn pixel_commands_in_feedback_mode_give_tokens_not_pixels() {
        let mut c = ctx();
        let mut buf = [0.0f32; 32];
        let bits = [0xffu8; 8];
        unsafe {
            dispatch::glFeedbackBuffer(&mut c, 32, GL_2D, buf.as_mut_ptr());
            dispatch::glRenderMode(&mut c, gl::GL_FEEDBACK);
            dispatch::glRasterPos2f(&mut c, 0.0, 0.0);
            dispatch::glBitmap(&mut c, 8, 8, 0.0, 0.0, 10.0, 0.0, bits.as_ptr());
            dispatch::glCopyPixels(&mut c, 0, 0, 4, 4, gl::GL_COLOR);
            dispatch::glDrawPixels(&mut c, 1, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, bits.as_ptr().cast());
        }
        assert!(c.frame.pixels.is_empty(), "nothing is drawn in feedback mode");
        assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 9);
        let expected = [
            tok(gl::GL_BITMAP_TOKEN), 50.0, 50.0,
            tok(gl::GL_COPY_PIXEL_TOKEN), 60.0, 50.0,
            tok(gl::GL_DRAW_PIXEL_TOKEN), 60.0, 50.0,
        ];
        assert_eq!(&buf[..9], &expected, "the bitmap still moves the raster position");
    }

    #[test]
    fn raster_position_is_a_selection_hit() {
        let mut c = ctx();
        let mut buf = [0u32; 8];
        unsafe {
            dispatch::glSelectBuffer(&mut c, 8, buf.as_mut_ptr());
            dispatch::glRenderMode(&mut c, gl::GL_SELECT);
            dispatch::glPushName(&mut c, 3);
            dispatch::glRasterPos3f(&mut c, 0.0, 0.0, 0.5);
            dispatch::glRasterPos3f(&mut c, 5.0, 0.0, 0.0); // invalid: no hit
        }
        assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 1);
        assert_eq!(&buf[..4], &[1, depth_to_uint(0.75), depth_to_uint(0.75), 3]);
    }
}
