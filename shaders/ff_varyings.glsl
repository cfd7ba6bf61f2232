// What ff.vert passes to ff.frag. Colours come twice: interpolated, and from the provoking
// vertex (flat shading, selected by the FLAT key bit).
#ifdef FF_FRAGMENT
#define VARYING in
#else
#define VARYING out
#endif

layout(location = 0) VARYING vec4 v_front;      // front primary colour
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
