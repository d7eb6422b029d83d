#pragma once
// The rules every training run's checkpoint follows (train, finetune; prune --recover keeps none),
// checked before any work so that nothing the user gave is lost and no run goes on from another:
//  - the checkpoint is none of the run's inputs and not its output;
//  - a file already there must be a vksplat checkpoint: a checkpoint never replaces a file of
//    another kind, whatever the write mode;
//  - resuming needs a checkpoint of this run (train::CheckpointOwner); not resuming, an existing
//    checkpoint (an interrupted run's state) is replaced only with WriteMode::overwrite (--force);
//  - its folder exists and may be written.
#include <filesystem>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vksplat/io/write_mode.hpp"
#include "vksplat/train/checkpoint.hpp"

namespace vksplat::jobs {

struct RunFiles {
    std::filesystem::path checkpoint;
    std::vector<std::filesystem::path> inputs;   // the scene, cameras and data files the run reads
    std::vector<std::filesystem::path> outputs;  // what it writes at the end
};

// Throws InputError naming the checkpoint and what to do. Returns the header of the checkpoint a
// resume continues (nullopt when not resuming).
std::optional<train::CheckpointHeader> check_run_checkpoint(const RunFiles& files, const train::CheckpointOwner& owner,
                                                            bool resume, io::WriteMode mode);

// What a resume of `checkpoint` to `iterations` in all will do, for the user: where it starts, or
// that the checkpoint is already there (no steps; its scene is the result).
std::string resume_notice(const train::CheckpointHeader& checkpoint, uint64_t iterations);

}  // namespace vksplat::jobs
