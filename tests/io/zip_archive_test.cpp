// The zip reader alone, on archives written by hand (tests/io/torch_save_writer.hpp): entries are
// listed in order and read back byte for byte, stored or deflated, with zip64 sizes and offsets;
// damage is refused with a message that names the archive and the entry.
#include <gtest/gtest.h>

#include "io/io_test_helpers.hpp"
#include "io/torch_save_writer.hpp"
#include "io/zip_archive.hpp"

namespace vksplat::io::test {
namespace {

// Overwrites the 16-bit field `offset` bytes into the first central directory record.
void patch_directory(std::string& archive, size_t offset, uint16_t value) {
    const size_t record = archive.find(std::string("PK\x01\x02", 4));
    ASSERT_NE(record, std::string::npos);
    std::memcpy(archive.data() + record + offset, &value, 2);
}

TEST(ZipArchive, ListsEntriesInOrderAndReadsThemBack) {
    ScratchDir dir;
    const std::string text = "a line of text\n";
    std::string repetitive;
    for (int i = 0; i < 1000; ++i) repetitive += "deflate me " + std::to_string(i % 7);
    write_bytes(dir / "a.zip", zip_of({{"top/stored.txt", text}, {"top/deflated.bin", repetitive, true},
                                      {"top/empty", ""}, {"top/far.bin", "after the others", false, true}}));

    zip::Archive archive(dir / "a.zip", "a.zip");
    ASSERT_EQ(archive.entries().size(), 4u);
    EXPECT_EQ(archive.entries()[0].name, "top/stored.txt");
    EXPECT_EQ(archive.entries()[1].name, "top/deflated.bin");
    EXPECT_EQ(archive.entries()[1].method, 8);
    EXPECT_LT(archive.entries()[1].compressed_size, repetitive.size());
    EXPECT_EQ(archive.read(archive.entries()[0]), text);
    EXPECT_EQ(archive.read(archive.entries()[1]), repetitive);
    EXPECT_EQ(archive.read(archive.entries()[2]), "");
    // The zip64 entry's size and offset come from its extra field, not the 0xffffffff beside them.
    const zip::Entry* far = archive.find("top/far.bin");
    ASSERT_NE(far, nullptr);
    EXPECT_EQ(far->size, 16u);
    EXPECT_GT(far->local_offset, 0u);
    EXPECT_EQ(archive.read(*far), "after the others");
    EXPECT_EQ(archive.find("top/missing"), nullptr);
}

TEST(ZipArchiveErrors, CorruptDataIsCaughtByItsCrc) {
    ScratchDir dir;
    std::string bytes = zip_of({{"entry", "the stored payload"}});
    bytes[bytes.find("payload")] = 'P';
    write_bytes(dir / "crc.zip", bytes);
    zip::Archive archive(dir / "crc.zip", "crc.zip");
    expect_input_error([&] { archive.read(archive.entries()[0]); }, {"crc.zip", "zip entry 'entry'", "CRC mismatch"});
}

TEST(ZipArchiveErrors, UnsupportedCompressionIsNamed) {
    ScratchDir dir;
    std::string bytes = zip_of({{"entry", "data"}});
    patch_directory(bytes, 10, 12);  // bzip2
    write_bytes(dir / "bzip2.zip", bytes);
    zip::Archive archive(dir / "bzip2.zip", "bzip2.zip");
    expect_input_error([&] { archive.read(archive.entries()[0]); }, {"bzip2.zip", "compression method 12"});
}

TEST(ZipArchiveErrors, EntryBeyondTheEndOfTheFile) {
    ScratchDir dir;
    std::string bytes = zip_of({{"entry", "data"}});
    patch_directory(bytes, 42, 0x7fff);  // the local header's offset, far past the end
    write_bytes(dir / "far.zip", bytes);
    zip::Archive archive(dir / "far.zip", "far.zip");
    expect_input_error([&] { archive.read(archive.entries()[0]); }, {"far.zip", "zip entry 'entry'", "truncated"});
}

TEST(ZipArchiveErrors, NotAZipArchive) {
    ScratchDir dir;
    write_bytes(dir / "text.zip", std::string(100, 'x'));
    expect_input_error([&] { zip::Archive(dir / "text.zip", "text.zip"); }, {"text.zip", "not a zip archive"});
    expect_input_error([&] { zip::Archive(dir / "absent.zip", "absent.zip"); }, {"absent.zip", "no such file"});
}

}  // namespace
}  // namespace vksplat::io::test
