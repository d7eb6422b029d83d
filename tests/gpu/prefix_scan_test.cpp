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

// Setup, barrier, scan: what a caller with nothing to run beside the setup records.
void record_scan(CommandStream& stream, VkDeviceAddress input, VkDeviceAddress output, VkDeviceAddress count,
                 VkDeviceAddress total, PrefixScan::Scratch& scratch, const PrefixScan& scan = shared_scan()) {
    scan.record_setup(stream, count, scratch);
    stream.barrier();
    scan.record(stream, input, output, total, scratch);
}

// Appended rather than "n" + to_string(...), which GCC 12 wrongly flags as an overlapping memcpy
// (-Wrestrict, GCC bug 105651).
std::string case_name(const testing::TestParamInfo<uint32_t>& info) {
    return std::string("n").append(std::to_string(info.param));
}

class PrefixScanTest : public testing::TestWithParam<uint32_t> {};

TEST_P(PrefixScanTest, MatchesExclusiveScan) {
    const uint32_t count = GetParam();
    const Context& context = shared_context();
    std::mt19937 random(count * 2);
    // Values small enough that the sum stays below 2^30, where the scan saturates.
    const uint32_t max_value = count > 0 ? std::min<uint32_t>(1000000u, 0x3fffffffu / count) : 1;
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
    record_scan(stream, input.address(), output.address(), small.address(), small.address() + 4, scratch);
    stream.barrier();
    stream.submit_and_wait();

    auto result = test::read_back(context, output, count + 1);
    EXPECT_EQ(result.back(), 0xcafef00du) << "wrote past count";
    result.pop_back();
    EXPECT_EQ(test::first_difference(result, expected), -1);
    EXPECT_EQ(test::read_back(context, small, 2)[1], expected_total);
    EXPECT_EQ(test::read_back(context, input, count + 1), padded) << "input changed";
}

INSTANTIATE_TEST_SUITE_P(Sizes, PrefixScanTest,
                         testing::Values(0u, 1u, 255u, 256u, 257u, 2048u, 2049u, 4097u, 100003u, 1000000u), case_name);

TEST(PrefixScan, RefusesToScanInPlace) {
    const Context& context = shared_context();
    Buffer data = test::device_buffer(context, 16, "scan data");
    PrefixScan::Scratch scratch(context, 16);
    CommandStream stream(context);
    stream.begin();
    EXPECT_THROW(shared_scan().record(stream, data.address(), data.address(), 0, scratch), std::invalid_argument);
    stream.submit_and_wait();
}

TEST(PrefixScan, NoTotalAddressAndScratchReusedAcrossScans) {
    const Context& context = shared_context();
    PrefixScan::Scratch scratch(context, 50000);
    CommandStream stream(context);
    std::vector<std::vector<uint32_t>> inputs;
    std::vector<Buffer> buffers, outputs;
    std::vector<Buffer> counts;
    const uint32_t sizes[] = {50000, 3, 40961};
    for (uint32_t n : sizes) {
        std::vector<uint32_t> v(n);
        for (uint32_t i = 0; i < n; ++i) v[i] = (i * 7919u) % 13u;
        buffers.push_back(test::upload(context, v, "scan data"));
        outputs.push_back(test::device_buffer(context, n, "scan output"));
        counts.push_back(test::upload(context, {n}, "scan count"));
        inputs.push_back(std::move(v));
    }
    // Three scans in one submission sharing one scratch, ordered by barriers.
    stream.begin();
    for (size_t i = 0; i < buffers.size(); ++i) {
        record_scan(stream, buffers[i].address(), outputs[i].address(), counts[i].address(), 0, scratch);
        stream.barrier();
    }
    stream.submit_and_wait();
    for (size_t i = 0; i < buffers.size(); ++i) {
        std::vector<uint32_t> expected(inputs[i].size());
        std::exclusive_scan(inputs[i].begin(), inputs[i].end(), expected.begin(), 0u);
        EXPECT_EQ(test::first_difference(test::read_back(context, outputs[i], expected.size()), expected), -1)
            << "scan " << i;
    }
}

TEST(PrefixScan, CountAboveCapacityIsClamped) {
    const Context& context = shared_context();
    std::vector<uint32_t> values(3000, 1u);
    Buffer data = test::upload(context, values, "scan data");
    Buffer output = test::upload(context, values, "scan output");
    Buffer small = test::upload(context, {1000000000u, 0u}, "scan count");
    PrefixScan::Scratch scratch(context, 2500);
    CommandStream stream(context);
    stream.begin();
    record_scan(stream, data.address(), output.address(), small.address(), small.address() + 4, scratch);
    stream.barrier();
    stream.submit_and_wait();
    const auto result = test::read_back(context, output, values.size());
    for (uint32_t i = 0; i < 3000; ++i) ASSERT_EQ(result[i], i < 2500 ? i : 1u) << "at " << i;
    EXPECT_EQ(test::read_back(context, small, 2)[1], 2500u);
}

// A block that finds its predecessor's sum unpublished sums that block's input itself. With no
// spinning that happens whenever blocks run at once (lavapipe's threads do).
TEST(PrefixScan, SumsUnpublishedPredecessorsItself) {
    const Context& context = shared_context();
    const PrefixScan impatient(context, 0);
    const uint32_t n = 300007;
    std::vector<uint32_t> values(n);
    for (uint32_t i = 0; i < n; ++i) values[i] = (i * 2654435761u) >> 22;
    std::vector<uint32_t> expected(n);
    std::exclusive_scan(values.begin(), values.end(), expected.begin(), 0u);
    Buffer data = test::upload(context, values, "scan data");
    Buffer output = test::device_buffer(context, n, "scan output");
    Buffer small = test::upload(context, {n, 0u}, "scan count and total");
    PrefixScan::Scratch scratch(context, n);
    CommandStream stream(context);
    stream.begin();
    record_scan(stream, data.address(), output.address(), small.address(), small.address() + 4, scratch, impatient);
    stream.barrier();
    stream.submit_and_wait();
    EXPECT_EQ(test::first_difference(test::read_back(context, output, n), expected), -1);
    EXPECT_EQ(test::read_back(context, small, 2)[1], std::accumulate(values.begin(), values.end(), 0u));
}

// Past 2^30 the sums saturate instead of wrapping: a total that large still reads as more than
// any buffer holds, and every offset below 2^30 is exact.
TEST(PrefixScan, SumsSaturateAtTwoToTheThirty) {
    const Context& context = shared_context();
    const uint32_t n = 5000, big = 1u << 20;  // 1024 elements reach 2^30
    Buffer data = test::upload(context, std::vector<uint32_t>(n, big), "scan data");
    Buffer output = test::device_buffer(context, n, "scan output");
    Buffer small = test::upload(context, {n, 0u}, "scan count and total");
    PrefixScan::Scratch scratch(context, n);
    CommandStream stream(context);
    stream.begin();
    record_scan(stream, data.address(), output.address(), small.address(), small.address() + 4, scratch);
    stream.barrier();
    stream.submit_and_wait();
    const auto result = test::read_back(context, output, n);
    for (uint32_t i = 0; i < 1024; ++i) ASSERT_EQ(result[i], i * big) << "at " << i;
    for (uint32_t i = 1024; i < n; ++i) ASSERT_GE(result[i], PrefixScan::saturated_sum) << "at " << i;
    EXPECT_EQ(test::read_back(context, small, 2)[1], PrefixScan::saturated_sum);
}

}  // namespace
}  // namespace vksplat::gpu
