//! Analytic height fog (seed 002, issue 23) in both modes: the density
//! `rho(z) = rho0 · e^(−b·z)` along the world's height, the fog amount `F` on the segment from
//! the eye to each visible point in closed form, and the colour `mix(scene, fog, clamp(F, 0, 1))`.
//! The formula is GLSL in one place, `shaders/fog/height.glsl`; [`settings`] reads `[fog]`.
//!
//! Where it applies: per fragment, as the seed's method does (not as a post-process over the
//! depth buffer, which cannot see what lies behind glass):
//! - raster draws: `ff.frag` (and the entry of translated GL 2.0 programs) fogs every fragment
//!   of a 3D draw after the program's own GL fog, which stays as the program set it; the
//!   block [`GpuHeightFog`] rides in the per-draw block (`FfBlock::height_fog`), written per
//!   batch by the raster renderer;
//! - traced frames: the composite (`trace_composite.frag`) fogs each primary hit it writes
//!   into the framebuffer, with the camera draw's block; the translucent draws rasterized over
//!   it are fogged as raster draws. Both modes use the same window → world mapping, so the same
//!   surface gets the same fog.
//!
//! Sky and overlay (HUD) draws are not fogged, nor draws into framebuffer objects.
//!
//! Translucent surfaces (the seed's `F_f`): each fragment is fogged on the segment from the eye
//! to itself, and blending does the rest. For alpha blending over a wall at P behind glass at
//! P_n, the result `a · mix(g, fog, F(O→P_n)) + (1 − a) · mix(w, fog, F(O→P))` counts the
//! segment O→P_n once (weights a and 1 − a) and the segment P_n→P, `F_f`, once, seen through
//! the glass; a clear glass (a = 0) leaves the fogged wall exactly as without it. Fogging the
//! wall with `F_f` alone, as the seed writes, would drop the segment O→P_n from everything seen
//! through glass. What would count fog twice is a pass that adds to or multiplies what is
//! under it: such a pass fades to its neutral colour, the one that leaves the framebuffer as
//! it is, as Quake 3 fogs its multi-pass shaders: an additive pass (destination factor one)
//! towards black (it adds only its own light, attenuated), a modulating pass (lightmaps:
//! `DST_COLOR, ZERO`) towards white, a doubling one (`DST_COLOR, SRC_COLOR`, overbright
//! lightmaps) towards grey 0.5; a fully fogged multi-pass surface is then the fog colour.
//!
//! World space: the recovered view's world ([`crate::frame::class::View`]) when the frame has
//! one, else the eye space of the draw; its up direction and the height origin come from the
//! settings.

pub mod settings;

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec4};

use crate::frame::class::{DrawClass, orthographic};
use crate::frame::state::BlendFactor;
use crate::frame::{Draw, Frame};
use settings::{DEFAULT_COLOR, FogColor, FogSettings};

/// `HeightFog` of `shaders/fog/height.glsl` (std140 and std430 alike): what a fragment shader
/// needs to fog its fragments.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuHeightFog {
    /// `(gl_FragCoord.xyz, 1)` → world position, homogeneous (column-major).
    pub window_to_world: [[f32; 4]; 4],
    /// The eye in the world; w: 1 where the fog applies, 0 elsewhere (all zero: no fog).
    pub eye: [f32; 4],
    /// Unit world up; w: the height of the density's origin.
    pub up: [f32; 4],
    /// rho0, falloff b, unused, unused.
    pub density: [f32; 4],
    /// What the fragments fade to (rgb): the fog colour, or the neutral colour of the draw's
    /// blending ([`neutral`]).
    pub color: [f32; 4],
}

/// The fog of one frame: its settings resolved against the frame (world, colour).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameFog {
    /// Eye space → world (the inverse of the recovered view; identity without one).
    world_from_eye: Mat4,
    settings: FogSettings,
    color: [f32; 3],
}

impl FrameFog {
    /// The fog of `frame` under `settings`; `None` when the fog is off or has no density.
    pub fn of(frame: &Frame, settings: &FogSettings) -> Option<FrameFog> {
        if !settings.enabled || settings.density <= 0.0 {
            return None;
        }
        let world_from_eye = frame.view.as_ref().map_or(Mat4::IDENTITY, |v| v.view.inverse());
        let color = match settings.color {
            FogColor::Fixed(c) => c,
            FogColor::FromGl => {
                let gl = frame.draws.iter().find_map(|d| d.state.fog.as_ref().map(|f| [f.color[0], f.color[1], f.color[2]]));
                gl.unwrap_or(DEFAULT_COLOR)
            }
        };
        Some(FrameFog { world_from_eye, settings: *settings, color })
    }

    /// The block that fogs `draw`'s fragments in a framebuffer `height` pixels high (Vulkan's
    /// `gl_FragCoord.y` counts from its top); all zero (no fog) for draws not fogged.
    pub fn for_draw(&self, draw: &Draw, height: u32) -> GpuHeightFog {
        let fogged = match draw.class {
            DrawClass::Overlay | DrawClass::Sky | DrawClass::Ignored => false,
            DrawClass::Unclassified => !orthographic(&draw.projection),
            _ => true,
        };
        if !fogged {
            return GpuHeightFog::zeroed();
        }
        let s = &self.settings;
        let window_to_world = self.world_from_eye * draw.projection.inverse() * ndc_from_window(draw, height);
        let eye = self.world_from_eye.w_axis.truncate();
        let [r, g, b] = neutral(draw).unwrap_or(self.color);
        GpuHeightFog {
            window_to_world: window_to_world.to_cols_array_2d(),
            eye: [eye.x, eye.y, eye.z, 1.0],
            up: [s.up.x, s.up.y, s.up.z, s.height],
            density: [s.density, s.falloff, 0.0, 0.0],
            color: [r, g, b, 1.0],
        }
    }
}

/// `(gl_FragCoord.xyz, 1)` → GL normalized device coordinates for `draw`'s viewport and depth
/// range in a framebuffer `height` pixels high (GL's window y = height − Vulkan's).
fn ndc_from_window(draw: &Draw, height: u32) -> Mat4 {
    let [vx, vy, vw, vh] = draw.state.viewport.map(|v| v as f32);
    let [d0, d1] = draw.state.depth_range.map(|d| d as f32);
    let dz = if d1 != d0 { d1 - d0 } else { 1.0 };
    let (sx, sy, sz) = (2.0 / vw.max(1.0), 2.0 / vh.max(1.0), 2.0 / dz);
    Mat4::from_cols(
        Vec4::new(sx, 0.0, 0.0, 0.0),
        Vec4::new(0.0, -sy, 0.0, 0.0),
        Vec4::new(0.0, 0.0, sz, 0.0),
        Vec4::new(-vx * sx - 1.0, (height as f32 - vy) * sy - 1.0, -d0 * sz - 1.0, 1.0),
    )
}

/// The neutral colour of `draw`'s blending, the source colour that leaves the framebuffer as
/// it is, for passes that add to or multiply it; `None` for opaque and alpha-blended draws
/// (they fade to the fog colour).
fn neutral(draw: &Draw) -> Option<[f32; 3]> {
    use BlendFactor::{DstColor, One, SrcColor, Zero};
    match draw.state.blend.map(|b| (b.src_rgb, b.dst_rgb)) {
        Some((_, One)) => Some([0.0; 3]),
        Some((DstColor, Zero) | (Zero, SrcColor)) => Some([1.0; 3]),
        Some((DstColor, SrcColor) | (SrcColor, DstColor)) => Some([0.5; 3]),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::Vec3;

    use super::*;
    use crate::frame::state::{Blend, RasterState};

    /// A perspective draw in a 64 × 48 viewport at (8, 4) of a 60-pixel-high framebuffer.
    fn draw(blend: Option<Blend>, class: DrawClass) -> Draw {
        let state = RasterState { viewport: [8, 4, 64, 48], depth_range: [0.0, 1.0], blend, ..RasterState::default() };
        // glFrustum(-0.4, 0.3, -0.2, 0.25, 0.5, 50).
        let (l, r, b, t, n, f) = (-0.4f32, 0.3, -0.2, 0.25, 0.5, 50.0);
        let projection = Mat4::from_cols(
            Vec4::new(2.0 * n / (r - l), 0.0, 0.0, 0.0),
            Vec4::new(0.0, 2.0 * n / (t - b), 0.0, 0.0),
            Vec4::new((r + l) / (r - l), (t + b) / (t - b), -(f + n) / (f - n), -1.0),
            Vec4::new(0.0, 0.0, -2.0 * f * n / (f - n), 0.0),
        );
        Draw { state: Arc::new(state), projection, class, ..Draw::default() }
    }

    fn fog() -> FrameFog {
        let settings = FogSettings { enabled: true, up: Vec3::Z, ..FogSettings::default() };
        let view = Mat4::from_rotation_x(0.3) * Mat4::from_rotation_z(0.7) * Mat4::from_translation(-Vec3::new(1.0, 2.0, 3.0));
        let frame = Frame { view: Some(crate::frame::class::View { view, ..Default::default() }), ..Frame::default() };
        FrameFog::of(&frame, &settings).expect("fog on")
    }

    /// The window → world matrix takes the window position of a world point (as the
    /// rasterizer computes it) back to that point, and the eye is the view's.
    #[test]
    fn window_positions_map_back_to_world_points() {
        let (fog, draw) = (fog(), draw(None, DrawClass::Static));
        let block = fog.for_draw(&draw, 60);
        assert!((Vec3::from_slice(&block.eye[..3]) - Vec3::new(1.0, 2.0, 3.0)).length() < 1e-5, "{:?}", block.eye);
        let view = fog.world_from_eye.inverse();
        for eye_space in [Vec3::new(0.1, 0.2, -4.0), Vec3::new(-1.0, 0.5, -2.0), Vec3::new(3.0, -2.0, -20.0)] {
            let world = fog.world_from_eye.transform_point3(eye_space);
            let clip = draw.projection * view * world.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            let [vx, vy, vw, vh] = draw.state.viewport.map(|v| v as f32);
            let gl_y = vy + (ndc.y * 0.5 + 0.5) * vh;
            let frag = Vec4::new(vx + (ndc.x * 0.5 + 0.5) * vw, 60.0 - gl_y, ndc.z * 0.5 + 0.5, 1.0);
            let back = Mat4::from_cols_array_2d(&block.window_to_world) * frag;
            assert!((back.truncate() / back.w - world).length() < 1e-3 * world.length(), "{world}: {back}");
        }
    }

    #[test]
    fn blending_chooses_the_target_and_classes_the_fogged_draws() {
        let fog = fog();
        let blend = |src, dst| Some(Blend { src_rgb: src, dst_rgb: dst, ..Blend::default() });
        let target_of = |b| fog.for_draw(&draw(b, DrawClass::Translucent), 60).color;
        let fog_color = [DEFAULT_COLOR[0], DEFAULT_COLOR[1], DEFAULT_COLOR[2], 1.0];
        assert_eq!(target_of(None), fog_color);
        assert_eq!(target_of(blend(BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha)), fog_color);
        assert_eq!(target_of(blend(BlendFactor::SrcAlpha, BlendFactor::One)), [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(target_of(blend(BlendFactor::DstColor, BlendFactor::Zero)), [1.0, 1.0, 1.0, 1.0]);
        assert_eq!(target_of(blend(BlendFactor::DstColor, BlendFactor::SrcColor)), [0.5, 0.5, 0.5, 1.0]);
        assert_eq!(fog.for_draw(&draw(None, DrawClass::Overlay), 60), GpuHeightFog::zeroed());
        assert_eq!(fog.for_draw(&draw(None, DrawClass::Sky), 60), GpuHeightFog::zeroed());
        assert_eq!(fog.for_draw(&draw(None, DrawClass::Static), 60).eye[3], 1.0);
        let off = FogSettings { density: 0.0, enabled: true, ..FogSettings::default() };
        assert!(FrameFog::of(&Frame::default(), &off).is_none());
    }
}
