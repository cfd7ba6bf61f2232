// The per-fragment operations of the fixed-function fragment stage that also run around a
// program's fragment shader (OpenGL 2.0 section 3.11: stipples, antialiasing coverage and the
// alpha test stay fixed-function). Included by ff.frag and by the fragment stages
// src/translate/glsl generates, after ff_key.glsl, ff_uniforms.glsl, ff_varyings.glsl and
// gl_compare.glsl.

// Line stipple, polygon stipple: whether the fragment is kept (sections 3.4.2, 3.5.2).
bool stippled_out() {
    if (GENERAL(LINE_STIPPLE) != 0u) {
        // The stipple distance is the fragment's count along the run plus one half at fragment
        // centres (ff/convert.rs aligns it), so interpolation error cannot change the count.
        uint count = uint(max(v_raster.z, 0.0));
        uint bit = (count / uint(max(u.raster.z, 1.0) + 0.5)) % 16u;
        if (((u.stipple.x >> bit) & 1u) == 0u) {
            return true;
        }
    }
    if (GENERAL(POLYGON_STIPPLE) != 0u) {
        // Window rows count from the bottom: GL y = height - Vulkan y.
        uint x = uint(gl_FragCoord.x) % 32u;
        uint y = uint(max(float(u.stipple.y) - gl_FragCoord.y, 0.0)) % 32u;
        uint row = u.polygon_stipple[y / 4u][y % 4u];
        if (((row >> (31u - x)) & 1u) == 0u) {
            return true;
        }
    }
    return false;
}

// Antialiasing coverage (sections 3.3.2, 3.4.3, 3.12): the area of the pixel inside the
// point's circle or the line's rectangle, approximated by the distance to its edge; the
// fragment's alpha is multiplied by it.
float smooth_coverage() {
    if (GENERAL(SMOOTH) != 0u) {
        uint primitive = GENERAL(PRIMITIVE);
        if (primitive == PRIM_POINT) {
            return clamp(v_misc.z * 0.5 + 0.5 - length(v_raster.xy), 0.0, 1.0);
        } else if (primitive == PRIM_LINE) {
            return clamp(u.raster.y * 0.5 + 0.5 - abs(v_raster.w), 0.0, 1.0);
        }
    }
    return 1.0;
}

// The alpha test (section 4.1.4): whether a fragment of alpha `a` is discarded.
bool alpha_tested_out(float a) {
    uint alpha_test = GENERAL(ALPHA_TEST);
    return alpha_test != 0u && !compare(alpha_test - 1u, a, clamp(u.raster.x, 0.0, 1.0));
}
