#version 460
// Packs the blended colour and alpha into 8-bit RGBA (or BGRA) words for an application's
// 8-bit image or buffer (render/render_target.hpp). Rounds to nearest like the PNG writer.
#extension GL_GOOGLE_include_directive : require

#include "shaders/render/pack_rgba8.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { PackRgba8Push pc; };

void main() {
    for (uint i = gl_GlobalInvocationID.x; i < pc.pixels; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        vec4 value = pc.color_alpha.v[i];
        // NaN compares false, so it selects 0, as in the PNG writer.
        value = mix(vec4(0.0), min(value, vec4(1.0)), greaterThan(value, vec4(0.0)));
        if (pc.bgra != 0u) value = value.bgra;
        pc.packed.v[i] = packUnorm4x8(value);
    }
}
