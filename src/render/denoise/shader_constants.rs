//! The denoiser's descriptor bindings and pass flags, shared with `shaders/denoise/` as
//! `generated/denoise_constants.glsl` (see [`crate::render::shader_abi`]), each named
//! `DENOISE_<NAME>` there.

glsl_constants! {
    glsl_prefix = "DENOISE_";
    /// The tracer's G-buffer (`GSample` of `trace/samples.glsl`), read.
    const BINDING_GBUFFER: u32 = 0;
    /// The traced image the composite draws (`OutputSample`), written by the last pass.
    const BINDING_OUTPUT: u32 = 1;
    /// Last frame's history light (`HistoryLight` of `denoise/common.glsl`), read.
    const BINDING_LIGHT_PREVIOUS: u32 = 2;
    /// This frame's history light, written.
    const BINDING_LIGHT: u32 = 3;
    /// Last frame's luminance means and variances (`HistoryMoments`), read.
    const BINDING_MOMENTS_PREVIOUS: u32 = 4;
    /// This frame's luminance means and variances, written.
    const BINDING_MOMENTS: u32 = 5;
    /// Last frame's surfaces (`Guide`: normal and eye distance), read.
    const BINDING_GUIDE_PREVIOUS: u32 = 6;
    /// This frame's surfaces, written by the temporal pass, read by the spatial ones.
    const BINDING_GUIDE: u32 = 7;
    /// The signal the spatial passes ping-pong (`Signal`): light and variance per channel,
    /// two halves, at the pass's offsets.
    const BINDING_SIGNAL: u32 = 8;
    /// The temporal gradients per 3x3 stratum (`gradient.comp`), read by the temporal pass.
    const BINDING_GRADIENT: u32 = 9;
    /// Number of bindings (`0..BINDING_COUNT`, all storage buffers).
    const BINDING_COUNT: u32 = 10;

    /// Pass flags: the tone mapping operator (`TONEMAP_*` of the tracer), bits 0 and 1.
    const FLAG_TONEMAP_MASK: u32 = 3;
    /// Pass flags: the first à-trous iteration's output becomes the history's light (while
    /// the camera moves, as in SVGF); without it the history keeps the unfiltered mean
    /// (accumulation while everything stands still converges to the traced mean).
    const FLAG_FEEDBACK: u32 = 4;
    /// Pass flags: the output shows each pixel's history length (frames, as grey levels
    /// 0..=255) instead of its colour (`[denoise] view = "history"`).
    const FLAG_VIEW_HISTORY: u32 = 8;
    /// Pass flags: temporal gradients shorten the history where the lighting changed
    /// (`[denoise] gradients`).
    const FLAG_GRADIENTS: u32 = 16;

    /// Frames of history below which the variance is estimated spatially (`variance.comp`).
    const YOUNG_HISTORY: u32 = 4;
}
