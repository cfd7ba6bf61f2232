// Radiosity's indirect light on the static world (render::trace::radiosity): the path's first
// diffuse bounce that hits a static-world triangle reads it there (trace/path.glsl).
// Include after trace/scene.glsl and trace/triangles.glsl.

#ifndef TRACE_RADIOSITY_GLSL
#define TRACE_RADIOSITY_GLSL

// Whether `hit` is on a triangle with radiosity's light (a static-world instance in a frame
// with radiosity) and, if so, the indirect irradiance / pi there: its corners' values
// interpolated by the hit's barycentrics.
bool radiosity_at(TraceHit hit, out vec3 value) {
    value = vec3(0.0);
    Instance inst = instances[hit.instance];
    uint first = materials[inst.material].radiosity;
    if (first == NO_RADIOSITY) {
        return false;
    }
    uint index = first + hit.triangle - inst.first_triangle;
    vec3 weights = vec3(1.0 - hit.bary.x - hit.bary.y, hit.bary);
    for (uint k = 0u; k < 3u; k++) {
        vec3 corner = vec3(radiosity_triangles[index].corner[3u * k], radiosity_triangles[index].corner[3u * k + 1u], radiosity_triangles[index].corner[3u * k + 2u]);
        value += weights[k] * corner;
    }
    return true;
}

#endif
