#include "eval/image_args.hpp"

#include <stdexcept>
#include <string>

namespace vksplat::eval::detail {

void check_image_pair(const char* metric, const float* a, const float* b, int width, int height,
                      int channels) {
    if (a == nullptr || b == nullptr)
        throw std::invalid_argument(std::string(metric) + ": image pointer is null");
    if (width <= 0 || height <= 0 || channels <= 0)
        throw std::invalid_argument(std::string(metric) + ": image size " + std::to_string(width) +
                                    " x " + std::to_string(height) + " x " +
                                    std::to_string(channels) + " is not positive");
}

}  // namespace vksplat::eval::detail
