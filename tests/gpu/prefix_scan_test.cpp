// PrefixScan against std::exclusive_scan, with the count read from GPU memory.
#include "gpu/prefix_scan.hpp"

#include "gpu_test_util.hpp"

#include <numeric>
#include <random>

namespace vksplat::gpu {
namespace {

using test::shared_context;

const PrefixScan& shared_scan() {
    static PrefixScan scan(shared_context());
    return scan;
}

struct ScanCase {
    uint32_t count;
    bool in_place;
};

std::string case_name(const testing::TestParamInfo<ScanCase>& info) {
    return "n" + std::to_string(info.param.count) + (info.param.in_place ? "_in_place" : "_out_of_place");
}

class PrefixScanTest : public testing::TestWithParam<ScanCase> {};

TEST_P(PrefixScanTest, MatchesExclusiveScan) {
    const auto [count, in_place] = GetParam();
    const Context& context = shared_context();
    std::mt19937 random(count * 2 + in_place);
    // Values small enough that the sum stays below 2^32.
    const uint32_t max_value = count > 0 ? std::min<uint32_t>(1000000u, 0xffffffffu / count) : 1;
    std::uniform_int_distribution<uint32_t> distribution(0, max_value);
    std::vector<uint32_t> values(count);
    for (auto& v : values) v = distribution(random);
    std::vector<uint32_t> expected(count);
    std::exclusive_scan(values.begin(), values.end(), expected.begin(), 0u);
    const uint32_t expected_total = std::accumulate(values.begin(), values.end(), 0u);

    // One spare element after the data, which the scan must leave alone.
    std::vector<uint32_t> padded = values;
    padded.push_back(0xdeadbeefu);
    Buffer input = test::upload(context, padded, "scan input");
    Buffer output = test::device_buffer(context, count + 1, "scan output");
    Buffer small = test::upload(context, {count, 0xabcdef01u}, "scan count and total");
    PrefixScan::Scratch scratch(context, count + 1);
    EXPECT_EQ(scratch.capacity(), count + 1);

    CommandStream stream(context);
    stream.begin();
    stream.fill(output, 0xcafef00du);
    stream.barrier();
    const Buffer& target = in_place ? input : output;
    shared_scan().record(stream, input.address(), target.address(), small.address(), small.address() + 4, scratch);
    stream.barrier();
    stream.submit_and_wait();

    auto result = test::read_back(context, target, count + 1);
    EXPECT_EQ(result.back(), in_place ? 0xdeadbeefu : 0xcafef00du) << "wrote past count";
    result.pop_back();
    EXPECT_EQ(test::first_difference(result, expected), -1);
    EXPECT_EQ(test::read_back(context, small, 2)[1], expected_total);
    if (!in_place) {
        EXPECT_EQ(test::read_back(context, input, count + 1), padded) << "input changed";
    }
}

std::vector<ScanCase> scan_cases() {
    std::vector<ScanCase> cases;
    for (uint32_t n : {0u, 1u, 255u, 256u, 257u, 2048u, 2049u, 4097u, 100003u, 1000000u})
        for (bool in_place : {false, true}) cases.push_back({n, in_place});
    return cases;
}

INSTANTIATE_TEST_SUITE_P(Sizes, PrefixScanTest, testing::ValuesIn(scan_cases()), case_name);

TEST(PrefixScan, NoTotalAddressAndScratchReusedAcrossScans) {
    const Context& context = shared_context();
    PrefixScan::Scratch scratch(context, 50000);
    CommandStream stream(context);
    std::vector<std::vector<uint32_t>> inputs;
    std::vector<Buffer> buffers;
    std::vector<Buffer> counts;
    const uint32_t sizes[] = {50000, 3, 40961};
    for (uint32_t n : sizes) {
        std::vector<uint32_t> v(n);
        for (uint32_t i = 0; i < n; ++i) v[i] = (i * 7919u) % 13u;
        buffers.push_back(test::upload(context, v, "scan data"));
        counts.push_back(test::upload(context, {n}, "scan count"));
        inputs.push_back(std::move(v));
    }
    // Three scans in one submission sharing one scratch, ordered by barriers.
    stream.begin();
    for (size_t i = 0; i < buffers.size(); ++i) {
        shared_scan().record(stream, buffers[i].address(), buffers[i].address(), counts[i].address(), 0, scratch);
        stream.barrier();
    }
    stream.submit_and_wait();
    for (size_t i = 0; i < buffers.size(); ++i) {
        std::vector<uint32_t> expected(inputs[i].size());
        std::exclusive_scan(inputs[i].begin(), inputs[i].end(), expected.begin(), 0u);
        EXPECT_EQ(test::first_difference(test::read_back(context, buffers[i], expected.size()), expected), -1)
            << "scan " << i;
    }
}

TEST(PrefixScan, CountAboveCapacityIsClamped) {
    const Context& context = shared_context();
    std::vector<uint32_t> values(3000, 1u);
    Buffer data = test::upload(context, values, "scan data");
    Buffer small = test::upload(context, {1000000000u, 0u}, "scan count");
    PrefixScan::Scratch scratch(context, 2500);
    CommandStream stream(context);
    stream.begin();
    shared_scan().record(stream, data.address(), data.address(), small.address(), small.address() + 4, scratch);
    stream.barrier();
    stream.submit_and_wait();
    const auto result = test::read_back(context, data, values.size());
    for (uint32_t i = 0; i < 3000; ++i) ASSERT_EQ(result[i], i < 2500 ? i : 1u) << "at " << i;
    EXPECT_EQ(test::read_back(context, small, 2)[1], 2500u);
}

}  // namespace
}  // namespace vksplat::gpu
