// The path integrator of both tracers (render::trace::compute and render::trace::hardware):
// per traced pixel, one path of a primary ray,
// next-event estimation at every vertex (one shadow ray per light that lights it: GL lights
// and the light of its own vertex colours, render::trace::vertex_light; one towards a point of an
// emissive triangle, trace/emitters.glsl, weighted against continuation rays that hit
// emitters by multiple importance sampling; one towards the sky, trace/sky_sampling.glsl,
// weighted likewise against continuation rays that miss), `bounces` indirect bounces and the
// environment (trace/environment.glsl: the sky cube map or the clear colour) through every
// continuation ray that misses (cosine-weighted diffuse or GGX visible-normal specular), and through
// primary rays that miss; a vertex-lit model with an ambient light (render::trace::vertex_light)
// samples neither emitters nor the sky, and its continuation rays that meet nothing within the
// model's width bring that light instead of the level's; a baked surface (render::trace::material) ends the path with its
// emission and the light of the dynamic lights (render::trace::lights); adds its share of the
// noisy radiance (1 / `samples`) to the G-buffer, which sample 0 writes with the primary hit
// (trace/gbuffer.glsl), whole and split into the denoiser's channels: direct light at the
// primary hit and indirect light, and with FRAME_SPECULAR the specular lobe's share of both
// apart (the specular parts of the primary hit's next-event samples, and the specular lobe's
// share of brdf_eval_cos in the direction of its continuation ray times all the light that
// ray brings), demodulated (trace/channels.glsl). With radiosity
// (render::trace::radiosity), the first vertex that a diffuse continuation ray reaches on the
// static world adds radiosity's indirect light there (the light of every later bounce,
// reflected by the surface's diffuse albedo) after its next-event estimation, and the path
// ends. The tracer runs it once per sample of the frame (see `dispatch` in
// src/render/trace/compute.rs for why), and with temporal gradients a second time per sample
// over the strata's gradient samples (trace_invocation, trace/gradient.glsl). src/render/trace/mod.rs describes
// the scene it reads. Ray counts and traversal work are summed per subgroup (subgroup
// arithmetic, which lavapipe and the desktop drivers have) and added to the counters once per
// subgroup.
//
// The including shader enables GL_KHR_shader_subgroup_arithmetic and _basic, and for the
// hardware tracer defines TRACE_HARDWARE (trace/surface.glsl then traverses with
// trace/hardware.glsl).

#ifndef TRACE_PATH_GLSL
#define TRACE_PATH_GLSL

// The sample of the frame this dispatch traces, 0 to samples - 1, and which pass it is: the
// main pass (0), one invocation per traced pixel, or the gradient pass (1), one per gradient
// stratum (trace/gradient.glsl).
layout(push_constant) uniform Pass {
    uint sample_index;
    uint gradients;
} pass;

#include "trace/emitters.glsl"
#include "trace/gbuffer.glsl"
#include "trace/sky_sampling.glsl"
#include "trace/channels.glsl"
#include "trace/gradient.glsl"
#include "trace/radiosity.glsl"

// The eye-space ray through window position `window` (GL window coordinates, y up).
void camera_ray(vec2 window, out vec3 origin, out vec3 dir) {
    vec2 ndc = 2.0 * (window - frame.viewport.xy) / frame.viewport.zw - 1.0;
    vec4 near = frame.inverse_projection * vec4(ndc, -1.0, 1.0);
    vec4 far = frame.inverse_projection * vec4(ndc, 1.0, 1.0);
    origin = near.xyz / near.w;
    dir = normalize(far.xyz / far.w - origin);
}

// Window depth of eye-space point p (glDepthRange applied).
float window_depth(mat4 projection, vec3 p) {
    vec4 clip = projection * vec4(p, 1.0);
    float ndc = clip.z / clip.w;
    return mix(frame.depth_range.x, frame.depth_range.y, ndc * 0.5 + 0.5);
}

vec2 window_xy(mat4 projection, vec3 p) {
    vec4 clip = projection * vec4(p, 1.0);
    return frame.viewport.xy + (clip.xy / clip.w * 0.5 + 0.5) * frame.viewport.zw;
}

// What a path vertex's next-event samples need to know of it besides its surface and view
// direction.
struct NextEvent {
    uint instance;
    // A baked surface's shown colour (display units; trace/lights.glsl dynamic_pass_light).
    vec3 shown;
    float cone_width;
    float spread;
    // Whether a continuation ray leaving the vertex also finds emitters (then the emitter
    // sample takes its MIS weight), and whether one finds the sky (the sky sample's).
    bool emitter_weighted;
    bool sky_weighted;
    // Whether the vertex samples emitters (there are some, and no vertex-lit model's ambient
    // holds their light).
    bool samples_emitters;
    uint light_count;
    float sky_chance;
    // Whether the path draws last frame's numbers (a gradient sample: the sky sample then
    // takes last frame's cells), and the pixel whose numbers it draws.
    bool last_frame;
    uvec2 pixel;
    uint seed_frame;
    uint sample_index;
    uint depth;
};

// The next-event sample of light k (on a baked surface what a dynamic light's pass brings).
ShadowSample light_sample(Surface s, vec3 v, NextEvent ne, uint k, inout Rng rng) {
    if (!s.baked) {
        return direct_light(s, v, ne.instance, k, rng);
    }
    return lights[k].params.w < 0.0 ? dynamic_pass_light(s, ne.shown, k, rng) : unshadowed(vec3(0.0));
}

// The next-event sample of one emitter.
ShadowSample emitter_sample(Surface s, vec3 v, NextEvent ne, inout Rng rng) {
    return !s.baked && ne.samples_emitters
        ? emitter_light(s, v, ne.cone_width, ne.spread, ne.emitter_weighted, rng) : unshadowed(vec3(0.0));
}

// The next-event sample of the sky, taken with the frame's probability (last frame's where the
// path draws last frame's numbers), chosen for a tile of pixels together.
ShadowSample sky_sample_at(Surface s, vec3 v, NextEvent ne, inout Rng rng) {
    return ne.sky_chance > 0.0 && sky_chosen(ne.pixel, ne.seed_frame, ne.sample_index, ne.depth, ne.sky_chance)
        ? sky_light(s, v, ne.sky_chance, ne.last_frame, ne.sky_weighted, rng) : unshadowed(vec3(0.0));
}

// Traces sample n's shadow ray from `origin` (counted in `shadow_rays`, and in `sky_rays` for
// the sky's) and adds its light where it is not occluded: to `lit` (its specular lobe's part
// also to `lit_specular`) through the path's `throughput`, or on a baked surface to `brought`
// (display units).
void next_event_add(ShadowSample n, vec3 origin, bool baked, vec3 throughput, bool sky, inout vec3 lit, inout vec3 lit_specular, inout vec3 brought, inout uint shadow_rays, inout SkyRays sky_rays) {
    if (n.distance > 0.0) {
        shadow_rays += 1u;
        sky_rays.traced += sky ? 1u : 0u;
        if (trace_any(origin, n.dir, 0.0, n.distance)) {
            return;
        }
        sky_rays.unoccluded += sky ? 1u : 0u;
    }
    if (baked) {
        brought += n.light;
    } else {
        lit += throughput * n.light;
        lit_specular += throughput * n.specular;
    }
}

// Uses camera_ray and window_xy.
#include "trace/forward_projection.glsl"

// Traces a sample of traced pixel `pixel` into G-buffer record `index` where `recorded`
// (otherwise only counts; every invocation of a subgroup must call it, for the counters'
// subgroup sums): where `traced`, the pixel's sample of this frame, or with `gradient` its
// gradient sample (trace/gradient.glsl), which repeats a sample of last frame with its random
// numbers and is traced no further where it can repeat none (the record then shows a miss).
void trace_pixel(uvec2 pixel, bool traced, bool gradient, bool recorded, uint index) {
    uvec2 size = frame.size.xy;
    uint samples = max(frame.counts.y, 1u);
    uint bounces = frame.counts.z;
    uint light_count = frame.counts.w;
    uint emitter_count = frame.flags.z;
    // Window pixels per traced pixel.
    vec2 scale = vec2(frame.size.zw) / vec2(size);

    uint sample_index = pass.sample_index;
    GSample g;
    g.radiance = vec3(0.0);
    g.albedo = 0u;
    g.normal = 0u;
    g.depth = 1.0;
    g.view_z = 0.0;
    g.motion = vec2(0.0);
    g.material = 0u;
    g.instance = 0xffffffffu;
    g.surface = 0u;
    g.gradient = 0u;
    uint primary = 0u, shadow = 0u, diffuse = 0u, specular = 0u;
    SkyRays sky_rays = SkyRays(0u, 0u);

    vec3 radiance = vec3(0.0);
    // The channels (trace/gbuffer.glsl): the primary hit's next-event estimation, and the
    // radiance before its continuation ray (what comes after is indirect light).
    vec3 direct = vec3(0.0);
    vec3 before_continuation = vec3(0.0);
    bool continued = false;
    // With FRAME_SPECULAR: the specular lobe's part of `direct`, and its share of the primary
    // hit's brdf_eval_cos in the direction of the continuation ray (per colour).
    bool split = (frame.flags.x & FRAME_SPECULAR) != 0u;
    vec3 direct_specular = vec3(0.0);
    vec3 specular_share = vec3(0.0);
    if (traced) {
        // A gradient sample draws last frame's random numbers.
        uint seed_frame = gradient ? frame.counts.x - 1u : frame.counts.x;
        Rng rng = rng_seed(pixel, seed_frame, sample_index);
        // The first sample of a frame goes through the pixel centre, so the G-buffer is stable.
        vec2 jitter = sample_index == 0u ? vec2(0.5) : rng_next2(rng);
        vec2 window = (vec2(pixel) + jitter) * scale;
        vec3 origin, dir;
        camera_ray(window, origin, dir);
        bool in_viewport = all(greaterThanEqual(window, frame.viewport.xy)) && all(lessThan(window, frame.viewport.xy + frame.viewport.zw));
        vec3 throughput = vec3(1.0);
        float cone_width = 0.0;
        float cone_spread = frame.params.w * max(scale.x, scale.y);
        primary += 1u;
        TraceHit hit;
        bool hit_found = in_viewport && trace_closest(origin, dir, 0.0, 1e30, hit);
        // A gradient sample repeats its source's sample of last frame, drawing the source's
        // numbers (and the sky choices of its tile).
        uvec2 source;
        bool repeated = gradient && hit_found && repeat_source(pixel, scale, sample_index, origin, dir, hit, rng, primary, source);
        uvec2 seed_pixel = repeated ? source : pixel;
        if (!hit_found) {
            radiance = environment(dir);
        }
        // A gradient sample that repeats nothing is not compared: no need to shade it.
        hit_found = hit_found && (repeated || !gradient);
        // Vertex `depth` of the path: emission, next-event estimation towards every light and
        // one emitter, then a continuation ray; the environment is found by continuation rays
        // that miss (also after the last vertex, so bounces = 0 is direct light with the sky
        // included), and a continuation ray past the last vertex that hits adds nothing (so
        // the emitter sample of the last vertex counts whole). `bsdf_density` is the density
        // with which the previous vertex chose the ray that reached this one, when it also
        // sampled emitters (the MIS weight of the emission found here).
        float bsdf_density = 0.0;
        // Whether the ray that reached this vertex was a diffuse continuation ray.
        bool diffuse_arrival = false;
        for (uint depth = 0u; hit_found; depth++) {
            cone_width += cone_spread * hit.t;
            Surface s = surface_at(hit, origin, dir, cone_width);
            vec3 v = -dir;
            if (depth == 0u && sample_index == 0u) {
                g.albedo = packUnorm4x8(vec4(s.albedo, s.alpha));
                g.normal = pack_normal(s.normal);
                g.depth = window_depth(frame.projection, s.position);
                g.view_z = -s.position.z;
                // Where the point was last frame (a deforming mesh's: the same point of the
                // triangle in its last shape).
                vec3 previous = previous_position(hit, s.position);
                g.motion = (window_xy(frame.projection, s.position) - window_xy(frame.previous_projection, previous)) / scale;
                g.material = pack_material(s.roughness, s.metalness, s.specular, max(dot(s.normal, v), 0.0));
                g.instance = hit.instance;
                g.surface = materials[instances[hit.instance].material].key;
                g.gradient = repeated ? source.y * size.x + source.x + 1u : 0u;
            }
            vec3 emitted = s.emission;
            if (bsdf_density > 0.0 && s.emitter_density > 0.0) {
                float w = mis_weight(bsdf_density, emitter_solid_angle_density(s, hit.t, abs(dot(s.geometric, dir))));
                emitted -= (1.0 - w) * s.sampled_emission;
            }
            radiance += throughput * emitted;
            // A vertex-lit model's light from every direction (render::trace::vertex_light):
            // the level's light at the model, which the light of emitters and the sky would
            // count a second time.
            vec4 ambient = materials[instances[hit.instance].material].ambient;
            bool ambient_lit = ambient.a > 0.0;
            // Next-event estimation: a sample of every light, of one emitter and of the sky (the
            // sky's taken with the frame's probability, chosen for a tile of pixels together);
            // a baked surface (render::trace::material) only emits, and samples the dynamic
            // lights its bake cannot hold as the game's passes bring them, added to what it
            // shows in display units (render::trace::lights). next_event_add traces the samples'
            // shadow rays.
            vec3 shown = s.baked ? linear_to_srgb(s.emission) : vec3(0.0);
            vec3 brought = vec3(0.0);
            vec3 lit = vec3(0.0);
            vec3 lit_specular = vec3(0.0);
            // The first diffuse bounce on the static world ends the path with radiosity's
            // light (below): no continuation ray weighs the emitter and sky samples there.
            vec3 bounced;
            bool radiosity_vertex = !s.baked && diffuse_arrival && radiosity_at(hit, bounced);
            float sky_chance = ambient_lit || s.baked ? 0.0 : sky_selection(gradient);
            vec3 shadow_origin = offset_ray(s.position, s.geometric);
            NextEvent ne = NextEvent(hit.instance, shown, cone_width, max(cone_spread, 1.0),
                depth < bounces && !radiosity_vertex, !radiosity_vertex, emitter_count > 0u && !ambient_lit, light_count, sky_chance, gradient, seed_pixel, seed_frame, sample_index, depth);
            // One call site of the traversal for every sample (lights 0..light_count - 1, one
            // emitter, the sky): a megakernel inlines each call (bench/pathtrace.md).
            for (uint k = 0u; k < light_count + 2u; k++) {
                ShadowSample n = k < light_count ? light_sample(s, v, ne, k, rng)
                    : k == light_count ? emitter_sample(s, v, ne, rng) : sky_sample_at(s, v, ne, rng);
                next_event_add(n, shadow_origin, s.baked, throughput, k == light_count + 1u, lit, lit_specular, brought, shadow, sky_rays);
            }
            if (s.baked) {
                // Not the surface's albedo times light (a pass that adds brings its colour over
                // any albedo): it stays out of the demodulated channels, unfiltered, as the
                // emission it is added to (denoise/modulate.comp). The path ends.
                lit = throughput * max(srgb_to_linear(shown + brought) - srgb_to_linear(shown), vec3(0.0));
                radiance += lit;
                break;
            }
            radiance += lit;
            if (depth == 0u) {
                direct = lit;
                direct_specular = lit_specular;
            }
            // Radiosity's indirect light (the bounced light only: the direct light was sampled
            // above), and the path ends.
            if (radiosity_vertex) {
                radiance += throughput * brdf_diffuse_albedo(s) * bounced;
                break;
            }
            vec3 l;
            bool chose_specular;
            vec3 u = vec3(rng_next2(rng), rng_next(rng));
            if (!brdf_sample(s, v, u, l, chose_specular)) {
                break;
            }
            float pdf = brdf_pdf(s, v, l);
            if (pdf <= 0.0) {
                break;
            }
            vec3 reflected_specular = brdf_specular_cos(s, v, l);
            vec3 reflected = brdf_diffuse_cos(s, v, l) + reflected_specular;
            if (depth == 0u) {
                specular_share = reflected_specular / max(reflected, vec3(1e-30));
            }
            throughput *= reflected / pdf;
            bsdf_density = emitter_count > 0u && !ambient_lit ? pdf : 0.0;
            if (chose_specular) {
                specular += 1u;
            } else {
                diffuse += 1u;
            }
            diffuse_arrival = !chose_specular;
            if (all(equal(throughput, vec3(0.0)))) {
                break;
            }
            if (depth == 0u) {
                before_continuation = radiance;
                continued = true;
            }
            origin = offset_ray(s.position, s.geometric);
            dir = l;
            // After a bounce the cone spreads as wide as the lobe sampled (textures seen by
            // diffuse rays are read from small levels).
            cone_spread = max(cone_spread, chose_specular ? ggx_alpha(s) : 1.0);
            if (!trace_closest(origin, dir, 0.0, ambient_lit ? ambient.a : 1e30, hit)) {
                if (ambient_lit) {
                    radiance += throughput * ambient.rgb;
                } else {
                    // The sky sample of this vertex, taken with probability `sky_chance`, found
                    // this light too (trace/sky_sampling.glsl).
                    float w = sky_chance > 0.0 ? mis_weight(pdf, sky_chance * sky_density(dir, gradient)) : 1.0;
                    radiance += throughput * environment(dir) * w;
                }
                break;
            }
            if (depth == bounces) {
                break;
            }
        }
    }

    vec3 indirect = continued ? radiance - before_continuation : vec3(0.0);
    vec3 specular_light = vec3(0.0);
    if (split) {
        specular_light = direct_specular + specular_share * indirect;
        direct -= direct_specular;
        indirect -= specular_share * indirect;
    }
    if (recorded && sample_index == 0u) {
        vec3 demodulate = 1.0 / (demodulating_albedo(g.albedo) * float(samples));
        g.radiance = radiance / float(samples);
        g.direct = direct * demodulate;
        g.indirect = indirect * demodulate;
        g.specular = specular_light / (demodulating_reflectance(g.albedo, g.material) * float(samples));
        gbuffer[index] = g;
    } else if (recorded) {
        vec3 demodulate = 1.0 / (demodulating_albedo(gbuffer[index].albedo) * float(samples));
        gbuffer[index].radiance += radiance / float(samples);
        gbuffer[index].direct += direct * demodulate;
        gbuffer[index].indirect += indirect * demodulate;
        gbuffer[index].specular += specular_light / (demodulating_reflectance(gbuffer[index].albedo, gbuffer[index].material) * float(samples));
    }
    // One atomic per subgroup and counter.
    uvec4 rays = subgroupAdd(uvec4(primary, shadow, diffuse, specular));
    uvec2 work = subgroupAdd(uvec2(bvh_nodes_visited, bvh_triangles_tested));
    uvec2 sky = subgroupAdd(uvec2(sky_rays.traced, sky_rays.unoccluded));
    if (subgroupElect()) {
        atomicAdd(counters.primary_rays, rays.x);
        atomicAdd(counters.shadow_rays, rays.y);
        atomicAdd(counters.diffuse_rays, rays.z);
        atomicAdd(counters.specular_rays, rays.w);
        atomicAdd(counters.nodes_visited, work.x);
        atomicAdd(counters.triangles_tested, work.y);
        atomicAdd(counters.sky_rays, sky.x);
        atomicAdd(counters.sky_unoccluded, sky.y);
    }
}

// The tracing pass's invocation `id` (every invocation of a subgroup must call it): in the main
// pass traced pixel `id`'s sample, into its G-buffer record; in the gradient pass (with
// FRAME_GRADIENTS, from the second frame) the gradient sample of stratum `id`, into the
// stratum's record after the pixels' (gradient_record), which shows a miss where the stratum
// has no sample. The gradient samples have a pass of their own, so that their extra primary ray
// and their replays keep no lane of the main pass waiting.
void trace_invocation(uvec2 id) {
    uvec2 size = frame.size.xy;
    bool gradient = pass.gradients != 0u;
    uvec2 pixel = id;
    bool recorded = all(lessThan(id, size));
    bool traced = recorded;
    uint record = id.y * size.x + id.x;
    if (gradient) {
        recorded = all(lessThan(id, gradient_strata(size)));
        pixel = gradient_pixel(id, frame.counts.x);
        traced = recorded && frame.counts.x > 0u && all(lessThan(pixel, size));
        record = recorded ? gradient_record(id, size) : 0u;
    }
    // One call: a megakernel inlines each call site of the path (two made NVIDIA's compiler
    // take minutes).
    trace_pixel(pixel, traced, gradient, recorded, record);
}

#endif
