#include <gtest/gtest.h>

#include "vksplat/error.hpp"
#include "vksplat/jobs/view_selection.hpp"

namespace vksplat::jobs {
namespace {

TEST(ViewSelection, ListsAndRanges) {
    EXPECT_EQ(parse_view_list("0,3,5-7", 10), (std::vector<size_t>{0, 3, 5, 6, 7}));
    EXPECT_EQ(parse_view_list("2", 3), (std::vector<size_t>{2}));
    EXPECT_EQ(parse_view_list("", 3), (std::vector<size_t>{0, 1, 2}));
    EXPECT_EQ(parse_view_list("all", 2), (std::vector<size_t>{0, 1}));
}

TEST(ViewSelection, RejectsMalformedAndOutOfRange) {
    for (const char* bad : {"x", "1,", "3-1", "1-", "-2", "1,,2", "0-10"}) {
        EXPECT_THROW(parse_view_list(bad, 5), InputError) << bad;
    }
    try {
        parse_view_list("7", 5);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("view 7 does not exist (there are 5 cameras)"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace vksplat::jobs
