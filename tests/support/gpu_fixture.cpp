#include "support/gpu_fixture.hpp"

#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>

namespace vksplat::test {
namespace {

// Fails the test during which validation messages arrived. A listener rather than a fixture's
// TearDown, so that plain TEST()s on the shared context are checked too. gtest calls OnTestEnd in
// reverse order of appending, so this runs before the result printer and the test's own line says
// FAILED.
class ValidationListener : public ::testing::EmptyTestEventListener {
public:
    explicit ValidationListener(const gpu::Context& context) : context_(context) {}

    void OnTestEnd(const ::testing::TestInfo&) override {
        const auto messages = context_.validation_messages();
        for (size_t i = seen_; i < messages.size(); ++i) ADD_FAILURE() << "Vulkan validation: " << messages[i];
        seen_ = messages.size();
    }

private:
    const gpu::Context& context_;
    size_t seen_ = 0;
};

void install_validation_listener(const gpu::Context& context) {
    // gtest owns its listeners.
    ::testing::UnitTest::GetInstance()->listeners().Append(new ValidationListener(context));
}

}  // namespace

gpu::ContextOptions test_context_options() {
    gpu::ContextOptions options;
    if (const char* device = std::getenv("VKSPLAT_TEST_DEVICE")) options.device = device;
    const char* switch_value = std::getenv("VKSPLAT_VALIDATION");
    const bool wanted = !switch_value || std::string(switch_value) != "0";
    if (wanted && !gpu::validation_layer_installed()) {
        static bool said = false;
        if (!said)
            std::cerr << "note: VK_LAYER_KHRONOS_validation is not installed (Debian: vulkan-validationlayers); "
                         "GPU tests run without validation\n";
        said = true;
    }
    options.validation = wanted && gpu::validation_layer_installed();
    return options;
}

gpu::Context& shared_test_context() {
    static const std::unique_ptr<gpu::Context> context = [] {
        const gpu::ContextOptions options = test_context_options();
        auto created = std::make_unique<gpu::Context>(options);
        if (options.validation) install_validation_listener(*created);
        return created;
    }();
    return *context;
}

}  // namespace vksplat::test
