//! Multisampling (OpenGL 1.5 sections 3.2.1 and 4.1.3, `ARB_multisample`) on Vulkan: the
//! sample counts a framebuffer may have, and the multisample state of each pipeline pass.
//!
//! **Sample counts.** A count is offered when the colour, depth and stencil attachments all
//! support it (`framebuffer*SampleCounts`) and the device uses the standard sample locations
//! (`standardSampleLocations`), limited to 2, 4 and 8 (the counts whose locations
//! [`locations`] lists: draws with `GL_MULTISAMPLE` disabled need them). GLX builds its
//! configurations before any context exists, so [`probe`] reads the counts of the device that
//! `GLRT_DEVICE` chooses once per process (an instance is created and destroyed for it).
//!
//! **Coverage** (section 4.1.3, applied only while `GL_MULTISAMPLE` is on and the drawable is
//! multisampled): `GL_SAMPLE_ALPHA_TO_COVERAGE` is the pipeline's `alphaToCoverageEnable`,
//! `GL_SAMPLE_ALPHA_TO_ONE` its `alphaToOneEnable` (when the device has `alphaToOne`; without
//! it the operation is skipped with a warning), and `glSampleCoverage(value, invert)` the
//! pipeline's sample mask: the lowest `round(value × samples)` bits, inverted when asked
//! ([`coverage_mask`]; which bits is left to the implementation).
//!
//! **`GL_MULTISAMPLE` disabled** (section 3.2.1): primitives are rasterized as if
//! single-sampled: the coverage, depth and colour at the pixel centre are written to every
//! sample of the pixel. Vulkan has no such mode (`VK_EXT_sample_locations` could place every
//! sample at the centre, but lavapipe lacks it), so such a draw is drawn once per sample `i`
//! with the sample mask `1 << i` and the viewport moved by `location(i) − (½, ½)`: sample `i`
//! of every pixel then lies where the pixel centre lay before the move, so its coverage,
//! depth and interpolated values are the centre's, and each sample holds what a single-sampled
//! drawable holds (`tests/raster/msaa.rs` compares the two images), for every primitive, at
//! the cost of one draw per sample ([`passes`]).
//!
//! Not done: with `GL_MULTISAMPLE` on, sections 3.3.3 and 3.4.4 ignore `GL_POINT_SMOOTH` and
//! `GL_LINE_SMOOTH` (points become circles and lines rectangles covered by samples); glrt
//! still draws smooth points and lines with their alpha fringe. The alpha test sees the
//! fragment's own alpha even with `GL_SAMPLE_ALPHA_TO_ONE` (section 4.1.3 applies it first).

use std::sync::OnceLock;

use ash::vk;

use crate::frame::state::Multisample;

/// Standard sample locations of Vulkan (section "Multisampling", table of standard sample
/// locations) for 1, 2, 4 and 8 samples, in pixel coordinates with the origin at the top-left
/// corner; `None` for other counts.
pub fn locations(samples: u32) -> Option<&'static [[f32; 2]]> {
    Some(match samples {
        1 => &[[0.5, 0.5]],
        2 => &[[0.75, 0.75], [0.25, 0.25]],
        4 => &[[0.375, 0.125], [0.875, 0.375], [0.125, 0.625], [0.625, 0.875]],
        8 => &[
            [0.5625, 0.3125],
            [0.4375, 0.6875],
            [0.8125, 0.5625],
            [0.3125, 0.1875],
            [0.1875, 0.8125],
            [0.0625, 0.4375],
            [0.6875, 0.9375],
            [0.9375, 0.0625],
        ],
        _ => return None,
    })
}

/// The multisampled counts (above 1) a framebuffer of a device with `limits` can have.
pub fn supported_counts(limits: &vk::PhysicalDeviceLimits) -> Vec<u32> {
    let all = limits.framebuffer_color_sample_counts & limits.framebuffer_depth_sample_counts & limits.framebuffer_stencil_sample_counts;
    [2, 4, 8].into_iter().filter(|&n| limits.standard_sample_locations == vk::TRUE && all.contains(flags(n))).collect()
}

/// The Vulkan flag of `samples` (a power of two up to 64; anything else is one sample).
pub fn flags(samples: u32) -> vk::SampleCountFlags {
    if samples.is_power_of_two() && samples <= 64 { vk::SampleCountFlags::from_raw(samples) } else { vk::SampleCountFlags::TYPE_1 }
}

/// The multisampled counts of the device `GLRT_DEVICE` chooses, read once per process; empty
/// without Vulkan 1.3.
pub fn probe() -> &'static [u32] {
    static COUNTS: OnceLock<Vec<u32>> = OnceLock::new();
    COUNTS.get_or_init(|| super::device::probe_properties().map(|p| supported_counts(&p.limits)).unwrap_or_default())
}

/// The sample mask of `glSampleCoverage(value, invert)` for `samples` samples.
pub fn coverage_mask(samples: u32, value: f32, invert: bool) -> u32 {
    let all = if samples >= 32 { u32::MAX } else { (1u32 << samples) - 1 };
    let bits = (value.clamp(0.0, 1.0) * samples as f32).round() as u32;
    let mask = if bits >= 32 { u32::MAX } else { (1u32 << bits) - 1 };
    (if invert { !mask } else { mask }) & all
}

/// The multisample state baked into a pipeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SampleState {
    /// Samples per pixel of the framebuffer (`rasterizationSamples`).
    pub samples: u32,
    /// Samples written (`pSampleMask`).
    pub mask: u32,
    /// `alphaToCoverageEnable`.
    pub alpha_to_coverage: bool,
    /// `alphaToOneEnable`.
    pub alpha_to_one: bool,
}

impl SampleState {
    /// One sample, every operation off.
    pub const SINGLE: SampleState = SampleState { samples: 1, mask: u32::MAX, alpha_to_coverage: false, alpha_to_one: false };
}

/// Most passes of a draw: one per sample of the largest count [`locations`] lists.
const MAX_PASSES: usize = 8;

/// The passes of a draw ([`passes`]), in order: per pass, the pipeline's multisample state and
/// the viewport offset in pixels. A slice of at most [`MAX_PASSES`], kept without allocation.
#[derive(Clone, Copy, Debug)]
pub struct Passes {
    list: [(SampleState, [f32; 2]); MAX_PASSES],
    len: usize,
}

impl Passes {
    /// The one pass `pass`, without offset.
    fn one(pass: SampleState) -> Passes {
        let mut list = [(SampleState::SINGLE, [0.0; 2]); MAX_PASSES];
        list[0].0 = pass;
        Passes { list, len: 1 }
    }
}

impl std::ops::Deref for Passes {
    type Target = [(SampleState, [f32; 2])];

    fn deref(&self) -> &Self::Target {
        &self.list[..self.len]
    }
}

/// The passes a draw with `state` takes on a framebuffer of `samples` samples: per pass, the
/// pipeline's multisample state and the viewport offset in pixels (framebuffer coordinates, y
/// down). One pass, except with `GL_MULTISAMPLE` disabled (see the module doc).
/// `alpha_to_one_supported` says whether the device has `alphaToOne`.
pub fn passes(samples: u32, state: &Multisample, alpha_to_one_supported: bool) -> Passes {
    if samples <= 1 {
        return Passes::one(SampleState::SINGLE);
    }
    if !state.enabled
        && let Some(at) = locations(samples) {
            let mut passes = Passes { list: [(SampleState::SINGLE, [0.0; 2]); MAX_PASSES], len: at.len() };
            for (i, (pass, l)) in passes.list.iter_mut().zip(at).enumerate() {
                *pass = (SampleState { samples, mask: 1 << i, ..SampleState::SINGLE }, [l[0] - 0.5, l[1] - 0.5]);
            }
            return passes;
        }
    let mask = match state.coverage {
        Some((value, invert)) if state.enabled => coverage_mask(samples, value, invert),
        _ => u32::MAX,
    };
    if state.enabled && state.alpha_to_one && !alpha_to_one_supported {
        super::renderer::log_once("the device has no alphaToOne feature: GL_SAMPLE_ALPHA_TO_ONE is ignored");
    }
    Passes::one(SampleState {
        samples,
        mask,
        alpha_to_coverage: state.enabled && state.alpha_to_coverage,
        alpha_to_one: state.enabled && state.alpha_to_one && alpha_to_one_supported,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coverage_masks_take_the_rounded_share_of_samples() {
        assert_eq!(coverage_mask(4, 0.5, false), 0b0011);
        assert_eq!(coverage_mask(4, 0.5, true), 0b1100);
        assert_eq!(coverage_mask(4, 1.0, false), 0b1111);
        assert_eq!(coverage_mask(4, 0.0, true), 0b1111);
        assert_eq!(coverage_mask(8, 0.3, false), 0b0011, "0.3 × 8 = 2.4 rounds to 2 samples");
    }

    #[test]
    fn counts_need_colour_depth_stencil_and_standard_locations() {
        let mut limits = vk::PhysicalDeviceLimits {
            framebuffer_color_sample_counts: vk::SampleCountFlags::TYPE_1 | vk::SampleCountFlags::TYPE_4 | vk::SampleCountFlags::TYPE_8,
            framebuffer_depth_sample_counts: vk::SampleCountFlags::TYPE_1 | vk::SampleCountFlags::TYPE_4,
            framebuffer_stencil_sample_counts: vk::SampleCountFlags::TYPE_1 | vk::SampleCountFlags::TYPE_4 | vk::SampleCountFlags::TYPE_8,
            standard_sample_locations: vk::TRUE,
            ..Default::default()
        };
        assert_eq!(supported_counts(&limits), [4]);
        limits.standard_sample_locations = vk::FALSE;
        assert!(supported_counts(&limits).is_empty());
    }

    #[test]
    fn disabled_multisample_draws_once_per_sample_at_the_centre() {
        let off = Multisample { enabled: false, coverage: Some((0.5, false)), ..Multisample::default() };
        let p = passes(4, &off, true);
        assert_eq!(p.len(), 4);
        assert_eq!(p.iter().map(|(s, _)| s.mask).collect::<Vec<_>>(), [1, 2, 4, 8]);
        assert_eq!(p[0].1, [-0.125, -0.375], "sample 0 at (0.375, 0.125) moves onto the centre");
        assert!(p.iter().all(|(s, _)| s.samples == 4 && !s.alpha_to_coverage));
        let on = Multisample { alpha_to_coverage: true, coverage: Some((0.5, true)), ..Multisample::default() };
        assert_eq!(*passes(4, &on, true), [(SampleState { samples: 4, mask: 0b1100, alpha_to_coverage: true, alpha_to_one: false }, [0.0; 2])]);
        assert_eq!(*passes(1, &on, true), [(SampleState::SINGLE, [0.0; 2])], "single-sampled: no multisample operation");
    }
}
