// A Gaussian's shape and opacity from its parameters, one definition for the renderer's
// preprocess, the trainer's, their backward pass and the trainer's position noise.
#ifndef VKSPLAT_COMMON_GAUSSIAN_SHAPE_GLSL
#define VKSPLAT_COMMON_GAUSSIAN_SHAPE_GLSL

// The logistic function: a Gaussian's opacity from its logit, as the reference's
// opacity_activation (and HostScene::activate on the host) computes it.
float sigmoid(float x) { return 1.0 / (1.0 + exp(-x)); }

// Rotation matrix of a unit quaternion (w, x, y, z), as the reference's build_rotation makes it.
mat3 rotation_matrix(vec4 q) {
    const float r = q.x, x = q.y, y = q.z, z = q.w;
    return transpose(mat3(
        vec3(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - r * z), 2.0 * (x * z + r * y)),
        vec3(2.0 * (x * y + r * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - r * x)),
        vec3(2.0 * (x * z - r * y), 2.0 * (y * z + r * x), 1.0 - 2.0 * (x * x + y * y))));
}

// Sigma = R S S^T R^T for scales `scale` and the unit quaternion q.
mat3 covariance_3d(vec3 scale, vec4 q) {
    const mat3 m = rotation_matrix(q) * mat3(scale.x, 0, 0, 0, scale.y, 0, 0, 0, scale.z);
    return m * transpose(m);
}

#endif
