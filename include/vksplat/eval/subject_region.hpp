#pragma once
// The subject of a capture, fixed in advance and independent of any pruning method, so that
// "did pruning keep the subject" can be measured on the same pixels for every variant.
//
// A subject ball is a ball in world space. The automatic one is the cameras' common focus (the
// least-squares nearest point to all optical axes) with radius 0.3 x the median camera distance to
// it: in a capture that circles a subject, the subject is what every camera points at. A pixel of a
// view is subject when the *unpruned* render there is mostly opaque (alpha > 0.5) and the point at
// its expected depth lies inside the ball.
#include <cstdint>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/render_types.hpp"

namespace vksplat::eval {

struct SubjectBall {
    glm::dvec3 centre{0.0};
    double radius = 0;
};

// Throws InputError when the cameras have no common focus (a forward-facing capture: give the ball
// or masks by hand).
SubjectBall auto_subject_ball(const std::vector<Camera>& cameras);

// "x,y,z,r" in scene units; throws InputError naming `text` when it is not four numbers with r > 0.
SubjectBall parse_subject_ball(const std::string& text);

inline constexpr float kSubjectMinAlpha = 0.5f;

// One byte per pixel of `unpruned` (rendered with `camera`): 1 where the pixel is subject.
std::vector<uint8_t> subject_mask(const RenderOutput& unpruned, const Camera& camera, const SubjectBall& ball);

}  // namespace vksplat::eval
