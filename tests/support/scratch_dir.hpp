#pragma once
// A fresh, empty folder for the running test's files, named after the process and the test so
// that tests running side by side (ctest -j) never share one. The test removes it in TearDown.
#include <filesystem>
#include <string>

namespace vksplat::test {

std::filesystem::path fresh_test_dir(const std::string& prefix);

}  // namespace vksplat::test
