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
    /// Last frame's specular history (`HistorySpecular`), read.
    const BINDING_SPECULAR_PREVIOUS: u32 = 10;
    /// This frame's specular history, written.
    const BINDING_SPECULAR: u32 = 11;
    /// The specular signal the first à-trous iterations ping-pong (`SpecularSignal`), two
    /// halves, at the pass's specular offsets.
    const BINDING_SPECULAR_SIGNAL: u32 = 12;
    /// Number of bindings (`0..BINDING_COUNT`, all storage buffers).
    const BINDING_COUNT: u32 = 13;

    /// Pass flags: the tone mapping operator (`TONEMAP_*` of the tracer), bits 0 and 1.
    const FLAG_TONEMAP_MASK: u32 = 3;
    /// Pass flags: the first à-trous iteration's output becomes the history's light (while
    /// the camera moves, as in SVGF); without it the history keeps the unfiltered mean
    /// (accumulation while everything stands still converges to the traced mean).
    const FLAG_FEEDBACK: u32 = 4;
    /// Pass flags: temporal gradients shorten the history where the lighting changed
    /// (`[denoise] gradients`).
    const FLAG_GRADIENTS: u32 = 16;
    /// Pass flags: what the output shows, `VIEW_*`, in bits `VIEW_SHIFT..` (`VIEW_MASK`).
    const VIEW_SHIFT: u32 = 6;
    /// The view's bits, shifted down.
    const VIEW_MASK: u32 = 7;
    /// View: the denoised colour.
    const VIEW_COLOR: u32 = 0;
    /// View: each pixel's history length (frames, as grey levels 0..=255).
    const VIEW_HISTORY: u32 = 1;
    /// View: this frame's traced direct diffuse light, remodulated (unfiltered).
    const VIEW_DIRECT: u32 = 2;
    /// View: this frame's traced indirect diffuse light, remodulated (unfiltered).
    const VIEW_INDIRECT: u32 = 3;
    /// View: this frame's traced specular light, remodulated (unfiltered).
    const VIEW_SPECULAR: u32 = 4;
    /// View: emission plus the three channels remodulated, unfiltered: the traced radiance
    /// through the channels.
    const VIEW_UNFILTERED: u32 = 5;

    /// Frames of history below which the variance is estimated spatially (`variance.comp`).
    const YOUNG_HISTORY: u32 = 4;
    /// À-trous iterations that filter the specular channel (the first ones, steps 1 and 2).
    const SPECULAR_ITERATIONS: u32 = 2;
    /// The specialisation constant (`constant_id`) of every pass: whether it filters the
    /// specular channel too (`[denoise] specular`; the à-trous filter in its first
    /// `SPECULAR_ITERATIONS` iterations only), `SPECULAR_CHANNEL` of `denoise/common.glsl`.
    const SPECULAR_CONSTANT: u32 = 0;
}
