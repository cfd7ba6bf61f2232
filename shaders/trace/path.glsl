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
// ray brings), demodulated (trace/channels.glsl). The primary hit's record is written as soon
// as it is known (its surface before the next-event samples, its direct light after them)
// and the rest of the path's light is added at its end, so that the path carries nothing of
// the primary hit through its bounces but the specular share (one packed word): the
// megakernel's registers are its occupancy (bench/denoise.md, "The specular channel's
// cost"). With radiosity
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
    return lights[k].params.w < 0.0 ? dynamic_pass_light(s, linear_to_srgb(s.emission), k, rng) : unshadowed(vec3(0.0));
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
// the sky's) and adds its light where it is not occluded to `lit`: through the path's
// `throughput` (its specular lobe's part also to `lit_specular`), or on a baked surface as it
// is (display units).
void next_event_add(ShadowSample n, vec3 origin, bool baked, vec3 throughput, bool sky, inout vec3 lit, inout vec3 lit_specular, inout uint shadow_rays, inout uint sky_rays) {
    if (n.distance > 0.0) {
        shadow_rays += 1u;
        sky_rays += sky ? SKY_RAY_TRACED : 0u;
        if (trace_any(origin, n.dir, 0.0, n.distance)) {
            return;
        }
        sky_rays += sky ? SKY_RAY_UNOCCLUDED : 0u;
    }
    if (baked) {
        lit += n.light;
    } else {
        lit += throughput * n.light;
        lit_specular += throughput * n.light * unpack_share(n.specular);
    }
}

// Uses camera_ray and window_xy.
#include "trace/forward_projection.glsl"

// The record of a primary ray that met nothing (and of a gradient sample that repeats
// nothing), without light: every record starts as it.
GSample missed_sample() {
    return GSample(vec3(0.0), 0u, vec3(0.0), 0u, vec3(0.0), 1.0, vec3(0.0), 0.0, vec2(0.0), 0u, 0xffffffffu, 0u, 0u, uint[2](0u, 0u));
}

// Adds light to G-buffer record `index`, `weight` (1 / samples) of it: `radiance` whole, and
// demodulated by the record's primary hit (trace/channels.glsl) the diffuse lobe's `direct`
// and `indirect` light and the specular lobe's `specular` light.
void record_light(uint index, float weight, vec3 radiance, vec3 direct, vec3 indirect, vec3 specular) {
    uint albedo = gbuffer[index].albedo;
    vec3 demodulate = weight / demodulating_albedo(albedo);
    gbuffer[index].radiance += weight * radiance;
    gbuffer[index].direct += direct * demodulate;
    gbuffer[index].indirect += indirect * demodulate;
    gbuffer[index].specular += specular * (weight / demodulating_reflectance(albedo, gbuffer[index].material));
}

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
    float weight = 1.0 / float(samples);
    // Rays counted (render::trace::stats): primary, shadow, the continuation rays in one word
    // (diffuse in bits 0-15, specular in 16-31: at most 9 of each) and the sky's (sky_sampling.glsl).
    uint primary = 0u, shadow = 0u, continuation = 0u, sky_rays = 0u;
    if (recorded && sample_index == 0u) {
        gbuffer[index] = missed_sample();
    }

    // The light not yet added to the record: after the primary hit's next-event samples
    // (added with its direct light), what its continuation ray brought (indirect light).
    vec3 radiance = vec3(0.0);
    bool continued = false;
    // With FRAME_SPECULAR the specular lobe's share of the primary hit's brdf_eval_cos in the
    // direction of its continuation ray (pack_share).
    bool split = (frame.flags.x & FRAME_SPECULAR) != 0u;
    uint specular_share = 0u;
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
            if (depth == 0u && sample_index == 0u && recorded) {
                GSample g = missed_sample();
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
                gbuffer[index] = g;
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
            vec3 lit = vec3(0.0);
            vec3 lit_specular = vec3(0.0);
            // The first diffuse bounce on the static world ends the path with radiosity's
            // light (below): no continuation ray weighs the emitter and sky samples there.
            vec3 bounced;
            bool radiosity_vertex = !s.baked && diffuse_arrival && radiosity_at(hit, bounced);
            float sky_chance = ambient_lit || s.baked ? 0.0 : sky_selection(gradient);
            vec3 shadow_origin = offset_ray(s.position, s.geometric);
            NextEvent ne = NextEvent(hit.instance, cone_width, max(cone_spread, 1.0),
                depth < bounces && !radiosity_vertex, !radiosity_vertex, emitter_count > 0u && !ambient_lit, light_count, sky_chance, gradient, seed_pixel, seed_frame, sample_index, depth);
            // One call site of the traversal for every sample (lights 0..light_count - 1, one
            // emitter, the sky): a megakernel inlines each call (bench/pathtrace.md).
            for (uint k = 0u; k < light_count + 2u; k++) {
                ShadowSample n = k < light_count ? light_sample(s, v, ne, k, rng)
                    : k == light_count ? emitter_sample(s, v, ne, rng) : sky_sample_at(s, v, ne, rng);
                next_event_add(n, shadow_origin, s.baked, throughput, k == light_count + 1u, lit, lit_specular, shadow, sky_rays);
            }
            if (s.baked) {
                // Not the surface's albedo times light (a pass that adds brings its colour over
                // any albedo): it stays out of the demodulated channels, unfiltered, as the
                // emission it is added to (denoise/modulate.comp). The path ends.
                vec3 shown = linear_to_srgb(s.emission);
                radiance += throughput * max(srgb_to_linear(shown + lit) - srgb_to_linear(shown), vec3(0.0));
                break;
            }
            radiance += lit;
            if (depth == 0u) {
                // The primary hit's emission and direct light go to its record now.
                vec3 direct_specular = split ? lit_specular : vec3(0.0);
                if (recorded) {
                    record_light(index, weight, radiance, lit - direct_specular, vec3(0.0), direct_specular);
                }
                radiance = vec3(0.0);
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
            if (depth == 0u && split) {
                specular_share = pack_share(reflected_specular / max(reflected, vec3(1e-30)));
            }
            throughput *= reflected / pdf;
            bsdf_density = emitter_count > 0u && !ambient_lit ? pdf : 0.0;
            continuation += chose_specular ? 0x10000u : 1u;
            diffuse_arrival = !chose_specular;
            if (all(equal(throughput, vec3(0.0)))) {
                break;
            }
            continued = true;
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

    if (recorded) {
        // What the continuation ray of the primary hit brought is indirect light, its
        // specular lobe's share apart.
        vec3 indirect = continued ? radiance : vec3(0.0);
        vec3 indirect_specular = unpack_share(specular_share) * indirect;
        record_light(index, weight, radiance, vec3(0.0), indirect - indirect_specular, indirect_specular);
    }
    // One atomic per subgroup and counter.
    uvec4 rays = subgroupAdd(uvec4(primary, shadow, continuation & 0xffffu, continuation >> 16));
    uvec2 work = subgroupAdd(uvec2(bvh_nodes_visited, bvh_triangles_tested));
    uvec2 sky = subgroupAdd(uvec2(sky_rays & 0xffffu, sky_rays >> 16));
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
