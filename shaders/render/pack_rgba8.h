// pack_rgba8.comp, recorded by src/render/renderer.cpp (Renderer::record into an application's
// 8-bit image): a frame's colours as RGBA (or BGRA) words, 256 pixels per workgroup.
#ifndef VKSPLAT_RENDER_PACK_RGBA8_H
#define VKSPLAT_RENDER_PACK_RGBA8_H

#include "shaders/common/buffers.h"

SHADER_NAMESPACE_BEGIN(render)

struct PackRgba8Push {
    Vec4s color_alpha;
    Uints packed;  // out: one word per pixel, bytes in memory order r, g, b, a (or b, g, r, a)
    uint pixels;
    uint bgra;
};

SHADER_NAMESPACE_END

#endif
