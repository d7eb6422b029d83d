// write_file_atomically(): nothing half-written, nothing overwritten by accident.
#include <gtest/gtest.h>

#include <stdexcept>

#include "io/io_test_helpers.hpp"
#include "vksplat/io/write_mode.hpp"

namespace vksplat::io::test {
namespace {

size_t files_in(const std::filesystem::path& folder) {
    return static_cast<size_t>(std::distance(std::filesystem::directory_iterator(folder), {}));
}

TEST(AtomicWrite, WritesRefusesAndOverwrites) {
    ScratchDir dir;
    const auto path = dir / "out.txt";
    write_file_atomically(path, WriteMode::refuse_existing, [](std::ostream& out) { out << "first"; });
    EXPECT_EQ(read_bytes(path), "first");
    expect_input_error(
        [&] { write_file_atomically(path, WriteMode::refuse_existing, [](std::ostream& out) { out << "second"; }); },
        {"out.txt", "already exists"});
    EXPECT_EQ(read_bytes(path), "first");
    write_file_atomically(path, WriteMode::overwrite, [](std::ostream& out) { out << "second"; });
    EXPECT_EQ(read_bytes(path), "second");
    EXPECT_EQ(files_in(dir.path()), 1u);
}

TEST(AtomicWrite, AFailingWriterLeavesNothingBehind) {
    ScratchDir dir;
    const auto path = dir / "out.txt";
    write_bytes(path, "old");
    EXPECT_THROW(write_file_atomically(path, WriteMode::overwrite,
                                       [](std::ostream& out) {
                                           out << "partial";
                                           throw std::runtime_error("writer failed");
                                       }),
                 std::runtime_error);
    EXPECT_EQ(read_bytes(path), "old");
    EXPECT_EQ(files_in(dir.path()), 1u);
}

TEST(AtomicWrite, MissingFolderIsNamed) {
    ScratchDir dir;
    expect_input_error(
        [&] { write_file_atomically(dir / "no" / "out.txt", WriteMode::overwrite, [](std::ostream&) {}); },
        {"out.txt", "does not exist"});
}

}  // namespace
}  // namespace vksplat::io::test
