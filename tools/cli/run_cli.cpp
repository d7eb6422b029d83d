// Parses the command line and runs the chosen subcommand, turning each kind of failure into its
// own message and exit code: 2 for bad input, 3 for GPU failures, 1 for anything else.
#include <cstdio>
#include <exception>

#include "commands.hpp"
#include "vksplat/error.hpp"

namespace vksplat::cli {

int run_cli(CLI::App& app, const Action& action, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    try {
        return action();
    } catch (const InputError& e) {
        std::fprintf(stderr, "vksplat: error: %s\n", e.what());
        return 2;
    } catch (const GpuError& e) {
        std::fprintf(stderr, "vksplat: GPU error: %s\n", e.what());
        return 3;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vksplat: error: %s\n", e.what());
        return 1;
    }
}

}  // namespace vksplat::cli
