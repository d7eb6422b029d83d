/* vksplat from C: open a device, load (or build) a scene, render one view into our own memory,
 * write it as a PPM and print its mean colour.
 *   c_api_example OUT.ppm [SCENE]
 * Without SCENE it builds a ring of coloured Gaussians itself. The camera looks at the origin from
 * 4 units away, 30 degrees up, +z up: it frames `vksplat demo`'s scene too. Exits 0 when the picture
 * was written, 1 with vksplat's message on stderr when something failed, 2 for a wrong command line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <vksplat/vksplat.h>

enum { WIDTH = 160, HEIGHT = 120, RING = 96 };

/* RING Gaussians on a wavy unit circle, their colour going round the hue circle: SH degree 0, whose
 * one coefficient per channel is (colour - 0.5) / 0.28209479. */
static vksplat_status build_ring(vksplat_scene** scene, vksplat_error* error) {
    static float positions[RING * 3], log_scales[RING * 3], rotations[RING * 4], opacity_logits[RING], sh[RING * 3];
    const double two_pi = 6.283185307179586;
    vksplat_scene_data data;
    int i, c;
    for (i = 0; i < RING; ++i) {
        const double t = two_pi * i / RING;
        positions[i * 3 + 0] = (float)cos(t);
        positions[i * 3 + 1] = (float)sin(t);
        positions[i * 3 + 2] = (float)(0.2 * sin(3 * t));
        for (c = 0; c < 3; ++c) {
            const double colour = 0.5 + 0.45 * cos(t - c * two_pi / 3);
            log_scales[i * 3 + c] = (float)log(0.08);
            sh[i * 3 + c] = (float)((colour - 0.5) / 0.28209479177387814);
        }
        rotations[i * 4 + 0] = 1.0f;
        rotations[i * 4 + 1] = rotations[i * 4 + 2] = rotations[i * 4 + 3] = 0.0f;
        opacity_logits[i] = 2.0f; /* opacity 0.88 */
    }
    data.count = RING;
    data.sh_degree = 0;
    data.positions = positions;
    data.log_scales = log_scales;
    data.rotations = rotations;
    data.opacity_logits = opacity_logits;
    data.sh = sh;
    return vksplat_scene_create(&data, scene, error);
}

static int write_ppm(const char* path, const unsigned char* rgba) {
    FILE* file = fopen(path, "wb");
    int i, ok;
    if (!file) return 0;
    fprintf(file, "P6\n%d %d\n255\n", WIDTH, HEIGHT);
    for (i = 0; i < WIDTH * HEIGHT; ++i) fwrite(rgba + i * 4, 1, 3, file);
    ok = !ferror(file);
    return fclose(file) == 0 && ok;
}

int main(int argc, char** argv) {
    static unsigned char rgba[WIDTH * HEIGHT * 4];
    const double eye[3] = {0.0, -3.464, 2.0}, target[3] = {0.0, 0.0, 0.0}, up[3] = {0.0, 0.0, 1.0};
    vksplat_error error;
    vksplat_context* context = NULL;
    vksplat_scene* scene = NULL;
    vksplat_renderer* renderer = NULL;
    vksplat_camera camera;
    vksplat_image image = {VKSPLAT_PIXELS_RGBA8, rgba, sizeof rgba, NULL, 0, NULL, 0};
    char device[256];
    double mean[3] = {0, 0, 0};
    int i, c, status = 1;

    if (argc != 2 && argc != 3) {
        fprintf(stderr, "usage: %s OUT.ppm [SCENE]\n", argv[0]);
        return 2;
    }
    printf("vksplat %s\n", vksplat_version());
    /* Each step runs only if every one before it succeeded; the first failure's message is kept. */
    if ((argc == 3 ? vksplat_scene_load(argv[2], &scene, &error) : build_ring(&scene, &error)) == VKSPLAT_OK &&
        vksplat_context_create(NULL, &context, &error) == VKSPLAT_OK &&
        vksplat_context_device_name(context, device, sizeof device, &error) == VKSPLAT_OK &&
        vksplat_renderer_create(context, &renderer, &error) == VKSPLAT_OK &&
        vksplat_renderer_set_scene(renderer, scene, &error) == VKSPLAT_OK &&
        vksplat_camera_look_at(eye, target, up, WIDTH, HEIGHT, 0.9 * WIDTH, 0.9 * WIDTH, &camera, &error) ==
            VKSPLAT_OK &&
        vksplat_render(renderer, &camera, NULL, &image, &error) == VKSPLAT_OK) {
        for (i = 0; i < WIDTH * HEIGHT; ++i)
            for (c = 0; c < 3; ++c) mean[c] += rgba[i * 4 + c] / (255.0 * WIDTH * HEIGHT);
        if (write_ppm(argv[1], rgba)) {
            printf("device: %s\nmean colour: %.4f %.4f %.4f\n", device, mean[0], mean[1], mean[2]);
            status = 0;
        } else {
            fprintf(stderr, "%s: could not be written\n", argv[1]);
        }
    } else {
        fprintf(stderr, "error: %s\n", error.message);
    }
    /* Destroy accepts NULL, so whatever was made is released the same way. */
    vksplat_renderer_destroy(renderer);
    vksplat_scene_destroy(scene);
    vksplat_context_destroy(context);
    return status;
}
