#version 450
// Fixed-function vertex stage (OpenGL 1.5 section 2.10-2.14): see src/render/raster/ff/mod.rs
// for the interface (vertex layout, descriptor bindings, specialisation constants).

layout(location = 0) in vec4 in_position;
layout(location = 1) in vec4 in_color;
layout(location = 5) in vec4 in_texcoord0;

layout(set = 0, binding = 0, std140) uniform Draw {
    mat4 mvp;
} u;

layout(location = 0) out vec4 v_color;
layout(location = 1) out vec4 v_texcoord0;

void main() {
    gl_Position = u.mvp * in_position;
    // OpenGL's window y grows upwards and its clip-space depth is [-w, w]; Vulkan's grows
    // downwards with depth [0, w]: the renderer flips y with a negative viewport height and the
    // depth range is mapped here.
    gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5;
    v_color = in_color;
    v_texcoord0 = in_texcoord0;
}
