#version 450
// Fixed-function fragment stage (OpenGL 1.5 sections 3.8-3.10, 4.1): see
// src/render/raster/ff/mod.rs for the interface.

layout(constant_id = 0) const uint KEY0 = 0u;
const uint TEXTURE_2D = 1u;

layout(set = 0, binding = 1) uniform sampler2D tex2d0;

layout(location = 0) in vec4 v_color;
layout(location = 1) in vec4 v_texcoord0;

layout(location = 0) out vec4 out_color;

void main() {
    vec4 color = v_color;
    if ((KEY0 & TEXTURE_2D) != 0u) {
        color *= texture(tex2d0, v_texcoord0.st / v_texcoord0.q);
    }
    out_color = color;
}
