#pragma once
// DensifyInputs over vectors a test fills in: DensifyPasses's own are views into its readback
// buffer. Declare the owner, not a DensifyInputs, where the inputs outlive the expression.
#include <cstdint>
#include <vector>

#include "train/densify.hpp"
#include "train/parameter_layout.hpp"

namespace vksplat::test {

struct HostDensifyInputs {
    uint32_t count = 0;
    std::vector<float> geometry, sums;

    explicit HostDensifyInputs(uint32_t n)
        : count(n), geometry(11 * size_t(n), 0.0f), sums(train::kDensifyStride * size_t(n), 0.0f) {}
    operator train::DensifyInputs() const { return {count, geometry, sums}; }
};

}  // namespace vksplat::test
