// What ff.vert passes to ff.frag. Colours come twice: interpolated, and from the provoking
// vertex (flat shading, selected by the FLAT key bit). With FF_LEAN (ff_lean.vert and
// ff_lean.frag, for the keys of ShaderKey::lean) only the primary colour and unit 0's
// coordinates are interpolated: the rest are private variables that
// ff_varyings_out leaves unread and ff_varyings_in sets to what such keys would read
// (a back colour equal to the front one, a zero secondary colour).
#ifdef FF_FRAGMENT
#define VARYING in
#else
#define VARYING out
#endif

layout(location = 0) VARYING vec4 v_front;      // front primary colour
#ifdef FF_LEAN
layout(location = 4) VARYING vec4 v_tex0;
vec4 v_front2, v_back, v_back2, f_front, f_front2, f_back, f_back2, v_misc, v_raster;
vec4 v_tex[MAX_UNITS];
#else
layout(location = 1) VARYING vec4 v_front2;     // front secondary colour
layout(location = 2) VARYING vec4 v_back;       // back primary colour
layout(location = 3) VARYING vec4 v_back2;      // back secondary colour
layout(location = 4) VARYING vec4 v_tex[MAX_UNITS];
layout(location = 8) flat VARYING vec4 f_front;
layout(location = 9) flat VARYING vec4 f_front2;
layout(location = 10) flat VARYING vec4 f_back;
layout(location = 11) flat VARYING vec4 f_back2;
layout(location = 12) VARYING vec4 v_misc;      // fog distance, unused, point size, unused
// Expanded lines: offset (x, y), stipple distance, distance across; points: offset from the
// centre in pixels (x, y).
layout(location = 13) noperspective VARYING vec4 v_raster;
#endif

#ifdef FF_FRAGMENT
// Called first in ff.frag's main.
void ff_varyings_in() {
#ifdef FF_LEAN
    v_back = v_front;
    f_front = v_front;
    f_back = v_front;
    v_front2 = vec4(0.0);
    v_back2 = vec4(0.0);
    f_front2 = vec4(0.0);
    f_back2 = vec4(0.0);
    v_misc = vec4(0.0);
    v_raster = vec4(0.0);
    v_tex[0] = v_tex0;
    for (int i = 1; i < MAX_UNITS; i++) {
        v_tex[i] = vec4(0.0);
    }
#endif
}
#else
// The colours of a vertex, interpolated and for flat shading (ff.vert and translated
// programs' vertex stages).
void ff_colors_out(vec4 front, vec4 front2, vec4 back, vec4 back2) {
    v_front = front;
    v_front2 = front2;
    v_back = back;
    v_back2 = back2;
    f_front = front;
    f_front2 = front2;
    f_back = back;
    f_back2 = back2;
}

// Called last in ff.vert's main.
void ff_varyings_out() {
#ifdef FF_LEAN
    v_tex0 = v_tex[0];
#endif
}
#endif
