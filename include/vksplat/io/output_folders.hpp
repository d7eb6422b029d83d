#pragma once
// The folders a job makes for its outputs, removed again where they are empty when it ends: a job
// refused or failing before it writes leaves no empty folder behind, nor does one that had nothing
// to put in a folder. Folders that existed before are never touched.
#include <filesystem>
#include <vector>

namespace vksplat::io {

class OutputFolders {
public:
    OutputFolders() = default;
    OutputFolders(const OutputFolders&) = delete;
    OutputFolders& operator=(const OutputFolders&) = delete;
    // Removes, deepest first, every folder create() made that is empty now.
    ~OutputFolders();

    // Makes `folder` and its missing parents, remembering each one it made. Throws InputError
    // naming the folder where it cannot be made.
    void create(const std::filesystem::path& folder);

private:
    std::vector<std::filesystem::path> made_;  // outermost first
};

}  // namespace vksplat::io
