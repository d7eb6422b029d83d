// vksplat_renderer: a Renderer that renders into the caller's memory or records into the caller's
// command buffer, image or buffer.
#include <cmath>
#include <cstring>
#include <string>

#include "capi/call.hpp"
#include "capi/conversions.hpp"
#include "capi/handles.hpp"

using vksplat::capi::guarded;
using vksplat::capi::out_pointer;
using vksplat::capi::require;

namespace {

// The camera the caller gave, checked (InputError naming the problem) before any size is computed.
vksplat::Camera checked_camera(const vksplat_camera* camera) {
    vksplat::Camera checked = vksplat::capi::to_camera(require(camera, "camera"), "vksplat_camera");
    checked.validate();
    return checked;
}

// Refuses a caller's buffer smaller than the picture needs, before anything is rendered.
void check_size(const char* what, size_t given, size_t needed, const vksplat::Camera& camera, const char* layout) {
    if (given < needed)
        throw std::invalid_argument(std::string(what) + " is " + std::to_string(given) + " bytes; a " +
                                    std::to_string(camera.width) + " x " + std::to_string(camera.height) + " " +
                                    layout + " picture needs " + std::to_string(needed));
}

// A [0, 1] value as an 8-bit level, clamped (NaN to 0) and rounded to nearest, as the PNG writer
// (io::write_png_rgb) does.
uint8_t level(float value) {
    if (!(value > 0.0f)) return 0;
    return static_cast<uint8_t>(std::lround(std::fmin(value, 1.0f) * 255.0f));
}

}  // namespace

extern "C" {

vksplat_render_settings vksplat_render_settings_default(void) {
    const vksplat::RenderSettings defaults;
    vksplat_render_settings out{};
    for (int c = 0; c < 3; ++c) out.background[c] = defaults.background[static_cast<size_t>(c)];
    out.max_sh_degree = defaults.max_sh_degree;
    return out;
}

vksplat_status vksplat_renderer_create(vksplat_context* context, vksplat_renderer** renderer, vksplat_error* error) {
    return guarded(__func__, error, [&] {
        vksplat_renderer*& out = out_pointer(renderer, "renderer");
        out = new vksplat_renderer(require(context, "context").context);
    });
}

vksplat_status vksplat_renderer_set_scene(vksplat_renderer* renderer, const vksplat_scene* scene,
                                          vksplat_error* error) {
    return guarded(__func__, error, [&] {
        vksplat::Renderer& target = require(renderer, "renderer").renderer;
        target.set_scene(require(scene, "scene").cloud);
    });
}

void vksplat_renderer_destroy(vksplat_renderer* renderer) { delete renderer; }

vksplat_status vksplat_render(vksplat_renderer* renderer, const vksplat_camera* camera,
                              const vksplat_render_settings* settings, const vksplat_image* image,
                              vksplat_error* error) {
    return guarded(__func__, error, [&] {
        vksplat::Renderer& source = require(renderer, "renderer").renderer;
        const vksplat_image& out = require(image, "image");
        const vksplat::Camera view = checked_camera(camera);
        const size_t pixels = size_t(view.width) * size_t(view.height);
        if (!out.pixels) throw std::invalid_argument("image->pixels is NULL");
        if (out.format == VKSPLAT_PIXELS_RGBA8)
            check_size("image->pixels_size", out.pixels_size, pixels * 4, view, "RGBA8");
        else if (out.format == VKSPLAT_PIXELS_RGB_FLOAT)
            check_size("image->pixels_size", out.pixels_size, pixels * 3 * sizeof(float), view, "RGB float");
        else
            throw std::invalid_argument("image->format " + std::to_string(int(out.format)) + " is no vksplat_pixel_format");
        if (out.depth) check_size("image->depth_size", out.depth_size, pixels * sizeof(float), view, "depth");
        if (out.alpha) check_size("image->alpha_size", out.alpha_size, pixels * sizeof(float), view, "alpha");

        const vksplat::RenderOutput rendered = source.render(view, vksplat::capi::to_settings(settings));
        if (out.format == VKSPLAT_PIXELS_RGB_FLOAT) {
            std::memcpy(out.pixels, rendered.rgb.data(), pixels * 3 * sizeof(float));
        } else {
            auto* bytes = static_cast<uint8_t*>(out.pixels);
            for (size_t i = 0; i < pixels; ++i) {
                for (size_t c = 0; c < 3; ++c) bytes[i * 4 + c] = level(rendered.rgb[i * 3 + c]);
                bytes[i * 4 + 3] = level(rendered.alpha[i]);
            }
        }
        if (out.depth) std::memcpy(out.depth, rendered.depth.data(), pixels * sizeof(float));
        if (out.alpha) std::memcpy(out.alpha, rendered.alpha.data(), pixels * sizeof(float));
    });
}

vksplat_status vksplat_record(vksplat_renderer* renderer, VkCommandBuffer command_buffer,
                              const vksplat_camera* camera, const vksplat_render_settings* settings,
                              const vksplat_target* target, vksplat_error* error) {
    return guarded(__func__, error, [&] {
        vksplat::Renderer& source = require(renderer, "renderer").renderer;
        const vksplat_target& into = require(target, "target");
        if (command_buffer == VK_NULL_HANDLE) throw std::invalid_argument("command_buffer is VK_NULL_HANDLE");
        vksplat::RenderTarget cpp;
        cpp.image = into.image;
        cpp.buffer = into.buffer;
        cpp.offset = into.offset;
        cpp.format = into.format;
        cpp.old_layout = into.old_layout;
        cpp.final_layout = into.final_layout;
        source.record(command_buffer, checked_camera(camera), vksplat::capi::to_settings(settings), cpp);
    });
}

}  // extern "C"
