// The viewer's loop: input -> CameraControls -> Renderer::record into the acquired swapchain
// image -> present. One frame in flight: the CPU waits for the last frame before recording the
// next, which Renderer::record asks for anyway (it must be submitted before the next record).
#include "viewer.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/quaternion.hpp>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "display_modes.hpp"
#include "frustum_splats.hpp"
#include "glfw_window.hpp"
#include "hud_overlay.hpp"
#include "swapchain.hpp"
#include "vksplat/camera/camera_controls.hpp"
#include "vk_result_check.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::viewer {
namespace {

// What the keys do: printed by H and at the start, named in the title.
constexpr const char* kKeys =
    "keys: Tab/F orbit or fly | W A S D Q E fly | N/right, P/left the next or previous dataset camera | "
    "+/- zoom | Space fly through the dataset cameras | V their frustums | B the --compare scene and back | "
    "0 1 2 3 SH degree | [ ] splat scale | M splats, points or ellipsoids | "
    "C screenshot (vksplat_view_NNN.png here) | H the keys, then no HUD | Esc quit";

// Seconds the fly-through takes from one dataset camera to the next.
constexpr double kFlySeconds = 1.5;

// The camera a fraction t of the way from a to b: centre along the line, rotation along the
// shortest arc, focal lengths in between; a's picture size.
Camera between(const Camera& a, const Camera& b, double t) {
    Camera c = a;
    const glm::dquat q = glm::slerp(glm::quat_cast(a.rotation), glm::quat_cast(b.rotation), t);
    c.rotation = glm::mat3_cast(q);
    const glm::dvec3 centre = glm::mix(a.centre(), b.centre(), t);
    c.translation = -(c.rotation * centre);
    c.fx = glm::mix(a.fx, b.fx * a.width / b.width, t);
    c.fy = glm::mix(a.fy, b.fy * a.height / b.height, t);
    return c;
}

// The first vksplat_view_NNN.png in the current folder that does not exist yet, so that a
// screenshot never replaces a file.
std::filesystem::path next_screenshot() {
    for (int n = 1;; ++n) {
        char name[32];
        std::snprintf(name, sizeof(name), "vksplat_view_%03d.png", n);
        if (!std::filesystem::exists(name)) return name;
    }
}

// The command buffer, fence and acquire semaphore of the one frame in flight.
struct FrameSync {
    VkDevice device;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer commands = VK_NULL_HANDLE;
    VkFence done = VK_NULL_HANDLE;
    VkSemaphore acquired = VK_NULL_HANDLE;

    FrameSync(VkDevice d, uint32_t family) : device(d) {
        VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool_info.queueFamilyIndex = family;
        check(vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        check(vkAllocateCommandBuffers(device, &alloc, &commands), "vkAllocateCommandBuffers");
        VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;
        check(vkCreateFence(device, &fence_info, nullptr, &done), "vkCreateFence");
        VkSemaphoreCreateInfo semaphore_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        check(vkCreateSemaphore(device, &semaphore_info, nullptr, &acquired), "vkCreateSemaphore");
    }
    ~FrameSync() {
        vkDestroySemaphore(device, acquired, nullptr);
        vkDestroyFence(device, done, nullptr);
        vkDestroyCommandPool(device, pool, nullptr);
    }
    FrameSync(const FrameSync&) = delete;
    FrameSync& operator=(const FrameSync&) = delete;
};

class Viewer {
public:
    Viewer(const ViewerOptions& options, GaussianCloud cloud, std::vector<Camera> cameras,
           std::optional<GaussianCloud> compare)
        : options_(options),
          cameras_(std::move(cameras)),
          window_(options.width, options.height, "vksplat view", options.validation),
          context_(window_.lend()),
          renderer_(context_),
          sync_(window_.device(), window_.queue_family()),
          hud_(window_),
          controls_(start_controls(cloud)) {
        gaussians_ = cloud.size();
        hud_state_ = options.hud ? Hud::status : Hud::none;
        renderer_.set_scene(cloud);
        // Frustums a twentieth of the first view's distance deep, edges a hundredth of that thick;
        // dots for M's points a five-hundredth of it.
        point_size_ = controls_.distance() / 500.0;
        if (!cameras_.empty()) {
            const double depth = controls_.distance() / 20.0;
            frustums_ = frustum_splats(cameras_, depth, depth / 100.0, cloud.sh_degree);
        }
        scene_ = std::move(cloud);
        // A renderer of its own, so that B switches at once, without uploading a scene again.
        if (compare) {
            compare_renderer_ = std::make_unique<Renderer>(context_);
            compare_renderer_->set_scene(*compare);
            compare_gaussians_ = compare->size();
        }
        settings_.background = options.background;
        if (!cameras_.empty()) show_dataset_camera(0);
        glfwSetWindowUserPointer(window_.window(), this);
        glfwSetKeyCallback(window_.window(), [](GLFWwindow* w, int key, int, int action, int mods) {
            static_cast<Viewer*>(glfwGetWindowUserPointer(w))->on_key(key, action, mods);
        });
        glfwSetMouseButtonCallback(window_.window(), [](GLFWwindow* w, int button, int action, int mods) {
            static_cast<Viewer*>(glfwGetWindowUserPointer(w))->on_button(button, action, mods);
        });
        glfwSetCursorPosCallback(window_.window(), [](GLFWwindow* w, double x, double y) {
            static_cast<Viewer*>(glfwGetWindowUserPointer(w))->on_cursor(x, y);
        });
        glfwSetScrollCallback(window_.window(), [](GLFWwindow* w, double, double dy) {
            static_cast<Viewer*>(glfwGetWindowUserPointer(w))->on_scroll(dy);
        });
        // A resized or uncovered window needs a new picture.
        glfwSetFramebufferSizeCallback(window_.window(), [](GLFWwindow* w, int, int) {
            static_cast<Viewer*>(glfwGetWindowUserPointer(w))->dirty_ = true;
        });
        glfwSetWindowRefreshCallback(window_.window(), [](GLFWwindow* w) {
            static_cast<Viewer*>(glfwGetWindowUserPointer(w))->dirty_ = true;
        });
    }

    ~Viewer() { vkDeviceWaitIdle(window_.device()); }

    int run() {
        auto last = std::chrono::steady_clock::now();
        while (!glfwWindowShouldClose(window_.window())) {
            // Redraw only when something changed: a CPU driver has better things to do.
            if (dirty_ || flying() || touring_) glfwPollEvents(); else glfwWaitEvents();
            const auto now = std::chrono::steady_clock::now();
            const double seconds = std::chrono::duration<double>(now - last).count();
            last = now;
            fly(std::min(seconds, 0.1));
            fly_through(seconds);
            int width = 0, height = 0;
            glfwGetFramebufferSize(window_.window(), &width, &height);
            if (width == 0 || height == 0 || !dirty_) continue;  // minimised, or nothing new
            draw(VkExtent2D{uint32_t(width), uint32_t(height)});
        }
        return 0;
    }

private:
    CameraControls start_controls(const GaussianCloud& cloud) const {
        const glm::dvec3 up = options_.up ? glm::dvec3((*options_.up)[0], (*options_.up)[1], (*options_.up)[2])
                                          : CameraControls::up_of(cameras_, {0, 0, 1});
        return CameraControls::framing(cloud.positions, up);
    }

    bool flying() const {
        for (int key : {GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D, GLFW_KEY_Q, GLFW_KEY_E})
            if (glfwGetKey(window_.window(), key) == GLFW_PRESS) return true;
        return false;
    }

    // W/S forward and back, A/D left and right, E/Q up and down: one focus distance a second.
    void fly(double seconds) {
        glm::dvec3 move(0.0);
        auto held = [&](int key) { return glfwGetKey(window_.window(), key) == GLFW_PRESS ? 1.0 : 0.0; };
        move.x = held(GLFW_KEY_D) - held(GLFW_KEY_A);
        move.y = held(GLFW_KEY_E) - held(GLFW_KEY_Q);
        move.z = held(GLFW_KEY_W) - held(GLFW_KEY_S);
        if (move == glm::dvec3(0.0)) return;
        controls_.move(move, seconds);
        dataset_index_ = -1;
        dirty_ = true;
    }

    // Space: glides from dataset camera to dataset camera, kFlySeconds each, until a key or drag.
    void fly_through(double seconds) {
        if (!touring_ || cameras_.size() < 2) return;
        tour_ += seconds / kFlySeconds;
        const size_t n = cameras_.size();
        const size_t from = size_t(tour_) % n;
        controls_.jump_to(between(cameras_[from], cameras_[(from + 1) % n], tour_ - std::floor(tour_)),
                          controls_.distance());
        dataset_index_ = int(from);
        dirty_ = true;
    }

    void show_dataset_camera(int index) {
        dataset_index_ = (index % int(cameras_.size()) + int(cameras_.size())) % int(cameras_.size());
        controls_.jump_to(cameras_[size_t(dataset_index_)], controls_.distance());
        dirty_ = true;
    }

    void on_key(int key, int action, int) {
        if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
        if (key == GLFW_KEY_SPACE && action == GLFW_PRESS && cameras_.size() > 1) {
            touring_ = !touring_;
            tour_ = std::max(dataset_index_, 0);
            dirty_ = true;
            return;
        }
        touring_ = false;
        switch (key) {
            case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_.window(), GLFW_TRUE); break;
            case GLFW_KEY_TAB:
            case GLFW_KEY_F:
                controls_.set_mode(controls_.mode() == CameraControls::Mode::orbit ? CameraControls::Mode::fly
                                                                                   : CameraControls::Mode::orbit);
                break;
            case GLFW_KEY_N:
            case GLFW_KEY_RIGHT:
                if (!cameras_.empty()) show_dataset_camera(dataset_index_ + 1);
                break;
            case GLFW_KEY_P:
            case GLFW_KEY_LEFT:
                if (!cameras_.empty()) show_dataset_camera(dataset_index_ < 0 ? 0 : dataset_index_ - 1);
                break;
            case GLFW_KEY_EQUAL:
            case GLFW_KEY_KP_ADD: zoom(1); break;
            case GLFW_KEY_MINUS:
            case GLFW_KEY_KP_SUBTRACT: zoom(-1); break;
            case GLFW_KEY_0:
            case GLFW_KEY_1:
            case GLFW_KEY_2:
            case GLFW_KEY_3: settings_.max_sh_degree = key - GLFW_KEY_0; break;
            case GLFW_KEY_C: screenshot(); return;
            case GLFW_KEY_V:
                if (cameras_.empty()) return;
                showing_frustums_ = !showing_frustums_;
                upload_scene();
                break;
            case GLFW_KEY_LEFT_BRACKET:
            case GLFW_KEY_RIGHT_BRACKET:
                splat_scale_ *= key == GLFW_KEY_RIGHT_BRACKET ? 1.25 : 0.8;
                upload_scene();
                break;
            case GLFW_KEY_M:
                display_mode_ = next(display_mode_);
                upload_scene();
                break;
            case GLFW_KEY_B:
                if (!compare_renderer_) return;
                showing_compare_ = !showing_compare_;
                break;
            case GLFW_KEY_H:
                hud_state_ = hud_state_ == Hud::status ? Hud::keys : hud_state_ == Hud::keys ? Hud::none : Hud::status;
                if (hud_state_ == Hud::keys) std::printf("%s\n", kKeys);
                std::fflush(stdout);
                break;
            default: return;
        }
        dirty_ = true;
    }

    // The scene as the display mode, splat scale and frustum switch say (the frustums keep their
    // own look, added after).
    void upload_scene() {
        GaussianCloud shown = display_cloud(scene_, display_mode_, splat_scale_, point_size_);
        if (showing_frustums_)
            for (size_t i = 0; i < frustums_.size(); ++i) shown.append(frustums_, i);
        renderer_.set_scene(shown);
    }

    // The view as it is on screen, rendered again at the window's size and written as a PNG.
    void screenshot() {
        const Camera camera = controls_.camera(int(extent_.width), int(extent_.height));
        const RenderOutput out = shown().render(camera, settings_);
        const std::filesystem::path path = next_screenshot();
        io::write_png_rgb(path, out.width, out.height, out.rgb.data(), 8);
        std::printf("wrote %s (%dx%d)\n", std::filesystem::absolute(path).string().c_str(), out.width, out.height);
        std::fflush(stdout);
    }

    void zoom(double steps) {
        controls_.zoom(steps);
        dataset_index_ = -1;
    }

    Renderer& shown() { return showing_compare_ ? *compare_renderer_ : renderer_; }

    void on_button(int button, int action, int mods) {
        if (action == GLFW_PRESS) {
            touring_ = false;
            dragging_ = button == GLFW_MOUSE_BUTTON_LEFT && !(mods & GLFW_MOD_SHIFT) ? Drag::rotate : Drag::pan;
            // A drag starts where the cursor was when the button went down: the last motion
            // event before this one. Asking the window system (glfwGetCursorPos) gives where the
            // cursor is now, which, while a slow frame leaves events queued, may already be where
            // the drag went, and the drag would then turn the view by less than it moved.
            if (!cursor_seen_) glfwGetCursorPos(window_.window(), &cursor_x_, &cursor_y_);
        } else {
            dragging_ = Drag::none;
        }
    }

    void on_cursor(double x, double y) {
        const double dx = x - cursor_x_, dy = y - cursor_y_;
        cursor_x_ = x;
        cursor_y_ = y;
        cursor_seen_ = true;
        if (dragging_ == Drag::none) return;
        if (dragging_ == Drag::rotate)
            controls_.rotate(dx, dy);
        else
            controls_.pan(dx, dy, int(extent_.height));
        dataset_index_ = -1;
        dirty_ = true;
    }

    void on_scroll(double dy) {
        zoom(dy);
        dirty_ = true;
    }

    void recreate_swapchain(VkExtent2D extent) {
        vkDeviceWaitIdle(window_.device());
        auto next = std::make_unique<Swapchain>(window_, extent, swapchain_ ? swapchain_->handle() : VK_NULL_HANDLE);
        swapchain_ = std::move(next);
        extent_ = swapchain_->extent();
        stale_swapchain_ = false;
    }

    void draw(VkExtent2D framebuffer) {
        if (!swapchain_ || stale_swapchain_ || framebuffer.width != extent_.width ||
            framebuffer.height != extent_.height)
            recreate_swapchain(framebuffer);
        const VkDevice device = window_.device();
        check(vkWaitForFences(device, 1, &sync_.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        const auto start = std::chrono::steady_clock::now();

        uint32_t index = 0;
        VkResult acquired = vkAcquireNextImageKHR(device, swapchain_->handle(), UINT64_MAX, sync_.acquired,
                                                  VK_NULL_HANDLE, &index);
        if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
            stale_swapchain_ = true;  // rebuilt at the next draw, which stays due (dirty_)
            return;
        }
        if (acquired != VK_SUBOPTIMAL_KHR) check(acquired, "vkAcquireNextImageKHR");
        check(vkResetFences(device, 1, &sync_.done), "vkResetFences");

        check(vkResetCommandBuffer(sync_.commands, 0), "vkResetCommandBuffer");
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        check(vkBeginCommandBuffer(sync_.commands, &begin), "vkBeginCommandBuffer");
        const Camera camera = controls_.camera(int(extent_.width), int(extent_.height));
        shown().record(sync_.commands, camera, settings_,
                       RenderTarget::to_image(swapchain_->images()[index], swapchain_->format(),
                                              VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL));
        // The last frame is done (the fence above), so the HUD's buffer is free to redraw.
        hud_.set_text(hud_lines(), extent_.width, extent_.height);
        hud_.record(sync_.commands, swapchain_->images()[index]);
        check(vkEndCommandBuffer(sync_.commands), "vkEndCommandBuffer");

        // The copy into the image (a transfer) waits for the presentation engine to let go of it;
        // vksplat's own passes need not. See render/render_target.hpp for the barriers this relies on.
        const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        const VkSemaphore drawn = swapchain_->drawn(index);
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.waitSemaphoreCount = 1;
        submit.pWaitSemaphores = &sync_.acquired;
        submit.pWaitDstStageMask = &wait_stage;
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &sync_.commands;
        submit.signalSemaphoreCount = 1;
        submit.pSignalSemaphores = &drawn;
        check(vkQueueSubmit(window_.queue(), 1, &submit, sync_.done), "vkQueueSubmit");

        const VkSwapchainKHR handle = swapchain_->handle();
        VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
        present.waitSemaphoreCount = 1;
        present.pWaitSemaphores = &drawn;
        present.swapchainCount = 1;
        present.pSwapchains = &handle;
        present.pImageIndices = &index;
        const VkResult presented = vkQueuePresentKHR(window_.queue(), &present);
        dirty_ = false;
        if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) {
            stale_swapchain_ = true;
            dirty_ = true;  // drawn again into the rebuilt swapchain
        } else {
            check(presented, "vkQueuePresentKHR");
        }

        // Frame time: recording, the GPU's work and presentation, as the user waits for them.
        check(vkWaitForFences(device, 1, &sync_.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        last_ms_ = ms;
        update_title(ms);
    }

    // The HUD: counts, SH degree and the last frame's time; then (H) every key, a group a line;
    // then (H again) nothing.
    std::vector<std::string> hud_lines() const {
        if (hud_state_ == Hud::none) return {};
        char status[160];
        const double fps = last_ms_ > 0 ? 1000.0 / last_ms_ : 0.0;
        std::snprintf(status, sizeof(status), "%zu Gaussians  SH %d  %.1f ms (%.*f fps)  %s%s  H: keys",
                      showing_compare_ ? compare_gaussians_ : gaussians_, settings_.max_sh_degree, last_ms_,
                      fps < 10 ? 1 : 0, fps, look().c_str(),
                      controls_.mode() == CameraControls::Mode::orbit ? "orbit" : "fly");
        std::vector<std::string> lines{status};
        if (hud_state_ != Hud::keys) return lines;
        const std::string keys = kKeys;
        for (size_t from = std::string("keys: ").size(); from < keys.size();) {
            const size_t bar = keys.find(" | ", from);
            lines.push_back(keys.substr(from, bar == std::string::npos ? std::string::npos : bar - from));
            if (bar == std::string::npos) break;
            from = bar + 3;
        }
        return lines;
    }

    // How the scene is drawn, when not as plain splats: "points - ", "scale 1.25 - ".
    std::string look() const {
        std::string text = display_mode_ == DisplayMode::splats ? "" : std::string(to_string(display_mode_)) + " - ";
        if (std::abs(splat_scale_ - 1.0) > 1e-9) {
            char scale[32];
            std::snprintf(scale, sizeof(scale), "scale %.2f - ", splat_scale_);
            text += scale;
        }
        return text;
    }

    void update_title(double ms) {
        char title[256];
        const std::string where = dataset_index_ >= 0 ? " - camera " + std::to_string(dataset_index_ + 1) + "/" +
                                                            std::to_string(cameras_.size()) + " (" +
                                                            cameras_[size_t(dataset_index_)].name + ")"
                                                      : "";
        // A CPU device draws a frame in seconds: frames per second with a decimal there, not "0 fps".
        const double fps = 1000.0 / ms;
        const std::string& scene = showing_compare_ ? options_.compare : options_.scene;
        const std::string which = compare_renderer_ ? (showing_compare_ ? "B: " : "A: ") : "";
        std::snprintf(title, sizeof(title),
                      "vksplat view - %s%s - %zu Gaussians - SH %d - %.1f ms (%.*f fps) - H: keys - %s%s%s", which.c_str(),
                      scene.c_str(), showing_compare_ ? compare_gaussians_ : gaussians_, settings_.max_sh_degree, ms,
                      fps < 10 ? 1 : 0, fps, (look() + (showing_frustums_ ? "frustums - " : touring_ ? "fly-through - " : "")).c_str(),
                      controls_.mode() == CameraControls::Mode::orbit ? "orbit" : "fly", where.c_str());
        glfwSetWindowTitle(window_.window(), title);
    }

    enum class Drag { none, rotate, pan };

    const ViewerOptions& options_;
    std::vector<Camera> cameras_;
    GlfwWindow window_;
    gpu::Context context_;
    Renderer renderer_;
    FrameSync sync_;
    HudOverlay hud_;
    CameraControls controls_;
    std::unique_ptr<Swapchain> swapchain_;
    bool stale_swapchain_ = false;  // out of date or suboptimal: rebuild before the next frame
    VkExtent2D extent_{};
    RenderSettings settings_;
    size_t gaussians_ = 0;
    GaussianCloud scene_;          // as read
    GaussianCloud frustums_;       // V's, with dataset cameras
    enum class Hud { none, status, keys };
    Hud hud_state_ = Hud::status;
    double last_ms_ = 0;      // the last frame's time, for the HUD
    bool showing_frustums_ = false;
    DisplayMode display_mode_ = DisplayMode::splats;
    double splat_scale_ = 1.0;
    double point_size_ = 0.01;
    std::unique_ptr<Renderer> compare_renderer_;  // --compare's scene
    size_t compare_gaussians_ = 0;
    bool showing_compare_ = false;
    bool touring_ = false;  // Space's fly-through
    double tour_ = 0;       // dataset cameras passed since it started
    int dataset_index_ = -1;
    bool dirty_ = true;
    Drag dragging_ = Drag::none;
    double cursor_x_ = 0, cursor_y_ = 0;
    bool cursor_seen_ = false;  // a motion event has set cursor_x_, cursor_y_
};

}  // namespace

int run_viewer(const ViewerOptions& options) {
    std::vector<std::string> notes, warnings;
    GaussianCloud cloud = io::read_scene(options.scene, &notes);
    for (const auto& note : notes) std::fprintf(stderr, "note: %s\n", note.c_str());
    std::vector<Camera> cameras;
    if (!options.cameras.empty()) {
        cameras = io::read_cameras(options.cameras, &warnings);
    } else if (const auto beside = std::filesystem::path(options.scene).parent_path() / "cameras.json";
               std::filesystem::is_regular_file(beside)) {
        // A trainer's output folder holds its cameras beside the scene: they know which way is up
        // and where the photos were taken from, which the scene alone does not.
        try {
            cameras = io::read_cameras(beside, &warnings);
            std::fprintf(stderr, "using the %zu cameras of %s beside the scene (--cameras names others)\n",
                         cameras.size(), beside.string().c_str());
        } catch (const InputError& e) {
            std::fprintf(stderr, "warning: %s beside the scene is not used: %s\n", beside.string().c_str(), e.what());
        }
    }
    for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    std::printf("%s\n", kKeys);
    std::fflush(stdout);
    std::optional<GaussianCloud> compare;
    if (!options.compare.empty()) {
        notes.clear();
        compare = io::read_scene(options.compare, &notes);
        for (const auto& note : notes) std::fprintf(stderr, "note: %s\n", note.c_str());
    }
    Viewer viewer(options, std::move(cloud), std::move(cameras), std::move(compare));
    return viewer.run();
}

}  // namespace vksplat::viewer
