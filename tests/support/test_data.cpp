#include "support/test_data.hpp"

#include <cstdlib>

namespace vksplat::test {

std::filesystem::path shared_data_dir() {
    if (const char* env = std::getenv("VKSPLAT_SHARED_DATA"); env && *env) return env;
    return VKSPLAT_SHARED_DATA_DIR;
}

bool shared_data_available() {
    const auto dir = shared_data_dir();
    return std::filesystem::exists(dir / "lego" / "point_cloud.ply") &&
           std::filesystem::exists(dir / "snowmiku" / "point_cloud.ply");
}

}  // namespace vksplat::test
