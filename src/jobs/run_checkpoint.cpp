#include "jobs/run_checkpoint.hpp"

#include "vksplat/error.hpp"

namespace vksplat::jobs {

std::optional<train::CheckpointHeader> check_run_checkpoint(const RunFiles& files, const train::CheckpointOwner& owner,
                                                            bool resume, io::WriteMode mode) {
    const auto& path = files.checkpoint;
    const std::string name = path.string();
    io::refuse_input_as_output(path, files.inputs);
    for (const auto& output : files.outputs)
        if (io::same_file(path, output))
            throw InputError(name, "is also the run's output; the checkpoint needs a file of its own");

    std::error_code error;
    const bool exists = std::filesystem::exists(path, error);
    const std::optional<train::CheckpointHeader> header = train::read_checkpoint_header(path);
    if (exists && !header)
        throw InputError(name, "exists and is not a vksplat checkpoint; a checkpoint never replaces another "
                               "file, --force or not (name a new one)");
    if (resume) {
        if (!header) throw InputError(name, "no checkpoint to resume from");
        train::check_checkpoint_owner(path, *header, owner);
        io::check_writable(path, io::WriteMode::overwrite);
        return header;
    }
    if (header && mode == io::WriteMode::refuse_existing)
        throw InputError(name, "holds iteration " + std::to_string(header->iteration) + " of an earlier run (" +
                                   header->owner.source + "); " +
                                   (header->records_run ? "--resume continues it, " : "it cannot be resumed; ") +
                                   "--force starts over and replaces it");
    io::check_writable(path, io::WriteMode::overwrite);
    return std::nullopt;
}

std::string resume_notice(const train::CheckpointHeader& checkpoint, uint64_t iterations) {
    const std::string at = std::to_string(checkpoint.iteration), asked = std::to_string(iterations);
    if (checkpoint.iteration >= iterations)
        return "the checkpoint is at iteration " + at + ", not below the " + asked +
               " asked for: no steps are taken, its scene is the result";
    return "resuming from iteration " + at + " of " + asked;
}

}  // namespace vksplat::jobs
