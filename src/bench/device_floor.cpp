#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/kernel.hpp"
#include "gpu/radix_sort.hpp"
#include "gpu/transfer.hpp"
#include "shaders/bench/bandwidth_copy.kernel.hpp"
#include "vksplat/error.hpp"
#include "vksplat/bench/benchmark.hpp"
#include "vksplat/bench/device_floor.hpp"

namespace vksplat::bench {

namespace {

// Median of `repetitions` submissions of what `record` records, in ms of GPU time, after a warm-up
// (warm_up: one warm-up submission alone left an H200 measuring half its bandwidth after the CPU
// had built a large scene).
template <class Record>
double median_gpu_ms(const gpu::Context& context, int repetitions, Record record) {
    gpu::CommandStream stream(context, 4);
    const auto timed_run = [&] {
        stream.begin();
        record(stream);
        stream.mark("timed");
        stream.submit_and_wait();
        const auto stages = stream.stage_times();
        if (stages.empty()) throw GpuError("measuring device rates: the queue has no timestamp queries");
        return stages.back().milliseconds;
    };
    warm_up(1, timed_run);
    std::vector<double> times;
    for (int i = 0; i < repetitions; ++i) times.push_back(timed_run());
    return median(times);
}

}  // namespace

DeviceRates measure_device_rates(const gpu::Context& context, const RateOptions& options) {
    if (options.repetitions < 1 || options.copy_bytes < 16 || options.copy_bytes >= (64ull << 30) || options.sort_pairs < 1)
        throw InputError("device rates", "repetitions and sort size must be positive, and the copy 16 B to 64 GiB");
    DeviceRates rates;
    rates.sort_pairs = options.sort_pairs;
    {
        rates.copy_bytes = options.copy_bytes & ~uint64_t(15);
        gpu::Buffer source(context, rates.copy_bytes, gpu::MemoryKind::device, "bandwidth source");
        gpu::Buffer target(context, rates.copy_bytes, gpu::MemoryKind::device, "bandwidth target");
        const gpu::Kernel<shader::bench::BandwidthCopyKernel> copy(context);
        const shader::bench::BandwidthCopyPush push{
            .source = source.address(), .target = target.address(), .count = uint32_t(rates.copy_bytes / 16)};
        const double ms = median_gpu_ms(context, options.repetitions, [&](gpu::CommandStream& stream) {
            stream.dispatch(copy, push, std::min<uint32_t>((push.count + 255) / 256, 65535));
        });
        rates.copy_bytes_per_ms = 2.0 * double(rates.copy_bytes) / ms;

        // A chain of copies of one 16-byte word, each behind a barrier; the difference between
        // two chain lengths removes the frame's own begin and end.
        const shader::bench::BandwidthCopyPush tiny{.source = source.address(), .target = target.address(), .count = 1};
        const auto chain_ms = [&](int length) {
            return median_gpu_ms(context, options.repetitions, [&](gpu::CommandStream& stream) {
                for (int i = 0; i < length; ++i) {
                    stream.dispatch(copy, tiny, 1);
                    stream.barrier();
                }
            });
        };
        constexpr int kShort = 8, kLong = 72;
        rates.dependent_dispatch_ms = std::max(0.0, chain_ms(kLong) - chain_ms(kShort)) / (kLong - kShort);
    }
    {
        const uint32_t n = rates.sort_pairs;
        std::mt19937 random(7);
        std::vector<uint32_t> keys(n), values(n);
        for (auto& k : keys) k = random();
        std::iota(values.begin(), values.end(), 0u);
        const gpu::Buffer original = gpu::upload_buffer(context, keys, "sort keys (original)");
        gpu::Buffer key_buffer(context, original.size(), gpu::MemoryKind::device, "sort keys");
        const gpu::Buffer value_buffer = gpu::upload_buffer(context, values, "sort values");
        const gpu::Buffer count = gpu::upload_buffer(context, std::vector<uint32_t>{n}, "sort count");
        gpu::RadixSort sort(context);
        gpu::RadixSort::Scratch scratch(context, n);
        // Each run sorts the same random keys: restoring them is timed separately and removed.
        const double restore_ms = median_gpu_ms(context, options.repetitions, [&](gpu::CommandStream& stream) {
            stream.copy(original, key_buffer, original.size());
        });
        const double ms = median_gpu_ms(context, options.repetitions, [&](gpu::CommandStream& stream) {
            stream.copy(original, key_buffer, original.size());
            sort.record_setup(stream, key_buffer, value_buffer, count.address(), scratch);
            stream.barrier();
            sort.record(stream, key_buffer, value_buffer, 32, scratch);
        });
        rates.sort_pairs_per_ms = double(n) / std::max(ms - restore_ms, 1e-6);
    }
    return rates;
}

FrameFloor frame_floor(const FrameWork& work, const DeviceRates& rates) {
    FrameFloor floor;
    floor.bytes = work.scene_bytes + uint64_t(work.tile_entries) * 48 + work.pixels * 16;
    if (rates.copy_bytes_per_ms > 0) floor.memory_ms = double(floor.bytes) / rates.copy_bytes_per_ms;
    if (rates.sort_pairs_per_ms > 0) {
        const double full_passes = double(gpu::RadixSort::passes_for(32));
        const double tile_passes = work.tile_key_bits ? double(gpu::RadixSort::passes_for(work.tile_key_bits)) : 0;
        floor.sort_ms = (double(work.visible) + double(work.tile_entries) * tile_passes / full_passes) /
                        rates.sort_pairs_per_ms;
    }
    return floor;
}

}  // namespace vksplat::bench
