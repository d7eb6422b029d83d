// The training loss: the double-precision reference against finite differences of itself and
// closed forms, then the GPU passes against the reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <random>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/transfer.hpp"
#include "support/gpu_fixture.hpp"
#include "train/loss_passes.hpp"
#include "vksplat/reference/training_loss.hpp"

namespace vksplat::test {
namespace {

constexpr double kLambda = 0.2;
constexpr double kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;

// A photo channel as the shader reads it (loss.comp's photo_channel): bit for bit.
float photo_channel(uint32_t word, int ch) { return float((word >> (8 * ch)) & 255u) * (1.0f / 255.0f); }

// A rendered image (vec4 per pixel, as the blend writes it) and a photo (RGBA8 words, alpha 0 =
// masked out), plus the same data as the reference takes it.
struct ImagePair {
    int width = 0, height = 0;
    std::vector<float> rendered;   // rgba per pixel
    std::vector<uint32_t> photo;   // RGBA8 per pixel

    size_t pixels() const { return size_t(width) * size_t(height); }
    std::vector<double> rendered_rgb() const {
        std::vector<double> rgb(3 * pixels());
        for (size_t p = 0; p < pixels(); ++p)
            for (int ch = 0; ch < 3; ++ch) rgb[3 * p + ch] = rendered[4 * p + ch];
        return rgb;
    }
    std::vector<float> photo_rgb() const {
        std::vector<float> rgb(3 * pixels());
        for (size_t p = 0; p < pixels(); ++p)
            for (int ch = 0; ch < 3; ++ch) rgb[3 * p + ch] = photo_channel(photo[p], ch);
        return rgb;
    }
    std::vector<uint8_t> mask() const {
        std::vector<uint8_t> m(pixels());
        for (size_t p = 0; p < pixels(); ++p) m[p] = uint8_t(photo[p] >> 24);
        return m;
    }
    reference::TrainingLoss reference(double lambda = kLambda) const {
        const std::vector<double> x = rendered_rgb();
        const std::vector<float> y = photo_rgb();
        const std::vector<uint8_t> m = mask();
        return reference::training_loss(width, height, x, y, m, lambda);
    }
};

enum class Content {
    noise,      // rendered and photo independent and uniform (rendered up to 1.1, as unclamped colours go)
    close,      // a smooth photo with grain, rendered = photo + small errors, 1 in 8 pixels exact (sign 0)
    identical,  // rendered = photo exactly
};

// Masked: one pixel in five at random plus a 16 x 16 block (so that some masked pixels have only
// masked pixels in their window), all with alpha 0 and arbitrary rgb.
ImagePair make_pair(int width, int height, Content content, bool masked, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> error(0.0, 0.03);
    const size_t pixels = size_t(width) * size_t(height);
    ImagePair pair{width, height, std::vector<float>(4 * pixels), std::vector<uint32_t>(pixels)};
    for (int py = 0; py < height; ++py) {
        for (int px = 0; px < width; ++px) {
            const size_t p = size_t(py) * width + px;
            uint32_t word = 0;
            for (int ch = 0; ch < 3; ++ch) {
                double value = unit(rng);
                if (content != Content::noise)
                    value = 0.5 + 0.35 * std::sin(0.21 * px + 0.9 * ch) * std::cos(0.17 * py - 0.4 * ch) +
                            0.1 * (value - 0.5);
                word |= uint32_t(std::lround(std::clamp(value, 0.0, 1.0) * 255.0)) << (8 * ch);
            }
            const bool in_block = px >= width / 2 && px < width / 2 + 16 && py >= height / 2 && py < height / 2 + 16;
            const bool out = masked && (unit(rng) < 0.2 || in_block);
            word |= (out ? 0u : 255u) << 24;
            pair.photo[p] = word;
            const bool exact = content == Content::identical || (content == Content::close && rng() % 8 == 0);
            for (int ch = 0; ch < 3; ++ch) {
                const float y = photo_channel(word, ch);
                float x = y;
                if (content == Content::noise) x = float(1.1 * unit(rng));
                else if (!exact) x = float(y + error(rng));
                pair.rendered[4 * p + ch] = x;
            }
            pair.rendered[4 * p + 3] = float(unit(rng));  // alpha: the loss must ignore it
        }
    }
    return pair;
}

double max_abs(const std::vector<double>& v) {
    double m = 0;
    for (double x : v) m = std::max(m, std::abs(x));
    return m;
}

// ---------------------------------------------------------------------------------------------
// The reference

// Central differences of the reference's own loss, for every pixel and channel.
void expect_gradient_matches_differences(const ImagePair& pair, double lambda) {
    const std::vector<double> x = pair.rendered_rgb();
    const std::vector<float> y = pair.photo_rgb();
    const std::vector<uint8_t> mask = pair.mask();
    const reference::TrainingLoss analytic = reference::training_loss(pair.width, pair.height, x, y, mask, lambda);
    const double h = 1e-6;
    double max_error = 0;
    std::vector<double> probe = x;
    for (size_t i = 0; i < x.size(); ++i) {
        probe[i] = x[i] + h;
        const double up = reference::training_loss(pair.width, pair.height, probe, y, mask, lambda).loss;
        probe[i] = x[i] - h;
        const double down = reference::training_loss(pair.width, pair.height, probe, y, mask, lambda).loss;
        probe[i] = x[i];
        max_error = std::max(max_error, std::abs((up - down) / (2 * h) - analytic.gradient[i]));
    }
    const double scale = max_abs(analytic.gradient);
    // The L1 part alone is (1 - lambda) / (3WH) per element: the gradient is not trivially small.
    EXPECT_GT(scale, 0.5 * (1 - lambda) / (3.0 * double(pair.pixels())));
    // Differences with h = 1e-6 are good to ~1e-10 here (rounding ~1e-16 / h, curvature ~h^2).
    EXPECT_LE(max_error, 1e-6 * scale) << "max error " << max_error << " of scale " << scale;
}

// The pair, with rendered values moved off the L1 kink (|x - y| >= 1e-3): a central difference
// across the kink measures the kink, not the derivative.
ImagePair away_from_kinks(ImagePair pair) {
    for (size_t p = 0; p < pair.pixels(); ++p)
        for (int ch = 0; ch < 3; ++ch) {
            float& x = pair.rendered[4 * p + ch];
            const float y = photo_channel(pair.photo[p], ch);
            if (std::abs(x - y) < 1e-3f) x = y + 2e-3f;
        }
    return pair;
}

TEST(LossReference, GradientMatchesFiniteDifferences) {
    expect_gradient_matches_differences(away_from_kinks(make_pair(19, 13, Content::noise, false, 1)), kLambda);
    expect_gradient_matches_differences(away_from_kinks(make_pair(19, 13, Content::close, false, 2)), kLambda);
}

TEST(LossReference, MaskedGradientMatchesFiniteDifferences) {
    const ImagePair pair = away_from_kinks(make_pair(19, 13, Content::noise, true, 3));
    expect_gradient_matches_differences(pair, kLambda);
    expect_gradient_matches_differences(pair, 0.7);
    // The mask takes terms out of the loss, but the pixels it masks still pass gradient to the
    // SSIM of their unmasked neighbours.
    const reference::TrainingLoss loss = pair.reference();
    const std::vector<uint8_t> mask = pair.mask();
    bool masked_with_gradient = false;
    for (size_t p = 0; p < pair.pixels(); ++p)
        masked_with_gradient |= mask[p] == 0 && std::abs(loss.gradient[3 * p]) > 0;
    EXPECT_TRUE(masked_with_gradient);
}

TEST(LossReference, IdenticalImagesHaveSsimOneAndNoLoss) {
    for (const bool masked : {false, true}) {
        const ImagePair pair = make_pair(23, 17, Content::identical, masked, 4);
        const reference::TrainingLoss loss = pair.reference();
        const std::vector<uint8_t> mask = pair.mask();
        const double kept = double(std::count_if(mask.begin(), mask.end(), [](uint8_t m) { return m != 0; })) /
                            double(pair.pixels());
        EXPECT_EQ(loss.l1, 0.0);
        EXPECT_EQ(loss.mse, 0.0);
        EXPECT_NEAR(loss.ssim, kept, 1e-12) << masked;
        EXPECT_NEAR(loss.loss, kLambda * (1 - kept), 1e-12) << masked;
        // SSIM = 1 is its maximum, and the L1 kink contributes sign(0) = 0.
        EXPECT_LE(max_abs(loss.gradient), 1e-12 / (3.0 * double(pair.pixels()))) << masked;
    }
    if (HasFailure()) return;
    // Not vacuous: different images do lose.
    const reference::TrainingLoss loss = make_pair(23, 17, Content::close, false, 4).reference();
    EXPECT_LT(loss.ssim, 0.99);
    EXPECT_GT(loss.loss, 0.001);
}

// One pixel: each moment is the window's centre weight w = g0^2 times the pixel's value, so SSIM
// has a closed form (zero padding leaves nothing else in the window).
TEST(LossReference, OnePixelHasTheClosedForm) {
    double sum = 0;
    for (int i = -5; i <= 5; ++i) sum += std::exp(-i * i / (2 * 1.5 * 1.5));
    const double g0 = 1.0 / sum;
    const double w = g0 * g0;
    const std::vector<double> x{0.3, 0.9, 0.5};
    const std::vector<float> y{0.7f, 0.2f, 0.5f};
    double ssim = 0, l1 = 0;
    for (int ch = 0; ch < 3; ++ch) {
        const double xv = x[ch], yv = y[ch];
        ssim += (2 * w * xv * w * yv + kC1) * (2 * (w * xv * yv - w * xv * w * yv) + kC2) /
                ((w * w * (xv * xv + yv * yv) + kC1) * ((w - w * w) * (xv * xv + yv * yv) + kC2)) / 3;
        l1 += std::abs(xv - yv) / 3;
    }
    const reference::TrainingLoss loss = reference::training_loss(1, 1, x, y, {}, kLambda);
    EXPECT_NEAR(loss.ssim, ssim, 1e-14);
    EXPECT_NEAR(loss.l1, l1, 1e-15);
    EXPECT_NEAR(loss.loss, (1 - kLambda) * l1 + kLambda * (1 - ssim), 1e-14);
    // Blue is equal in both: SSIM is at its maximum and L1 at its kink, sign(0) = 0.
    EXPECT_NEAR(loss.gradient[2], 0.0, 1e-15);
}

TEST(LossReference, RejectsMismatchedSizes) {
    const std::vector<double> x(3 * 6);
    const std::vector<float> y(3 * 6);
    const std::vector<uint8_t> mask(5);
    EXPECT_THROW(reference::training_loss(3, 2, x, y, mask, kLambda), std::invalid_argument);
    EXPECT_THROW(reference::training_loss(2, 2, x, y, {}, kLambda), std::invalid_argument);
    EXPECT_THROW(reference::training_loss(0, 2, {}, {}, {}, kLambda), std::invalid_argument);
    EXPECT_NO_THROW(reference::training_loss(3, 2, x, y, {}, kLambda));
}

// ---------------------------------------------------------------------------------------------
// The GPU passes

class Loss : public GpuTest {
protected:
    struct Result {
        train::LossValue value;
        std::vector<float> gradient;  // rgba per pixel
    };

    Result run(train::LossPasses& passes, const ImagePair& pair, float lambda = float(kLambda)) {
        const gpu::Buffer rendered = gpu::upload_buffer(context(), pair.rendered, "rendered");
        const gpu::Buffer photo = gpu::upload_buffer(context(), pair.photo, "photo");
        const gpu::Buffer gradient(context(), pair.pixels() * 4 * sizeof(float), gpu::MemoryKind::device, "gradient");
        gpu::CommandStream stream(context());
        stream.begin();
        // NaN everywhere first: every pixel must be written.
        stream.fill(gradient, 0x7fc00000u);
        stream.barrier();
        passes.record(stream, {.rendered = rendered.address(),
                               .photo = photo.address(),
                               .gradient = gradient.address(),
                               .width = uint32_t(pair.width),
                               .height = uint32_t(pair.height),
                               .ssim_weight = lambda});
        stream.barrier();
        stream.submit_and_wait();
        return {passes.last(), gpu::read_buffer<float>(context(), gradient, pair.pixels() * 4)};
    }
};

struct Errors {
    // Largest error of loss, l1, ssim, mse, relative to the value or to 0.01, whichever is larger:
    // a loss near 0 (identical images) is a difference of float terms near 1.
    double sums = 0;
    double gradient = 0;  // largest error over max(max |reference gradient|, (1 - lambda) / (3WH))
};

Errors compare(const ImagePair& pair, const reference::TrainingLoss& ref, const train::LossValue& gpu,
               const std::vector<float>& gradient, double lambda) {
    Errors e;
    const auto relative = [](double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-2); };
    e.sums = std::max({relative(gpu.loss, ref.loss), relative(gpu.l1, ref.l1), relative(gpu.ssim, ref.ssim),
                       relative(gpu.mse, ref.mse)});
    const double scale = std::max(max_abs(ref.gradient), (1 - lambda) / (3.0 * double(pair.pixels())));
    for (size_t p = 0; p < pair.pixels(); ++p) {
        for (int ch = 0; ch < 3; ++ch) {
            const double error = std::abs(double(gradient[4 * p + ch]) - ref.gradient[3 * p + ch]);
            e.gradient = std::max(e.gradient, std::isfinite(error) ? error / scale : INFINITY);
        }
        EXPECT_EQ(gradient[4 * p + 3], 0.0f) << p;
    }
    return e;
}

TEST_F(Loss, MatchesTheReference) {
    // One object for every size, small and large in turn: its scratch grows and is reused.
    train::LossPasses passes(context());
    struct Case {
        int width, height;
        Content content;
    };
    // Sizes that are not multiples of the tile (32 x 8), thinner than a tile, or thinner than the
    // window, so that tiles' regions reach past every edge of the image; heights of more than one
    // strip of tiles (64 rows).
    const Case cases[] = {{64, 48, Content::close},     {1, 1, Content::noise},   {130, 75, Content::noise},
                          {7, 5, Content::close},       {33, 17, Content::noise}, {130, 75, Content::close},
                          {1, 1, Content::close},       {37, 29, Content::identical}, {37, 23, Content::noise},
                          {300, 7, Content::close},     {3, 90, Content::noise}};
    uint32_t seed = 10;
    for (const Case& c : cases) {
        for (const bool masked : {false, true}) {
            const ImagePair pair = make_pair(c.width, c.height, c.content, masked, seed++);
            SCOPED_TRACE(::testing::Message() << c.width << " x " << c.height << " content " << int(c.content)
                                              << (masked ? " masked" : ""));
            const Result gpu = run(passes, pair);
            const reference::TrainingLoss ref = pair.reference();
            const Errors e = compare(pair, ref, gpu.value, gpu.gradient, kLambda);
            // Float moments against double ones: SSIM's variances cancel E[x^2] - E[x]^2, which
            // costs a few digits where the window is flat.
            EXPECT_LE(e.sums, 1e-5) << "loss " << gpu.value.loss << " vs " << ref.loss;
            EXPECT_LE(e.gradient, 1e-4);
            if (c.content == Content::identical) {
                EXPECT_EQ(gpu.value.l1, 0.0);
                EXPECT_EQ(gpu.value.mse, 0.0);
            }
            // Masked pixels whose window holds only masked pixels (the block's inner 6 x 6, less
            // what lies outside the image, where the window holds nothing) get no gradient at all.
            if (masked && c.width >= 33 && c.height >= 17) {
                int isolated = 0;
                for (int py = c.height / 2 + 5; py < std::min(c.height / 2 + 11, c.height); ++py)
                    for (int px = c.width / 2 + 5; px < std::min(c.width / 2 + 11, c.width); ++px) {
                        ++isolated;
                        for (int ch = 0; ch < 3; ++ch)
                            EXPECT_EQ(gpu.gradient[4 * (size_t(py) * c.width + px) + ch], 0.0f);
                    }
                EXPECT_GT(isolated, 0);
            }
        }
    }
    // The per-pixel maps between the SSIM's moments and the gradient stay in shared memory: the
    // scratch holds the workgroups' sums only, less than a float per pixel.
    EXPECT_LT(passes.device_bytes(), 130u * 75u * sizeof(float));
}

// The GPU's own loss, moved by +-h at a few pixels, against the gradient it writes: the sums and
// the gradient agree with each other, not only each with the reference. The pixels lie on tile
// edges and image corners, some masked (their gradient is all from their neighbours' SSIM).
TEST_F(Loss, GradientMatchesDifferencesOfItsLoss) {
    train::LossPasses passes(context());
    ImagePair pair = make_pair(37, 23, Content::noise, true, 40);
    struct Probe {
        int x, y;
    };
    const Probe probes[] = {{0, 0}, {15, 7}, {16, 8}, {36, 22}, {20, 16}, {31, 12}, {32, 12}};
    const float h = 1e-2f;
    // Off the L1 kink by more than h: a difference across the kink measures the kink.
    for (const Probe& probe : probes)
        for (int ch = 0; ch < 3; ++ch) {
            const size_t p = size_t(probe.y) * pair.width + probe.x;
            float& x = pair.rendered[4 * p + ch];
            const float y = photo_channel(pair.photo[p], ch);
            if (std::abs(x - y) < 3 * h) x = y + (y < 0.5f ? 4 * h : -4 * h);
        }
    const std::vector<uint8_t> mask = pair.mask();
    int masked_probes = 0;
    for (const Probe& probe : probes) masked_probes += mask[size_t(probe.y) * pair.width + probe.x] == 0;
    ASSERT_GT(masked_probes, 0);
    ASSERT_LT(masked_probes, int(std::size(probes)));

    const Result at = run(passes, pair);
    const double scale = max_abs(std::vector<double>(at.gradient.begin(), at.gradient.end()));
    for (const Probe& probe : probes)
        for (int ch = 0; ch < 3; ++ch) {
            const size_t i = 4 * (size_t(probe.y) * pair.width + probe.x) + ch;
            ImagePair moved = pair;
            moved.rendered[i] = pair.rendered[i] + h;
            const double up = run(passes, moved).value.loss;
            moved.rendered[i] = pair.rendered[i] - h;
            const double down = run(passes, moved).value.loss;
            // The step actually taken, in float.
            const double step = double(pair.rendered[i] + h) - double(pair.rendered[i] - h);
            const double error = std::abs((up - down) / step - double(at.gradient[i]));
            // Float sums: ~1e-4 of the scale here.
            EXPECT_LE(error, 1e-3 * scale) << probe.x << ", " << probe.y << " channel " << ch << ": difference "
                                           << (up - down) / step << ", gradient " << at.gradient[i];
        }
}

TEST_F(Loss, TakesTheSsimWeight) {
    train::LossPasses passes(context());
    const ImagePair pair = make_pair(40, 21, Content::close, true, 30);
    const Result gpu = run(passes, pair, 0.7f);
    const reference::TrainingLoss ref = pair.reference(double(0.7f));
    const Errors e = compare(pair, ref, gpu.value, gpu.gradient, 0.7);
    EXPECT_LE(e.sums, 1e-5);
    EXPECT_LE(e.gradient, 1e-4);
    EXPECT_NEAR(gpu.value.loss, 0.3 * gpu.value.l1 + 0.7 * (1 - gpu.value.ssim), 1e-6);
}

TEST_F(Loss, IsDeterministic) {
    train::LossPasses passes(context());
    const ImagePair pair = make_pair(130, 75, Content::close, true, 31);
    const Result first = run(passes, pair);
    const Result second = run(passes, pair);
    EXPECT_EQ(first.value.loss, second.value.loss);
    EXPECT_EQ(first.value.ssim, second.value.ssim);
    EXPECT_EQ(first.value.mse, second.value.mse);
    ASSERT_EQ(first.gradient.size(), second.gradient.size());
    for (size_t i = 0; i < first.gradient.size(); ++i)
        ASSERT_EQ(std::bit_cast<uint32_t>(first.gradient[i]), std::bit_cast<uint32_t>(second.gradient[i])) << i;
}

TEST_F(Loss, RejectsAnEmptyImage) {
    train::LossPasses passes(context());
    gpu::CommandStream stream(context());
    stream.begin();
    EXPECT_THROW(passes.record(stream, {.width = 0, .height = 4}), std::invalid_argument);
    stream.submit_and_wait();
    EXPECT_EQ(passes.last().loss, 0.0);
}

}  // namespace
}  // namespace vksplat::test
