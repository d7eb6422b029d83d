// RadixSort against std::stable_sort by the masked key, comparing keys and values (values are the
// original indices, so stability is checked exactly).
#include "gpu/radix_sort.hpp"

#include "gpu_test_util.hpp"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <numeric>
#include <random>

namespace vksplat::gpu {
namespace {

using test::shared_context;

const RadixSort& shared_sort() {
    static RadixSort sort(shared_context());
    return sort;
}

enum class Pattern { random, few_distinct, all_equal, sorted, reversed };

const char* pattern_name(Pattern p) {
    switch (p) {
        case Pattern::random: return "random";
        case Pattern::few_distinct: return "few_distinct";
        case Pattern::all_equal: return "all_equal";
        case Pattern::sorted: return "sorted";
        case Pattern::reversed: return "reversed";
    }
    return "?";
}

uint32_t mask_for(uint32_t bits) { return bits >= 32 ? 0xffffffffu : (1u << bits) - 1u; }

// Keys carry random bits above key_bits too: the sort must ignore them and keep them.
std::vector<uint32_t> make_keys(uint32_t count, uint32_t bits, Pattern pattern, uint32_t seed) {
    std::mt19937 random(seed);
    const uint32_t mask = mask_for(bits);
    std::vector<uint32_t> keys(count);
    for (auto& k : keys) k = random();
    switch (pattern) {
        case Pattern::random: break;
        case Pattern::few_distinct:
            for (auto& k : keys) k = (k & ~mask) | ((k % 5u) * 0x9e3779b9u & mask);
            break;
        case Pattern::all_equal: std::fill(keys.begin(), keys.end(), keys.empty() ? 0u : keys[0]); break;
        case Pattern::sorted:
        case Pattern::reversed: {
            std::vector<uint32_t> low(count);
            for (auto& l : low) l = random() & mask;
            std::sort(low.begin(), low.end());
            if (pattern == Pattern::reversed) std::reverse(low.begin(), low.end());
            for (uint32_t i = 0; i < count; ++i) keys[i] = (keys[i] & ~mask) | low[i];
            break;
        }
    }
    return keys;
}

// Reference result: std::stable_sort of (key, index) pairs by key & mask.
void reference_sort(std::vector<uint32_t>& keys, std::vector<uint32_t>& values, uint32_t bits) {
    const uint32_t mask = mask_for(bits);
    std::vector<uint32_t> order(keys.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return (keys[a] & mask) < (keys[b] & mask); });
    std::vector<uint32_t> sorted_keys(keys.size()), sorted_values(keys.size());
    for (size_t i = 0; i < order.size(); ++i) {
        sorted_keys[i] = keys[order[i]];
        sorted_values[i] = values[order[i]];
    }
    keys.swap(sorted_keys);
    values.swap(sorted_values);
}

struct SortResult {
    std::vector<uint32_t> keys;
    std::vector<uint32_t> values;
    double sort_ms = -1;  // GPU time of the sort alone, when the queue has timestamps
};

// Sorts on the GPU. The buffers hold `keys.size()` elements; the GPU reads `count` from memory.
SortResult gpu_sort(const std::vector<uint32_t>& keys, const std::vector<uint32_t>& values, uint32_t count,
                    uint32_t bits, uint32_t scratch_capacity, const RadixSort& sort = shared_sort()) {
    const Context& context = shared_context();
    Buffer key_buffer = test::upload(context, keys, "keys");
    Buffer value_buffer = test::upload(context, values, "values");
    Buffer count_buffer = test::upload(context, {count}, "count");
    RadixSort::Scratch scratch(context, scratch_capacity);
    CommandStream stream(context);
    stream.begin();
    stream.barrier();
    stream.mark("before");
    sort.record_setup(stream, key_buffer, value_buffer, count_buffer.address(), scratch);
    stream.barrier();
    sort.record(stream, key_buffer, value_buffer, bits, scratch);
    stream.barrier();
    stream.mark("sort");
    stream.submit_and_wait();
    SortResult result;
    for (const auto& t : stream.stage_times())
        if (t.label == "sort") result.sort_ms = t.milliseconds;
    result.keys = test::read_back(context, key_buffer, keys.size());
    result.values = test::read_back(context, value_buffer, values.size());
    return result;
}

struct SortCase {
    uint32_t count;
    uint32_t bits;
    Pattern pattern;
};

std::string sort_case_name(const testing::TestParamInfo<SortCase>& info) {
    return "n" + std::to_string(info.param.count) + "_bits" + std::to_string(info.param.bits) + "_" +
           pattern_name(info.param.pattern);
}

class RadixSortTest : public testing::TestWithParam<SortCase> {};

void check_sort(uint32_t count, uint32_t bits, Pattern pattern, bool print_time = false,
                const RadixSort& sort = shared_sort()) {
    auto keys = make_keys(count, bits, pattern, count * 37u + bits);
    std::vector<uint32_t> values(count);
    std::iota(values.begin(), values.end(), 0u);
    const SortResult result = gpu_sort(keys, values, count, bits, count, sort);
    reference_sort(keys, values, bits);
    const long key_difference = test::first_difference(result.keys, keys);
    ASSERT_EQ(key_difference, -1) << "keys differ, e.g. at " << key_difference << ": got "
                                  << result.keys[std::max(0l, key_difference)] << " expected "
                                  << keys[std::max(0l, key_difference)];
    const long value_difference = test::first_difference(result.values, values);
    ASSERT_EQ(value_difference, -1) << "values (original indices) differ, e.g. at " << value_difference << ": got "
                                    << result.values[std::max(0l, value_difference)] << " expected "
                                    << values[std::max(0l, value_difference)];
    if (print_time && result.sort_ms > 0)
        std::cout << "[ timing   ] " << count << " pairs, " << bits << "-bit keys: " << result.sort_ms << " ms on "
                  << shared_context().info().name << " = " << count / (result.sort_ms * 1e-3) / 1e6
                  << " M pairs/s (information only)\n";
}

TEST_P(RadixSortTest, MatchesStableSort) {
    const auto& c = GetParam();
    check_sort(c.count, c.bits, c.pattern);
}

std::vector<SortCase> sort_cases() {
    std::vector<SortCase> cases;
    // The full size list at 32 and 12 bits (10^6 at 32 bits is the timing test below).
    for (uint32_t n : {0u, 1u, 255u, 256u, 257u, 2048u, 2049u, 4097u, 100003u}) cases.push_back({n, 32, Pattern::random});
    for (uint32_t n : {0u, 1u, 255u, 256u, 257u, 4097u, 1000000u}) cases.push_back({n, 12, Pattern::random});
    // Every other width at a couple of sizes.
    for (uint32_t bits : {1u, 4u, 7u, 8u, 9u, 16u, 24u, 31u}) {
        cases.push_back({257, bits, Pattern::random});
        cases.push_back({100003, bits, Pattern::random});
    }
    // Patterns that stress stability and the per-digit bookkeeping.
    for (uint32_t bits : {32u, 12u, 1u}) {
        cases.push_back({4097, bits, Pattern::all_equal});
        cases.push_back({4097, bits, Pattern::few_distinct});
        cases.push_back({4097, bits, Pattern::sorted});
        cases.push_back({4097, bits, Pattern::reversed});
    }
    cases.push_back({100003, 32, Pattern::all_equal});
    cases.push_back({100003, 32, Pattern::sorted});
    cases.push_back({100003, 16, Pattern::few_distinct});
    cases.push_back({1000000, 16, Pattern::all_equal});
    return cases;
}

INSTANTIATE_TEST_SUITE_P(Cases, RadixSortTest, testing::ValuesIn(sort_cases()), sort_case_name);

// A scatter block that finds a predecessor's digit counts unpublished counts that block's keys
// itself. With no spinning that happens whenever blocks run at once (lavapipe's threads do: a
// fallback that added one key too many failed this test and four of the cases above).
TEST(RadixSort, CountsUnpublishedPredecessorsItself) {
    const RadixSort impatient(shared_context(), 0);
    for (uint32_t bits : {32u, 12u}) {
        check_sort(100003, bits, Pattern::random, false, impatient);
        check_sort(100003, bits, Pattern::few_distinct, false, impatient);
    }
}

// Checks a 10^6-pair 32-bit sort and prints its GPU time (information only, no assertion): the
// second of two sorts on the same buffers, so first-touch costs of fresh memory are not counted.
// VKSPLAT_SORT_TIMING_COUNT and VKSPLAT_SORT_TIMING_BITS change the size and key width.
TEST(RadixSort, MillionPairs32BitsWithTiming) {
    const Context& context = shared_context();
    const char* count_text = std::getenv("VKSPLAT_SORT_TIMING_COUNT");
    const char* bits_text = std::getenv("VKSPLAT_SORT_TIMING_BITS");
    const uint32_t n = count_text ? static_cast<uint32_t>(std::stoul(count_text)) : 1000000;
    const uint32_t bits = bits_text ? static_cast<uint32_t>(std::stoul(bits_text)) : 32;
    auto keys = make_keys(n, bits, Pattern::random, 99);
    std::vector<uint32_t> values(n);
    std::iota(values.begin(), values.end(), 0u);
    Buffer key_staging = test::staging(context, keys);
    Buffer value_staging = test::staging(context, values);
    Buffer key_buffer = test::device_buffer(context, n, "keys");
    Buffer value_buffer = test::device_buffer(context, n, "values");
    Buffer count_buffer = test::upload(context, {n}, "count");
    RadixSort::Scratch scratch(context, n);
    CommandStream stream(context);
    double sort_ms = -1;
    for (int round = 0; round < 2; ++round) {
        stream.begin();
        stream.copy(key_staging, key_buffer, n * 4);
        stream.copy(value_staging, value_buffer, n * 4);
        stream.barrier();
        stream.mark("upload");
        shared_sort().record_setup(stream, key_buffer, value_buffer, count_buffer.address(), scratch);
        stream.barrier();
        shared_sort().record(stream, key_buffer, value_buffer, bits, scratch);
        stream.barrier();
        stream.mark("sort");
        stream.submit_and_wait();
        for (const auto& t : stream.stage_times())
            if (t.label == "sort") sort_ms = t.milliseconds;
    }
    reference_sort(keys, values, bits);
    EXPECT_EQ(test::first_difference(test::read_back(context, key_buffer, n), keys), -1);
    EXPECT_EQ(test::first_difference(test::read_back(context, value_buffer, n), values), -1);
    if (sort_ms > 0) {
        std::cout << "[ timing   ] sort of " << n << " pairs by " << bits << "-bit keys: " << sort_ms << " ms = "
                  << n / (sort_ms * 1e-3) / 1e6 << " M pairs/s on " << context.info().name
                  << " (information only)\n";
        for (const auto& t : stream.stage_times()) std::cout << "[ timing   ]   " << t.label << " " << t.milliseconds << " ms\n";
    }
}

TEST(RadixSort, CountFromGpuMemoryLeavesTheRestUntouched) {
    const uint32_t size = 5000, count = 3001, bits = 20;
    auto keys = make_keys(size, 32, Pattern::random, 7);
    std::vector<uint32_t> values(size);
    std::iota(values.begin(), values.end(), 0u);
    // Scratch larger than the count, buffers larger still.
    const SortResult result = gpu_sort(keys, values, count, bits, 4000);
    std::vector<uint32_t> head_keys(keys.begin(), keys.begin() + count), head_values(values.begin(), values.begin() + count);
    reference_sort(head_keys, head_values, bits);
    for (uint32_t i = 0; i < size; ++i) {
        const uint32_t expected_key = i < count ? head_keys[i] : keys[i];
        const uint32_t expected_value = i < count ? head_values[i] : values[i];
        ASSERT_EQ(result.keys[i], expected_key) << "key at " << i;
        ASSERT_EQ(result.values[i], expected_value) << "value at " << i;
    }
}

TEST(RadixSort, CountAboveCapacityIsClamped) {
    const uint32_t size = 3000, capacity = 2000, bits = 32;
    auto keys = make_keys(size, 32, Pattern::random, 11);
    std::vector<uint32_t> values(size);
    std::iota(values.begin(), values.end(), 0u);
    const SortResult result = gpu_sort(keys, values, 0xffffffffu, bits, capacity);
    std::vector<uint32_t> head_keys(keys.begin(), keys.begin() + capacity),
        head_values(values.begin(), values.begin() + capacity);
    reference_sort(head_keys, head_values, bits);
    for (uint32_t i = 0; i < size; ++i) {
        ASSERT_EQ(result.keys[i], i < capacity ? head_keys[i] : keys[i]) << "key at " << i;
        ASSERT_EQ(result.values[i], i < capacity ? head_values[i] : values[i]) << "value at " << i;
    }
}

TEST(RadixSort, CountIsClampedToTheBuffers) {
    const uint32_t size = 1500, bits = 16;
    auto keys = make_keys(size, 32, Pattern::random, 13);
    std::vector<uint32_t> values(size);
    std::iota(values.begin(), values.end(), 0u);
    const SortResult result = gpu_sort(keys, values, 0xffffffffu, bits, 4000);  // scratch > buffers
    reference_sort(keys, values, bits);
    EXPECT_EQ(test::first_difference(result.keys, keys), -1);
    EXPECT_EQ(test::first_difference(result.values, values), -1);
}

// The renderer's pattern: a depth sort, then a stable sort of the same pairs by a narrower key,
// sharing one scratch in one submission.
TEST(RadixSort, TwoSortsInOneSubmissionShareScratch) {
    const Context& context = shared_context();
    const uint32_t n = 30011;
    auto keys = make_keys(n, 32, Pattern::random, 3);
    std::vector<uint32_t> values(n);
    std::iota(values.begin(), values.end(), 0u);
    Buffer key_buffer = test::upload(context, keys, "keys");
    Buffer value_buffer = test::upload(context, values, "values");
    Buffer count_buffer = test::upload(context, {n}, "count");
    RadixSort::Scratch scratch(context, n);
    CommandStream stream(context);
    stream.begin();
    for (uint32_t bits : {32u, 10u}) {
        shared_sort().record_setup(stream, key_buffer, value_buffer, count_buffer.address(), scratch);
        stream.barrier();
        shared_sort().record(stream, key_buffer, value_buffer, bits, scratch);
        stream.barrier();
    }
    stream.barrier();
    stream.submit_and_wait();
    reference_sort(keys, values, 32);
    reference_sort(keys, values, 10);
    EXPECT_EQ(test::first_difference(test::read_back(context, key_buffer, n), keys), -1);
    EXPECT_EQ(test::first_difference(test::read_back(context, value_buffer, n), values), -1);
}

TEST(RadixSort, RejectsBadKeyWidths) {
    const Context& context = shared_context();
    Buffer keys = test::device_buffer(context, 16, "keys");
    Buffer values = test::device_buffer(context, 16, "values");
    RadixSort::Scratch scratch(context, 16);
    CommandStream stream(context);
    stream.begin();
    EXPECT_THROW(shared_sort().record(stream, keys, values, 0, scratch), std::invalid_argument);
    EXPECT_THROW(shared_sort().record(stream, keys, values, 33, scratch), std::invalid_argument);
    stream.submit_and_wait();
}

// A sort whose count is known when recording: one sweep gets its setup from the host and tells
// the keys' producer which digits to count (the renderer's preprocess does, checked by the render
// tests against the CPU reference); a larger one is left to record_setup.
TEST(RadixSort, HostSetupOnlyForOneSweepSorts) {
    const Context& context = shared_context();
    const uint32_t small = 1000, large = 192 * shared_sort().block_size() + 1;
    Buffer small_keys = test::device_buffer(context, small, "keys");
    Buffer small_values = test::device_buffer(context, small, "values");
    Buffer large_keys = test::device_buffer(context, large, "keys");
    Buffer large_values = test::device_buffer(context, large, "values");
    RadixSort::Scratch small_scratch(context, small), large_scratch(context, large);
    CommandStream stream(context);
    stream.begin();
    const auto depth = shared_sort().record_host_setup(stream, small_keys, small_values, small, 32, small_scratch);
    ASSERT_TRUE(depth.has_value());
    EXPECT_EQ(depth->passes, 4u);
    for (uint32_t pass = 0; pass < 4; ++pass) EXPECT_EQ(depth->digits[pass], pass * 8 | 8u << 8);
    EXPECT_NE(depth->totals.value, 0u);
    EXPECT_NE(depth->lookback.value, 0u);
    EXPECT_EQ(depth->lookback_words, 4u * 256u);  // one block: its words of every pass
    stream.barrier();  // the same scratch is set up again
    const auto tiles = shared_sort().record_host_setup(stream, small_keys, small_values, small, 12, small_scratch);
    ASSERT_TRUE(tiles.has_value());
    EXPECT_EQ(tiles->passes, 2u);
    EXPECT_EQ(tiles->digits[0], 0u | 6u << 8);
    EXPECT_EQ(tiles->digits[1], 6u | 6u << 8);
    EXPECT_FALSE(shared_sort().record_host_setup(stream, large_keys, large_values, large, 32, large_scratch));
    EXPECT_THROW(shared_sort().record(stream, large_keys, large_values, 32, large_scratch, true), std::logic_error);
    stream.submit_and_wait();
}

// Blocks are 256 x 16 keys where the device runs 256 invocations whose subgroups are at most 16
// and whose scatter fits its shared memory, else 128 x 16 (never below one subgroup).
TEST(RadixSort, BlockSizeFollowsTheDeviceLimits) {
    DeviceInfo info;
    info.subgroup_size = info.min_subgroup_size = 32;
    info.max_workgroup_invocations = 1024;
    info.max_shared_memory_bytes = 48 * 1024;
    EXPECT_EQ(RadixSort::block_size_for(info), 4096u);
    info.max_shared_memory_bytes = 26 * 1024 - 4;  // the 256-wide scatter needs 26 KiB
    EXPECT_EQ(RadixSort::block_size_for(info), 2048u);
    info.max_shared_memory_bytes = 48 * 1024;
    info.max_workgroup_invocations = 128;
    EXPECT_EQ(RadixSort::block_size_for(info), 2048u);
    info.max_workgroup_invocations = 1024;
    info.subgroup_size = info.min_subgroup_size = 8;  // lavapipe: 256 would be 32 subgroups
    EXPECT_EQ(RadixSort::block_size_for(info), 2048u);
    info.subgroup_size = 32, info.min_subgroup_size = 4;  // 4-lane subgroups: 16 of them in 64
    EXPECT_EQ(RadixSort::block_size_for(info), 64u * 16u);
    info.subgroup_size = info.min_subgroup_size = 64;  // AMD wave64
    EXPECT_EQ(RadixSort::block_size_for(info), 4096u);
}

}  // namespace
}  // namespace vksplat::gpu
