#include "vksplat/eval/metrics.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vksplat::eval {

void colorize_heat(const std::vector<float>& err, float max_value, std::vector<uint8_t>& rgb_out) {
    if (!(max_value > 0.0f) || !std::isfinite(max_value))
        throw std::invalid_argument("colorize_heat: max_value " + std::to_string(max_value) +
                                    " is not positive and finite");
    rgb_out.resize(err.size() * 3);
    if (err.empty()) return;

    cv::Mat levels(1, static_cast<int>(err.size()), CV_8U);
    for (size_t i = 0; i < err.size(); ++i) {
        const float t = std::isnan(err[i]) ? 1.0f : std::clamp(err[i] / max_value, 0.0f, 1.0f);
        levels.at<uint8_t>(static_cast<int>(i)) = static_cast<uint8_t>(std::lround(t * 255.0f));
    }
    cv::Mat bgr;
    cv::applyColorMap(levels, bgr, cv::COLORMAP_INFERNO);
    // OpenCV colours are BGR; write straight into the caller's RGB buffer.
    cv::Mat rgb(1, static_cast<int>(err.size()), CV_8UC3, rgb_out.data());
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
}

}  // namespace vksplat::eval
