#pragma once
// Training checkpoints: what a resumed run needs to go on as if it had never stopped (parameters,
// Adam's moments, the densification sums gathered since the last densification, the counters),
// and a record of the run it belongs to, so that a resume never continues another scene's run and
// a checkpoint path never replaces a file that is not a checkpoint.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vksplat::train {

// What a checkpoint belongs to. `fields` (name, value) are compared on resume, every one: the
// fingerprints of the starting scene and of the cameras, the recipe. `source` only names the run
// in messages (files may move without the run changing).
struct CheckpointOwner {
    std::string source;
    std::vector<std::pair<std::string, std::string>> fields;
};

// What a checkpoint file says of itself, read without its arrays.
struct CheckpointHeader {
    uint64_t gaussians = 0;
    uint64_t iteration = 0;  // steps taken when it was written
    CheckpointOwner owner;
    // False for the first format, which recorded neither its run nor the densification sums: it
    // is recognised (and may be replaced) but never resumed.
    bool records_run = true;
};

// nullopt when `path` holds no vksplat checkpoint (no such file, or a file of another kind);
// throws InputError naming the file when its header is cut short or corrupt.
std::optional<CheckpointHeader> read_checkpoint_header(const std::filesystem::path& path);

// Throws InputError naming the checkpoint at `path` when `found` may not be resumed by the run
// `expected`: a checkpoint of the first format, or one whose owner differs (the first field that
// does, with both runs' values and the checkpoint's source).
void check_checkpoint_owner(const std::filesystem::path& path, const CheckpointHeader& found,
                            const CheckpointOwner& expected);

}  // namespace vksplat::train
