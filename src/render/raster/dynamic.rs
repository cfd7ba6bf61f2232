//! The pipeline and dynamic state last recorded in the rendering pass, so that a draw records
//! only the commands that change them. Every raster pipeline declares the same dynamic states
//! ([`super::pipelines`]), so binding one leaves them as set; the tracking is forgotten at
//! every new rendering pass ([`super::renderer::Recorder::begin_rendering`]), so commands
//! recorded between passes by other parts cannot leave it stale.

use ash::vk;

use super::device::Device;

/// Values of the dynamic states a draw sets (`PartialEq` on floats: a value equal to the one
/// set, `-0.0` for `0.0` included, draws the same).
#[derive(Clone, Copy, PartialEq)]
pub struct DynamicValues {
    /// Viewport: x, y, width, height, min and max depth.
    pub viewport: [f32; 6],
    /// Scissor rectangle.
    pub scissor: vk::Rect2D,
    /// Line width.
    pub line_width: f32,
    /// Depth bias: constant factor and slope factor.
    pub depth_bias: [f32; 2],
    /// Blend constants.
    pub blend_constants: [f32; 4],
    /// Stencil reference, compare mask and write mask, front then back.
    pub stencil: [[u32; 3]; 2],
}

/// The pipeline and dynamic values set in the pass being recorded (`None`: not yet).
#[derive(Default)]
pub struct Tracked {
    pipeline: Option<vk::Pipeline>,
    values: Option<DynamicValues>,
}

impl Tracked {
    /// Forgets what was set (a new rendering pass begins).
    pub fn forget(&mut self) {
        *self = Tracked::default();
    }

    /// Binds `pipeline` and sets `values` on `cmd`, each command recorded only when its value
    /// differs from the one set before in the pass.
    ///
    /// # Safety
    /// `cmd` is recording inside the rendering pass this tracking was forgotten at, and
    /// `pipeline` is alive for the frame.
    pub unsafe fn set(&mut self, device: &Device, cmd: vk::CommandBuffer, pipeline: vk::Pipeline, values: &DynamicValues) {
        let d = &device.raw;
        // Safety (this block): as the caller guarantees.
        unsafe {
            if self.pipeline != Some(pipeline) {
                d.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::GRAPHICS, pipeline);
                self.pipeline = Some(pipeline);
            }
            let old = self.values.replace(*values);
            if old.is_none_or(|o| o.viewport != values.viewport) {
                let [x, y, width, height, min_depth, max_depth] = values.viewport;
                d.cmd_set_viewport(cmd, 0, &[vk::Viewport { x, y, width, height, min_depth, max_depth }]);
            }
            if old.is_none_or(|o| o.scissor != values.scissor) {
                d.cmd_set_scissor(cmd, 0, &[values.scissor]);
            }
            if old.is_none_or(|o| o.line_width != values.line_width) {
                d.cmd_set_line_width(cmd, values.line_width);
            }
            if old.is_none_or(|o| o.depth_bias != values.depth_bias) {
                d.cmd_set_depth_bias(cmd, values.depth_bias[0], 0.0, values.depth_bias[1]);
            }
            if old.is_none_or(|o| o.blend_constants != values.blend_constants) {
                d.cmd_set_blend_constants(cmd, &values.blend_constants);
            }
            for (i, face) in [vk::StencilFaceFlags::FRONT, vk::StencilFaceFlags::BACK].into_iter().enumerate() {
                let [reference, compare, write] = values.stencil[i];
                let old = old.map(|o| o.stencil[i]);
                if old.is_none_or(|o| o[0] != reference) {
                    d.cmd_set_stencil_reference(cmd, face, reference);
                }
                if old.is_none_or(|o| o[1] != compare) {
                    d.cmd_set_stencil_compare_mask(cmd, face, compare);
                }
                if old.is_none_or(|o| o[2] != write) {
                    d.cmd_set_stencil_write_mask(cmd, face, write);
                }
            }
        }
    }
}
