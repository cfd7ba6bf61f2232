// The entry point of a translated vertex shader (src/translate/glsl): runs the program's
// main (renamed u_main) between what the fixed-function stage around it does. The rewrite
// defines GLRT_BEFORE_MAIN (statements: attributes bound to index 0 read the position).

void main() {
    glrt_ClipVertex = glrt_ModelViewMatrix * glrt_Vertex;
    gl_PointSize = glrt_Point.size;
    for (int i = 0; i < glrt_MaxTextureCoords; i++) {
        glrt_TexCoord[i] = vec4(0.0, 0.0, 0.0, 1.0);
    }
    GLRT_BEFORE_MAIN
    u_main();
    if (glrt_Flags.x == 0u) {
        gl_PointSize = glrt_Point.size;
    }

    // Colours are clamped to [0, 1] (OpenGL 2.0 section 2.14.6); back faces take the back
    // colours only with GL_VERTEX_PROGRAM_TWO_SIDE (the key's TWO_SIDE bit for a program).
    bool two_side = GENERAL(TWO_SIDE) != 0u;
    vec4 front = clamp(glrt_FrontColor, 0.0, 1.0);
    vec4 front2 = clamp(glrt_FrontSecondaryColor, 0.0, 1.0);
    vec4 back = two_side ? clamp(glrt_BackColor, 0.0, 1.0) : front;
    vec4 back2 = two_side ? clamp(glrt_BackSecondaryColor, 0.0, 1.0) : front2;
    ff_colors_out(front, front2, back, back2);
    for (int i = 0; i < MAX_UNITS; i++) {
        v_tex[i] = glrt_TexCoord[i];
    }
    v_misc = vec4(glrt_FogFragCoord, 0.0, gl_PointSize, 0.0);
    v_raster = vec4(0.0);

    // User clip planes (section 2.12) against gl_ClipVertex, in eye space.
    for (int i = 0; i < MAX_CLIP_PLANES; i++) {
        bool on = (field(KEY_CLIP, CLIP_MASK_SHIFT, CLIP_MASK_BITS) & (1u << uint(i))) != 0u;
        gl_ClipDistance[i] = on ? dot(u.clip_plane[i], glrt_ClipVertex) : 1.0;
    }

    // OpenGL's clip-space depth is [-w, w], Vulkan's [0, w].
    gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5;
}
