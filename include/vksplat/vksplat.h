/* vksplat's C API: open a Vulkan device (or adopt the application's), load or build a scene, render
 * views into the caller's memory or into the caller's VkImage / VkBuffer, and prune a scene.
 * Plain C99 (it compiles as C++ too), for C programs and other languages' foreign-function
 * interfaces. It wraps the C++ library (vksplat/gpu/context.hpp, vksplat/render/renderer.hpp,
 * vksplat/io/formats.hpp, vksplat/prune/...), whose headers say more about each step.
 *
 *   vksplat_error error;
 *   vksplat_context* context = NULL;
 *   vksplat_scene* scene = NULL;
 *   vksplat_renderer* renderer = NULL;
 *   if (vksplat_context_create(NULL, &context, &error) != VKSPLAT_OK ||
 *       vksplat_scene_load("scene.ply", &scene, &error) != VKSPLAT_OK ||
 *       vksplat_renderer_create(context, &renderer, &error) != VKSPLAT_OK ||
 *       vksplat_renderer_set_scene(renderer, scene, &error) != VKSPLAT_OK ||
 *       vksplat_render(renderer, &camera, NULL, &image, &error) != VKSPLAT_OK)
 *       fprintf(stderr, "%s\n", error.message);
 *   vksplat_renderer_destroy(renderer);   (destroy functions accept NULL)
 *   vksplat_scene_destroy(scene);
 *   vksplat_context_destroy(context);
 *
 * Errors: every function that can fail returns a vksplat_status and, when `error` is not NULL,
 * writes a message into it that names what is at fault ("scene.ply: truncated ...", "vksplat_render:
 * renderer is NULL"); on success the message is empty. The message lives in the caller's
 * vksplat_error, so calls on different threads never share one, and the library keeps no mutable
 * global state of its own. No C++ exception ever leaves a function of this header.
 *
 * Threads: a handle is used by one thread at a time. A renderer submits to its context's queue, so
 * calls on one context and the renderers made from it must not run at the same time.
 *
 * Lifetimes: a renderer refers to its context, which must outlive it; a renderer keeps its own copy
 * of the scene given to it, so a scene may be destroyed once it has been set. */
#ifndef VKSPLAT_VKSPLAT_H
#define VKSPLAT_VKSPLAT_H

#include <stddef.h>
#include <stdint.h>
#include <vulkan/vulkan_core.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- status, errors, version ----------------------------------------------------------------- */

typedef enum vksplat_status {
    VKSPLAT_OK = 0,
    /* A programming error of the caller: a NULL handle or pointer, a buffer too small for the
     * picture, an unknown enum value. */
    VKSPLAT_INVALID_ARGUMENT = 1,
    /* Bad input data: a missing, malformed or truncated file, an invalid camera, an unwritable
     * output. The message names the file or thing at fault and the problem. */
    VKSPLAT_INVALID_INPUT = 2,
    /* The GPU could not do it: no usable device, out of device memory, a Vulkan failure. */
    VKSPLAT_GPU_ERROR = 3,
    /* Host memory ran out. */
    VKSPLAT_OUT_OF_MEMORY = 4,
    /* Anything else (a bug in vksplat: please report the message). */
    VKSPLAT_INTERNAL_ERROR = 5
} vksplat_status;

/* Room for one message, always NUL-terminated; a longer message is cut to fit. */
#define VKSPLAT_ERROR_MESSAGE_SIZE 1024
typedef struct vksplat_error {
    char message[VKSPLAT_ERROR_MESSAGE_SIZE];
} vksplat_error;

/* "VKSPLAT_OK", "VKSPLAT_INVALID_INPUT", ...; "unknown status" for any other value. */
const char* vksplat_status_name(vksplat_status status);

/* The library's version, "major.minor.patch" (CMake's project version, as `vksplat --version`). */
const char* vksplat_version(void);

/* ---- opaque handles ---------------------------------------------------------------------------- */

typedef struct vksplat_context vksplat_context;   /* a Vulkan device and compute queue */
typedef struct vksplat_scene vksplat_scene;       /* Gaussians in host memory */
typedef struct vksplat_renderer vksplat_renderer; /* a scene on the device, and what renders it */

/* ---- context: a device of vksplat's own, or the application's ---------------------------------- */

typedef struct vksplat_context_options {
    /* NULL or "": the first usable discrete GPU, then integrated, then anything (lavapipe). A
     * number picks by index; other text picks the first device whose name contains it. */
    const char* device;
    /* Non-zero: enable VK_LAYER_KHRONOS_validation when it is installed. */
    int validation;
    /* Device memory vksplat may hold, in bytes; 0: the device's own limit. Frames that would not
     * fit are rendered in depth-ordered chunks. */
    uint64_t memory_budget;
} vksplat_context_options;

/* Creates an instance and device of vksplat's own. `options` may be NULL (all defaults). */
vksplat_status vksplat_context_create(const vksplat_context_options* options, vksplat_context** context,
                                      vksplat_error* error);

/* The application's Vulkan objects, lent to vksplat: it never destroys them, and they must outlive
 * the context and everything made from it. The device must be Vulkan 1.2 with bufferDeviceAddress
 * enabled (see vksplat/gpu/context.hpp's AdoptedDevice for the whole contract, including the queue's
 * external synchronisation). */
typedef struct vksplat_adopted_device {
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    uint32_t queue_family;  /* must support compute */
    VkQueue queue;          /* a queue of queue_family */
    /* The application's loader entry point; NULL: vksplat opens the system loader. */
    PFN_vkGetInstanceProcAddr get_instance_proc_addr;
    int int64_atomics_enabled;  /* non-zero if created with shaderInt64 + shaderBufferInt64Atomics */
    int float_atomics_enabled;  /* non-zero if created with shaderBufferFloat32AtomicAdd */
} vksplat_adopted_device;

/* Works on the application's device (see vksplat_adopted_device); destroys nothing of it. */
vksplat_status vksplat_context_adopt(const vksplat_adopted_device* device, vksplat_context** context,
                                     vksplat_error* error);

/* The device's name as its driver gives it, into `name` (`size` bytes, cut to fit, NUL-terminated). */
vksplat_status vksplat_context_device_name(const vksplat_context* context, char* name, size_t size,
                                           vksplat_error* error);

/* Accepts NULL. Every renderer made from the context must be destroyed first. */
void vksplat_context_destroy(vksplat_context* context);

/* ---- scene ------------------------------------------------------------------------------------- */

/* Reads a scene file, the format told by its extension: INRIA .ply (and PlayCanvas compressed PLY),
 * .splat, .spz, gsplat checkpoint .pt (vksplat/io/formats.hpp). A missing, malformed or truncated
 * file gives VKSPLAT_INVALID_INPUT with a message naming the file. */
vksplat_status vksplat_scene_load(const char* path, vksplat_scene** scene, vksplat_error* error);

/* A scene from the caller's arrays (copied), laid out as vksplat's GaussianCloud and the INRIA PLY. */
typedef struct vksplat_scene_data {
    size_t count;                /* Gaussians */
    int sh_degree;               /* 0 to 3 */
    const float* positions;      /* 3 per Gaussian: x, y, z */
    const float* log_scales;     /* 3 per Gaussian: natural log of the standard deviations */
    const float* rotations;      /* 4 per Gaussian: quaternion w, x, y, z (need not be normalised) */
    const float* opacity_logits; /* 1 per Gaussian: opacity = sigmoid(logit) */
    /* (sh_degree + 1)^2 * 3 per Gaussian, [coefficient][r, g, b]; coefficient 0 is the DC term
     * (colour = 0.5 + 0.28209479 * dc for a view-independent splat). */
    const float* sh;
} vksplat_scene_data;

vksplat_status vksplat_scene_create(const vksplat_scene_data* data, vksplat_scene** scene, vksplat_error* error);

/* Writes the scene in the format its extension names (.ply, .compressed.ply, .splat, .spz). An
 * existing file is refused (VKSPLAT_INVALID_INPUT) unless `overwrite` is non-zero. */
vksplat_status vksplat_scene_save(const vksplat_scene* scene, const char* path, int overwrite, vksplat_error* error);

/* How many Gaussians, and of which SH degree; either pointer may be NULL. */
vksplat_status vksplat_scene_info(const vksplat_scene* scene, size_t* count, int* sh_degree, vksplat_error* error);

/* Accepts NULL. */
void vksplat_scene_destroy(vksplat_scene* scene);

/* ---- cameras ----------------------------------------------------------------------------------- */

/* A pinhole camera with OpenCV axes (x right, y down, z forward). */
typedef struct vksplat_camera {
    int width, height;     /* pixels */
    double fx, fy;         /* focal lengths in pixels */
    double cx, cy;         /* principal point; pixel (i, j) covers [i, i+1) x [j, j+1) */
    /* World to camera: p_camera = rotation * p_world + translation, rotation row-major. */
    double rotation[9];
    double translation[3];
} vksplat_camera;

/* A camera at `eye` looking at `target` with `up` pointing up in the picture, principal point at
 * the centre. VKSPLAT_INVALID_INPUT when eye and target coincide or up is parallel to the view. */
vksplat_status vksplat_camera_look_at(const double eye[3], const double target[3], const double up[3], int width,
                                      int height, double fx, double fy, vksplat_camera* camera,
                                      vksplat_error* error);

/* Reads a camera file: INRIA cameras.json, a COLMAP model folder, a NeRF transforms*.json
 * (vksplat/io/cameras.hpp), e.g. the views to prune over. On success *cameras holds *count cameras
 * in the file's order (NULL when there are none), allocated by vksplat: free them with
 * vksplat_cameras_free. */
vksplat_status vksplat_cameras_load(const char* path, vksplat_camera** cameras, size_t* count, vksplat_error* error);

/* Accepts NULL. */
void vksplat_cameras_free(vksplat_camera* cameras);

/* ---- rendering --------------------------------------------------------------------------------- */

typedef struct vksplat_render_settings {
    float background[3];  /* each in [0, 1] */
    int max_sh_degree;    /* SH bands above this are ignored (0 to 3) */
} vksplat_render_settings;

/* Black background, SH degree 3: what a NULL settings pointer means. */
vksplat_render_settings vksplat_render_settings_default(void);

vksplat_status vksplat_renderer_create(vksplat_context* context, vksplat_renderer** renderer, vksplat_error* error);

/* Sanitises a copy of the scene (non-finite or degenerate Gaussians dropped, overflowing values
 * clamped) and uploads it; the renderer keeps it until the next set_scene or prune. */
vksplat_status vksplat_renderer_set_scene(vksplat_renderer* renderer, const vksplat_scene* scene,
                                          vksplat_error* error);

/* Accepts NULL. Waits for the GPU to finish frames recorded with vksplat_record. */
void vksplat_renderer_destroy(vksplat_renderer* renderer);

typedef enum vksplat_pixel_format {
    /* 4 bytes a pixel: r, g, b and alpha, each clamped to [0, 1] and rounded to 8 bits. */
    VKSPLAT_PIXELS_RGBA8 = 0,
    /* 3 floats a pixel: the renderer's colour as it is (background * T included, unclamped). */
    VKSPLAT_PIXELS_RGB_FLOAT = 1
} vksplat_pixel_format;

/* The caller's memory a view is rendered into: camera width x height pixels, row-major, top row
 * first, tightly packed. Each buffer's size, in bytes, must be at least what the picture needs
 * (VKSPLAT_INVALID_ARGUMENT otherwise); depth and alpha may be NULL when not wanted. */
typedef struct vksplat_image {
    vksplat_pixel_format format;
    void* pixels;
    size_t pixels_size;
    /* 1 float a pixel: the expected view-space depth of the blended surface, 0 where nothing was. */
    float* depth;
    size_t depth_size;
    /* 1 float a pixel: 1 - T, the coverage. */
    float* alpha;
    size_t alpha_size;
} vksplat_image;

/* Renders one view of the renderer's scene into `image`, waiting for the GPU. `settings` may be NULL. */
vksplat_status vksplat_render(vksplat_renderer* renderer, const vksplat_camera* camera,
                              const vksplat_render_settings* settings, const vksplat_image* image,
                              vksplat_error* error);

/* The application's image or buffer a view is recorded into; exactly one of image and buffer is
 * set. Formats: VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM / _SRGB,
 * VK_FORMAT_B8G8R8A8_UNORM / _SRGB (vksplat/render/render_target.hpp). */
typedef struct vksplat_target {
    VkImage image;
    VkBuffer buffer;
    VkDeviceSize offset;         /* buffer only: where the first pixel goes */
    VkFormat format;
    VkImageLayout old_layout;    /* image only: its layout on entry (UNDEFINED discards its contents) */
    VkImageLayout final_layout;  /* image only: the layout it is left in */
} vksplat_target;

/* Records the render of one view into `command_buffer`, which the application has begun and will
 * submit to the context's queue; the picture lands in `target`. Submits nothing and waits for
 * nothing (but the queue, when its buffers must grow). The barriers it records and what the
 * application must do are in vksplat/render/render_target.hpp. */
vksplat_status vksplat_record(vksplat_renderer* renderer, VkCommandBuffer command_buffer,
                              const vksplat_camera* camera, const vksplat_render_settings* settings,
                              const vksplat_target* target, vksplat_error* error);

/* ---- pruning ----------------------------------------------------------------------------------- */

/* One importance score per Gaussian; the lowest are dropped (vksplat/prune/scores.hpp). */
typedef enum vksplat_score_method {
    VKSPLAT_SCORE_OPACITY = 0,      /* sigmoid of the stored logit */
    VKSPLAT_SCORE_FOOTPRINT = 1,    /* sum over views of opacity * pi * r^2 */
    VKSPLAT_SCORE_BLEND = 2,        /* sum over every pixel of every view of alpha * T */
    VKSPLAT_SCORE_BLEND_MAX = 3,    /* max over pixels and views of alpha * T */
    VKSPLAT_SCORE_VOLUME_BLEND = 4, /* blend weighted by volume (LightGaussian) */
    VKSPLAT_SCORE_RANDOM = 5,       /* seeded uniform: the baseline the others must beat */
    VKSPLAT_SCORE_FISHER = 6,       /* log det of the pictures' Fisher information in mean and log-scale
                                     * (PUP 3D-GS), computed on the CPU from the views */
    VKSPLAT_SCORE_BLEND_MIX = 7     /* sqrt(blend * blend max): the best ranking for a re-fit */
} vksplat_score_method;

typedef struct vksplat_prune_options {
    vksplat_score_method method;
    double ratio;    /* the fraction of the Gaussians to drop, in [0, 1] (else VKSPLAT_INVALID_INPUT) */
    uint64_t seed;   /* VKSPLAT_SCORE_RANDOM only */
    /* The views scored over. With views, the Gaussians that reach alpha >= 1/255 on no pixel of
     * any of them are dropped first whatever the method (it leaves those views' renders
     * identical), as `vksplat prune` does. Opacity and random need no views (view_count 0). */
    const vksplat_camera* views;
    size_t view_count;
    const vksplat_render_settings* settings;  /* of the scoring renders; NULL: the defaults */
} vksplat_prune_options;

/* Makes `pruned`, a new scene: the sanitised `scene` without the Gaussians the options drop. Rendering
 * the views uses `renderer` (NULL is allowed only without views), whose scene is then the sanitised
 * input: set the pruned scene on it to render that. */
vksplat_status vksplat_prune(vksplat_renderer* renderer, const vksplat_scene* scene,
                             const vksplat_prune_options* options, vksplat_scene** pruned, vksplat_error* error);

#ifdef __cplusplus
}
#endif

#endif /* VKSPLAT_VKSPLAT_H */
