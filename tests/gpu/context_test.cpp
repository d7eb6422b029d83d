// Context, Buffer and CommandStream basics on whatever Vulkan device is present (lavapipe here).
#include "gpu_test_util.hpp"

#include "gpu/compute_pipeline.hpp"
#include "gpu/prefix_scan.hpp"

#include <algorithm>
#include <numeric>

namespace vksplat::gpu {
namespace {

using test::shared_context;

TEST(Context, ListsDevices) {
    const auto devices = list_devices();
    ASSERT_FALSE(devices.empty());
    bool any_usable = false;
    for (const auto& device : devices) {
        EXPECT_FALSE(device.name.empty());
        if (device.usable) {
            any_usable = true;
        } else {
            EXPECT_FALSE(device.unusable_reason.empty()) << device.name;
        }
    }
    EXPECT_TRUE(any_usable);
}

TEST(Context, CreatesDeviceWithSubgroupInfo) {
    const Context& context = shared_context();
    EXPECT_NE(context.device(), VK_NULL_HANDLE);
    EXPECT_NE(context.queue(), VK_NULL_HANDLE);
    const DeviceInfo& info = context.info();
    EXPECT_TRUE(info.usable);
    EXPECT_GE(info.subgroup_size, 4u);
    EXPECT_LE(info.subgroup_size, 128u);
    EXPECT_GE(info.min_subgroup_size, 1u);
    EXPECT_LE(info.min_subgroup_size, info.subgroup_size);
    EXPECT_TRUE(context.validation_messages().empty());
    std::cout << "[ device   ] " << info.name << " (" << info.type_name() << "), subgroup size " << info.subgroup_size
              << " (min " << info.min_subgroup_size << ")\n";
}

// Asked for, the driver's description of every pipeline built on the context, in order, where the
// driver offers one (NVIDIA: registers, shared memory, binary size); otherwise nothing, and the
// device is created without the extension rather than failing.
TEST(Context, PipelineStatisticsWhereTheDriverOffersThem) {
    ContextOptions options;
    options.pipeline_statistics = true;
    const Context context(options);
    const PrefixScan scan(context);
    const auto statistics = context.pipeline_statistics();
    if (!context.info().pipeline_statistics) {
        EXPECT_TRUE(statistics.empty());
        GTEST_SKIP() << context.info().name << " offers no VK_KHR_pipeline_executable_properties";
    }
    ASSERT_FALSE(statistics.empty());
    EXPECT_TRUE(std::any_of(statistics.begin(), statistics.end(),
                            [](const PipelineStatistics& p) { return p.pipeline == "scan_lookback"; }));
    for (const auto& p : statistics) EXPECT_FALSE(p.values.empty()) << p.pipeline;
}

TEST(Context, NoPipelineStatisticsUnlessAskedFor) {
    const PrefixScan scan(shared_context());
    EXPECT_TRUE(shared_context().pipeline_statistics().empty());
}

TEST(Context, SecondContextCoexists) {
    Context other;
    EXPECT_NE(other.device(), shared_context().device());
}

TEST(Buffer, DeviceBuffersHaveAddressesHostBuffersAreMapped) {
    const Context& context = shared_context();
    Buffer device(context, 1024, MemoryKind::device, "device");
    Buffer upload(context, 1024, MemoryKind::upload, "upload");
    Buffer readback(context, 1024, MemoryKind::readback, "readback");
    EXPECT_NE(device.address(), 0u);
    EXPECT_EQ(device.mapped(), nullptr);
    EXPECT_NE(upload.mapped(), nullptr);
    EXPECT_NE(readback.mapped(), nullptr);
    EXPECT_EQ(device.size(), 1024u);
    EXPECT_EQ(device.name(), "device");

    Buffer moved = std::move(device);
    EXPECT_TRUE(moved);
    EXPECT_FALSE(device);  // NOLINT(bugprone-use-after-move): moved-from state is specified
    Buffer empty(context, 0, MemoryKind::device, "empty");
    EXPECT_TRUE(empty);
    EXPECT_EQ(empty.size(), 0u);
}

// The context counts device buffers as they come and go, and remembers the most it held; staging
// buffers are host memory and do not count. A fresh context, so no other test's buffers are in it.
TEST(Buffer, ContextCountsHeldAndPeakDeviceBytes) {
    const Context context;
    EXPECT_EQ(context.held_device_bytes(), 0u);
    {
        const Buffer a(context, 1 << 20, MemoryKind::device, "a");
        const Buffer staging(context, 4 << 20, MemoryKind::upload, "staging");
        EXPECT_GE(context.held_device_bytes(), 1u << 20);
        EXPECT_LT(context.held_device_bytes(), 2u << 20);  // alignment rounds up, not the staging buffer
        {
            Buffer b(context, 3 << 20, MemoryKind::device, "b");
            EXPECT_GE(context.held_device_bytes(), 4u << 20);
            Buffer moved = std::move(b);  // moving hands the count over: it is counted once
            EXPECT_LT(context.held_device_bytes(), 5u << 20);
        }
        EXPECT_LT(context.held_device_bytes(), 2u << 20);
        EXPECT_GE(context.peak_device_bytes(), 4u << 20);
        context.reset_peak_device_bytes();
        EXPECT_EQ(context.peak_device_bytes(), context.held_device_bytes());
    }
    EXPECT_EQ(context.held_device_bytes(), 0u);
    EXPECT_GE(context.peak_device_bytes(), 1u << 20);
}

TEST(CommandStream, UploadReadbackRoundTrip) {
    const Context& context = shared_context();
    std::vector<uint32_t> data(10007);
    std::iota(data.begin(), data.end(), 12345u);
    Buffer device = test::upload(context, data, "round trip");
    EXPECT_EQ(test::read_back(context, device, data.size()), data);
}

TEST(CommandStream, FillAndCopyWithOffsetsInOneSubmission) {
    const Context& context = shared_context();
    const size_t n = 1000;
    Buffer a(context, n * 4, MemoryKind::device, "a");
    Buffer b(context, n * 4, MemoryKind::device, "b");
    Buffer host(context, n * 4, MemoryKind::readback, "host");
    CommandStream stream(context);
    stream.begin();
    stream.fill(a, 7u);
    stream.barrier();  // the second fill overwrites part of the first: write after write
    stream.fill(a, 9u, 100 * 4, 50 * 4);
    stream.fill(b, 0xffffffffu);
    stream.barrier();
    stream.copy(a, b, 200 * 4, 50 * 4, 10 * 4);  // a[50..250) -> b[10..210)
    stream.barrier();
    stream.mark("work");
    stream.copy(b, host, n * 4);
    stream.submit_and_wait();
    const auto* out = static_cast<const uint32_t*>(host.mapped());
    for (size_t i = 0; i < n; ++i) {
        uint32_t expected = 0xffffffffu;
        if (i >= 10 && i < 210) {
            const size_t j = i - 10 + 50;
            expected = (j >= 100 && j < 150) ? 9u : 7u;
        }
        ASSERT_EQ(out[i], expected) << "at " << i;
    }
    const auto times = stream.stage_times();
    if (context.info().timestamp_period_ns > 0) {
        ASSERT_EQ(times.size(), 1u);
        EXPECT_EQ(times[0].label, "work");
        EXPECT_GE(times[0].milliseconds, 0.0);
    }
}

TEST(CommandStream, ReusableAcrossSubmissions) {
    const Context& context = shared_context();
    Buffer device(context, 64, MemoryKind::device, "reuse");
    Buffer host(context, 64, MemoryKind::readback, "reuse host");
    CommandStream stream(context);
    for (uint32_t round = 0; round < 3; ++round) {
        stream.begin();
        stream.fill(device, round * 11);
        stream.barrier();
        stream.copy(device, host, 64);
        stream.submit_and_wait();
        EXPECT_EQ(static_cast<const uint32_t*>(host.mapped())[15], round * 11);
    }
}

}  // namespace
}  // namespace vksplat::gpu
