// The per-pixel records every back end writes and the denoiser reads: the G-buffer's
// GSample and the composite's OutputSample (bound by trace/gbuffer.glsl and denoise/common.glsl).

#ifndef TRACE_SAMPLES_GLSL
#define TRACE_SAMPLES_GLSL

// What the primary ray of a pixel saw this frame (the G-buffer's records: one per traced pixel,
// then one per gradient stratum, its gradient sample, trace/gradient.glsl). The lighting
// channels are demodulated (trace/channels.glsl): direct is the light of the next-event
// estimation at the primary hit (lights and emitters), indirect all light that reached the
// primary hit through its continuation ray, both as the diffuse lobe reflects them when the
// frame splits specular light off (FRAME_SPECULAR; otherwise both lobes), and specular what
// the specular lobe reflects of both (0 without FRAME_SPECULAR); radiance minus the three,
// remodulated, is the primary hit's own emission (baked light, emissive surfaces) or the
// environment of a miss. Each vec3 shares its 16 bytes with the scalar after it (std430).
struct GSample {
    vec3 radiance;      // noisy linear radiance, averaged over this frame's samples (all channels)
    uint albedo;        // linear albedo, unorm8 RGB (a: coverage)
    vec3 direct;        // direct light at the primary hit / the demodulating albedo
    uint normal;        // shading normal, octahedral (pack.glsl)
    vec3 indirect;      // indirect light at the primary hit / the demodulating albedo
    float depth;        // window depth as glDepthRange maps it; >= 1 for rays that missed
    vec3 specular;      // specular light at the primary hit / the demodulating reflectance
    float view_z;       // eye-space distance along -z (0: missed)
    vec2 motion;        // window position now minus window position last frame, in traced pixels
    uint material;      // roughness, metalness, dielectric F0 and n.v as unorm8 (channels.glsl)
    uint instance;      // index of the instance hit, 0xffffffff on a miss
    uint surface;       // the key of the material hit (Material.key; 0 on a miss): history follows it
    uint gradient;      // a stratum's gradient sample (trace/gradient.glsl): 1 + the index of the pixel whose sample of last frame it repeats; 0: none (and every pixel's record)
    uint pad[2];
};

// What the composite draws: tone-mapped colour and depth.
struct OutputSample {
    uint color;         // display-encoded unorm8 RGBA
    float depth;        // window depth; >= 1 where the primary ray missed (the composite keeps the framebuffer)
};

#endif
