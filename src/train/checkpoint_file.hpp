#pragma once
// The checkpoint file's layout (vksplat/train/checkpoint.hpp says what it is for): magic
// "VKSCKPT2", uint64 count, SH degree, iteration, skipped steps, then the owner as uint64-length-
// prefixed strings (source, field count, each field's name and value), then the parameters,
// first and second moments (float32, the trainer's layout) and the densification sums
// (kDensifyStride floats per Gaussian). Little-endian as the machine writes it: checkpoints are
// for resuming on the same kind of machine.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "vksplat/io/write_mode.hpp"
#include "vksplat/train/checkpoint.hpp"

namespace vksplat::train {

struct CheckpointData {
    CheckpointHeader header;
    uint64_t sh_degree = 0, skipped = 0;
    std::vector<float> params, first_moment, second_moment, densify_sums;
};

// Through io::write_file_atomically: an interrupted write leaves the previous checkpoint whole.
void write_checkpoint(const std::filesystem::path& path, const CheckpointData& data, io::WriteMode mode);
// Throws InputError naming the file if it is not a checkpoint, is cut short, or may not be resumed
// by the run `expected` (check_checkpoint_owner, before any array is read).
CheckpointData read_checkpoint(const std::filesystem::path& path, const CheckpointOwner& expected);

}  // namespace vksplat::train
