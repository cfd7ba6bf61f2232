// The entry point of a translated fragment shader (src/translate/glsl): the fixed-function
// operations before (stipples, colour selection by facing and shading) and after (coverage,
// alpha test, clamping) run around the program's main (renamed u_main). The rewrite defines
// GLRT_FRAGMENT_OUTPUT (glrt_FragColor or glrt_FragData[0]).

void main() {
    if (stippled_out()) {
        discard;
    }
    uint facing = GENERAL(FACING);
    bool front = facing == FACING_RASTERIZER ? gl_FrontFacing : facing == FACING_FRONT;
    bool flat_shaded = GENERAL(FLAT) != 0u;
    glrt_Color = flat_shaded ? (front ? f_front : f_back) : (front ? v_front : v_back);
    glrt_SecondaryColor = flat_shaded ? (front ? f_front2 : f_back2) : (front ? v_front2 : v_back2);
    glrt_FrontFacing = front;
    // Window y counts from the bottom in GL: GL y = framebuffer height - Vulkan y.
    glrt_FragCoord = vec4(gl_FragCoord.x, float(u.stipple.y) - gl_FragCoord.y, gl_FragCoord.zw);
    for (int i = 0; i < MAX_UNITS; i++) {
        glrt_TexCoord[i] = v_tex[i];
    }
    glrt_FogFragCoord = v_misc.x;
    // Points the fixed-function stage expanded carry their offset from the centre in pixels.
    glrt_PointCoord = GENERAL(PRIMITIVE) == PRIM_POINT
        ? vec2(0.5) + vec2(v_raster.x, -v_raster.y) / max(v_misc.z, 1.0)
        : gl_PointCoord;
    glrt_FragData[0] = vec4(0.0);

    u_main();

    vec4 color = GLRT_FRAGMENT_OUTPUT;
    // The renderer's height fog (src/render/fog), after the program's own.
    color.rgb = height_fog_apply(u.height_fog, gl_FragCoord.xyz, color.rgb);
    color.a *= smooth_coverage();
    if (alpha_tested_out(color.a)) {
        discard;
    }
    out_color = clamp(color, 0.0, 1.0);
}
