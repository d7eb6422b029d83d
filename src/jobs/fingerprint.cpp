#include "jobs/fingerprint.hpp"

#include <cstdint>
#include <cstdio>
#include <sstream>

namespace vksplat::jobs {
namespace {

class Fnv1a {
public:
    void add(const void* data, size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * 0x100000001b3ull;
    }
    template <class T>
    void add(const std::vector<T>& values) {
        add_value(uint64_t(values.size()));  // so that [a][bc] and [ab][c] differ
        add(values.data(), values.size() * sizeof(T));
    }
    template <class T>
    void add_value(const T& value) { add(&value, sizeof(value)); }
    std::string hex() const {
        char text[17];
        std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash_));
        return text;
    }

private:
    uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace

std::string fingerprint(const GaussianCloud& cloud) {
    Fnv1a hash;
    hash.add_value(cloud.sh_degree);
    for (const auto* values : {&cloud.positions, &cloud.log_scales, &cloud.rotations, &cloud.opacity_logits, &cloud.sh})
        hash.add(*values);
    return hash.hex();
}

std::string fingerprint(const std::vector<Camera>& cameras) {
    Fnv1a hash;
    hash.add_value(uint64_t(cameras.size()));
    for (const auto& camera : cameras) {
        hash.add(std::vector<char>(camera.name.begin(), camera.name.end()));
        for (int size : {camera.width, camera.height}) hash.add_value(size);
        for (double value : {camera.fx, camera.fy, camera.cx, camera.cy}) hash.add_value(value);
        for (int column = 0; column < 3; ++column) hash.add_value(camera.rotation[column]);
        hash.add_value(camera.translation);
    }
    return hash.hex();
}

std::string list_text(const std::vector<size_t>& values) {
    std::ostringstream text;
    for (size_t i = 0; i < values.size(); ++i) text << (i == 0 ? "" : ",") << values[i];
    return text.str();
}

std::string colour_text(const std::array<float, 3>& colour) {
    std::ostringstream text;
    text << colour[0] << ',' << colour[1] << ',' << colour[2];
    return text.str();
}

}  // namespace vksplat::jobs
