// The size budget: a bisection on the file's bytes, and the trade of count against SH bands.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <stdexcept>
#include <vector>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "support/scratch_dir.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/prune/sh_precision.hpp"
#include "vksplat/prune/sh_reduction.hpp"
#include "vksplat/prune/size_budget.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

TEST(LargestFitting, FindsTheLastCountThatFitsInAFewCallsWhereBytesGrowAsALine) {
    size_t calls = 0;
    const auto bytes_of = [&](size_t count) {
        ++calls;
        return 100 + 10 * count;
    };
    EXPECT_EQ(prune::largest_fitting(1000, 595, bytes_of), 49u);
    EXPECT_LE(calls, 6u) << "bisection took 12";
    EXPECT_EQ(prune::largest_fitting(1000, 600, bytes_of), 50u);
    EXPECT_EQ(prune::largest_fitting(1000, 109, bytes_of), 0u) << "not even one";
    EXPECT_EQ(prune::largest_fitting(1000, 110, bytes_of), 1u);
    EXPECT_EQ(prune::largest_fitting(1000, 100000, bytes_of), 1000u);
    EXPECT_EQ(prune::largest_fitting(0, 100000, bytes_of), 0u);
    // A compressed file: a line with a wobble of a few bytes that never falls.
    calls = 0;
    size_t written = 0;  // Gaussians written in all: what the search costs
    const auto wobbly = [&](size_t count) {
        ++calls;
        written += count;
        return 5000 + 37 * count + (count * 7919 % 13);
    };
    EXPECT_EQ(prune::largest_fitting(400000, 3000000, wobbly), 80945u);
    EXPECT_LE(calls, 8u);
    // The whole cloud is not written where the line says it cannot fit: a file of all 400,000 would
    // cost more than the search's other counts together.
    EXPECT_LT(written, 6 * 80945u) << calls << " calls";
    // Where it fits, it is found.
    EXPECT_EQ(prune::largest_fitting(400000, 15000000, wobbly), 400000u);
}

TEST(LargestFitting, IsExactAndNeverMuchSlowerThanBisectionWhereBytesAreFarFromALine) {
    // Steps, plateaus, jumps and curves that never fall, against the last count that fits by a walk.
    const std::vector<std::function<size_t(size_t)>> shapes = {
        [](size_t c) { return c * c; },
        [](size_t c) { return size_t(1000 * std::sqrt(double(c))); },
        [](size_t c) { return c < 3000 ? c : 1000000 + c; },
        [](size_t c) { return 100 * (c / 250); },
        [](size_t c) { return size_t(std::exp(double(c) / 400.0)); },
    };
    constexpr size_t kMost = 4000;
    for (size_t s = 0; s < shapes.size(); ++s) {
        const auto& bytes_of = shapes[s];
        for (size_t max_bytes : {size_t(1), size_t(7), size_t(500), size_t(12345), size_t(999999), size_t(4000000)}) {
            size_t expected = 0;
            while (expected < kMost && bytes_of(expected + 1) <= max_bytes) ++expected;
            size_t calls = 0;
            const size_t found = prune::largest_fitting(kMost, max_bytes, [&](size_t c) {
                ++calls;
                EXPECT_TRUE(c >= 1 && c <= kMost) << c;
                return bytes_of(c);
            });
            EXPECT_EQ(found, expected) << "shape " << s << ", " << max_bytes << " bytes";
            EXPECT_LE(calls, 3 * 12 + 2u) << "shape " << s << ", " << max_bytes << " bytes";
        }
    }
}

TEST(SceneFileBytes, AreTheBytesTheWriterWrites) {
    const fs::path dir = fresh_test_dir("vksplat_size_budget_");
    const GaussianCloud cloud = random_scene(91, 100, 3);
    for (const std::string format : {"spz", "compressed-ply", "ply"}) {
        const fs::path path = dir / ("scene." + format);
        io::write_scene(cloud, path, io::WriteMode::refuse_existing, format);
        EXPECT_EQ(prune::scene_file_bytes(cloud, format), fs::file_size(path)) << format;
    }
    fs::remove_all(dir);
}

// A choice that took every Gaussian's top band is a model of lower degree: the bands it kept are
// counted among that degree's.
TEST(ModelShShare, IsTheShareOfTheChosenModelsOwnBands) {
    prune::BudgetResult choice;
    choice.sh_degree = 3;
    choice.sh_share = 0.5;
    EXPECT_DOUBLE_EQ(prune::model_sh_share(choice, 3), 0.5);
    choice.sh_degree = 2;  // of 3 bands each, 1 kept: half of the 2 left
    choice.sh_share = 4.0 / 6.0;
    EXPECT_NEAR(prune::model_sh_share(choice, 3), 0.5, 1e-12);
    choice.sh_degree = 0;  // every higher band gone: none left to drop
    choice.sh_share = 1.0;
    EXPECT_EQ(prune::model_sh_share(choice, 3), 0.0);
    choice.sh_degree = 2;  // the whole cloud at degree 2
    choice.sh_share = 0.0;
    EXPECT_EQ(prune::model_sh_share(choice, 3), 0.0);
}

TEST(FitRefitted, DropsTheBandsTheRefittedModelNeedsLeastAndItsLeastGaussiansUntilItFits) {
    // A re-fit gives every Gaussian colour in every band; which go is decided on these values.
    const GaussianCloud refitted = random_scene(93, 300, 3);
    std::vector<double> weights(refitted.size());
    for (size_t i = 0; i < weights.size(); ++i) weights[i] = double((i * 11) % 7) + 0.5;
    std::vector<float> scores(refitted.size());
    for (size_t i = 0; i < scores.size(); ++i) scores[i] = float((i * 37) % 300);
    const std::vector<uint8_t> degrees = prune::reduced_sh_degrees(refitted, weights, 0.5);
    ASSERT_NE(degrees, prune::reduced_sh_degrees(refitted, {}, 0.5)) << "the test needs weights that matter";

    prune::SizeBudget budget;
    budget.format = "spz";
    budget.max_bytes = prune::scene_file_bytes(refitted, "spz");
    const GaussianCloud roomy = prune::fit_refitted(refitted, weights, scores, 0.5, budget);
    EXPECT_EQ(roomy.size(), refitted.size());
    EXPECT_EQ(prune::sh_degrees_in_use(roomy), degrees) << "the cheapest bands by the weights and re-fitted values";
    EXPECT_EQ(roomy.positions, refitted.positions);

    const GaussianCloud reduced = prune::with_sh_degrees(refitted, degrees);
    budget.max_bytes = prune::scene_file_bytes(reduced, "spz") / 2;
    const GaussianCloud tight = prune::fit_refitted(refitted, weights, scores, 0.5, budget);
    EXPECT_LE(prune::scene_file_bytes(tight, "spz"), budget.max_bytes);
    EXPECT_LT(tight.size(), refitted.size());
    EXPECT_GT(tight.size(), refitted.size() / 4);
    const prune::KeepMask best = prune::Ranking(scores, prune::keep_all(scores.size())).keep_best(tight.size());
    EXPECT_EQ(tight.positions, reduced.subset(best).positions) << "the best kept";
    EXPECT_EQ(tight.sh, reduced.subset(best).sh);
    EXPECT_THROW(prune::fit_refitted(refitted.subset(best), weights, scores, 0.5, budget), std::invalid_argument);
}

class SizeBudget : public GpuTest {
protected:
    void SetUp() override {
        renderer = std::make_unique<Renderer>(context());
        views = eval::render_targets(*renderer, cloud, cameras, {});
    }
    // At full SH precision unless asked otherwise (nullopt: the budget tries kSizeBudgetPrecisions).
    prune::BudgetResult fit(size_t max_bytes, const std::string& format,
                            std::optional<prune::ShPrecision> precision = prune::ShPrecision{}) {
        prune::SizeBudget budget;
        budget.max_bytes = max_bytes;
        budget.format = format;
        budget.sh_precision = precision;
        return prune::fit_size_budget(*renderer, cloud, ranking, {}, views, budget, {});
    }
    GaussianCloud cloud = random_scene(92, 400, 3);
    std::vector<Camera> cameras = {forward_camera(64, 48, 60.0)};
    std::vector<float> scores = prune::score(cloud, {}, prune::ScoreMethod::opacity);
    prune::Ranking ranking{scores, prune::keep_all(cloud.size())};
    std::unique_ptr<Renderer> renderer;
    eval::TestViews views;
};

TEST_F(SizeBudget, KeepsTheBestModelThatFitsTradingCountAgainstBands) {
    const size_t whole = prune::scene_file_bytes(cloud, "spz");
    const prune::BudgetResult small = fit(whole / 3, "spz");
    ASSERT_TRUE(small.model);
    EXPECT_LE(prune::scene_file_bytes(*small.model, "spz"), whole / 3);
    EXPECT_EQ(small.model->size(), small.kept);
    EXPECT_EQ(prune::count_kept(small.keep), small.kept);
    // Per-Gaussian bands, whole degrees and count all tried, each at the most Gaussians that fit.
    EXPECT_EQ(small.probes.size(), 9u);
    bool per_gaussian = false;
    for (const auto& probe : small.probes) {
        EXPECT_LE(probe.bytes, whole / 3);
        EXPECT_GE(probe.drop, small.drop);
        per_gaussian |= probe.sh_share > 0 && probe.sh_share < 1;
    }
    EXPECT_TRUE(per_gaussian);
    for (const auto& probe : small.probes) {
        if (probe.drop == small.drop) {
            EXPECT_EQ(probe.sh_share, small.sh_share) << "the share of the model chosen";
        }
    }
    EXPECT_GT(small.probes.back().kept, small.probes.front().kept) << "fewer bands, more Gaussians";

    const prune::BudgetResult larger = fit(whole / 2, "spz");
    EXPECT_LT(larger.drop, small.drop);
    const prune::BudgetResult all = fit(whole, "spz");
    EXPECT_EQ(all.probes.size(), 1u);
    EXPECT_EQ(all.kept, cloud.size());
    EXPECT_EQ(all.drop, 0.0);
}

// Fewer bits of SPZ's SH byte: the candidates are measured as rounded, so the model chosen is
// rounded, fits, and keeps more Gaussians at full SH than at full precision.
TEST_F(SizeBudget, MeasuresItsCandidatesAtTheSHPrecisionAsked) {
    const size_t budget = prune::scene_file_bytes(cloud, "spz") / 2;
    const prune::ShPrecision coarse{6, 4};
    const prune::BudgetResult rounded = fit(budget, "spz", coarse);
    ASSERT_TRUE(rounded.model);
    EXPECT_LE(prune::scene_file_bytes(*rounded.model, "spz"), budget);
    EXPECT_EQ(rounded.model->sh, prune::with_sh_precision(*rounded.model, coarse).sh) << "already on the grid";
    const prune::BudgetResult full = fit(budget, "spz");
    EXPECT_GT(rounded.probes.front().kept, full.probes.front().kept) << "at every band, more Gaussians fit";
}

// Unset, the precision is one more thing traded by measurement: every precision's choices are
// probed (where the format gains from it) and the least drop of all is kept.
TEST_F(SizeBudget, TriesEachPrecisionWhereTheFormatGainsAndKeepsTheLeastDrop) {
    const size_t budget = prune::scene_file_bytes(cloud, "spz") / 3;
    const prune::BudgetResult searched = fit(budget, "spz", std::nullopt);
    ASSERT_TRUE(searched.model);
    EXPECT_LE(prune::scene_file_bytes(*searched.model, "spz"), budget);
    std::set<std::pair<int, int>> tried;
    for (const auto& probe : searched.probes) {
        tried.insert({probe.sh_precision.degree1_bits, probe.sh_precision.higher_bits});
        EXPECT_GE(probe.drop, searched.drop);
    }
    EXPECT_EQ(tried.size(), std::size(prune::kSizeBudgetPrecisions));
    EXPECT_EQ(searched.model->sh, prune::with_sh_precision(*searched.model, searched.sh_precision).sh);
    // compressed PLY stores each SH value in a byte of its own grid: rounding them gains nothing.
    const prune::BudgetResult fixed_bytes = fit(prune::scene_file_bytes(cloud, "compressed-ply") / 2, "compressed-ply",
                                                std::nullopt);
    for (const auto& probe : fixed_bytes.probes) EXPECT_EQ(probe.sh_precision, prune::ShPrecision{});
}

TEST_F(SizeBudget, SkipsPerGaussianBandsWhereTheFormatStoresNoZerosCompactly) {
    const size_t whole = prune::scene_file_bytes(cloud, "compressed-ply");
    const prune::BudgetResult result = fit(whole / 2, "compressed-ply");
    ASSERT_TRUE(result.model);
    EXPECT_LE(prune::scene_file_bytes(*result.model, "compressed-ply"), whole / 2);
    // Its SH bytes are fixed: zeros gain only where every Gaussian lost the band (degree below 3).
    for (const auto& probe : result.probes) {
        if (probe.sh_share > 0) {
            EXPECT_LT(probe.sh_degree, 3) << "share " << probe.sh_share;
        }
    }
    EXPECT_LT(result.probes.size(), 9u) << "a share too small to empty band 3 is skipped unmeasured";
}

// With a re-fit to come, a shortlist is measured again after it and the choice is by those
// measurements alone: at each precision the least drop as it is, and every band at full degree.
TEST_F(SizeBudget, WithAReFitChoosesAmongTheShortlistAsReFitted) {
    prune::SizeBudget budget;
    budget.max_bytes = prune::scene_file_bytes(cloud, "spz") / 3;
    budget.format = "spz";
    budget.sh_precision = std::nullopt;
    const prune::BudgetResult plain = prune::fit_size_budget(*renderer, cloud, ranking, {}, views, budget, {});
    // A stand-in re-fit that ruins every candidate with dropped bands (all but transparent) and
    // leaves those with every band as they are.
    size_t refits = 0;
    budget.refit = [&](const GaussianCloud& model) {
        ++refits;
        if (model.sh_degree == cloud.sh_degree) {
            const size_t stride = size_t(model.sh_coefficients()) * 3;
            bool every_band = true;
            for (size_t i = 0; every_band && i < model.size(); ++i) every_band = model.sh[i * stride + stride - 1] != 0.0f;
            if (every_band) return model;
        }
        GaussianCloud ruined = model;
        for (float& logit : ruined.opacity_logits) logit = -10.0f;
        return ruined;
    };
    const prune::BudgetResult refitted = prune::fit_size_budget(*renderer, cloud, ranking, {}, views, budget, {});
    const size_t precisions = std::size(prune::kSizeBudgetPrecisions);
    EXPECT_GE(refits, precisions);
    EXPECT_LE(refits, 2 * precisions) << "the shortlist only";
    size_t refitted_probes = 0;
    for (const auto& probe : refitted.probes) refitted_probes += probe.refitted;
    EXPECT_EQ(refitted_probes, refits);
    EXPECT_EQ(refitted.probes.size(), plain.probes.size() + refitted_probes) << "the plain probes first";
    EXPECT_EQ(refitted.sh_share, 0.0) << "the stand-in re-fit left every band the best";
    EXPECT_EQ(refitted.sh_degree, cloud.sh_degree);
    for (const auto& probe : refitted.probes)
        if (probe.refitted) {
            EXPECT_GE(probe.drop, refitted.drop);
        }
}

// A re-fit that makes the file grow: the candidate keeps the count whose file, grown as much, fits.
TEST_F(SizeBudget, AReFitThatGrowsTheFileKeepsTheCountThatStillFits) {
    prune::SizeBudget budget;
    budget.max_bytes = prune::scene_file_bytes(cloud, "spz") / 3;
    budget.format = "spz";
    const prune::BudgetResult plain = prune::fit_size_budget(*renderer, cloud, ranking, {}, views, budget, {});
    // Noise in every SH value and position, which SPZ then stores in more bytes.
    budget.refit = [&](const GaussianCloud& model) {
        GaussianCloud noisy = model;
        for (size_t k = 0; k < noisy.sh.size(); ++k) noisy.sh[k] += 0.5f * float((k * 7919) % 13) / 13.0f;
        for (size_t k = 0; k < noisy.positions.size(); ++k) noisy.positions[k] += 1e-3f * float((k * 104729) % 17);
        return noisy;
    };
    const prune::BudgetResult refitted = prune::fit_size_budget(*renderer, cloud, ranking, {}, views, budget, {});
    size_t fewer = 0, compared = 0;
    for (const auto& probe : refitted.probes) {
        if (!probe.refitted) continue;
        EXPECT_LE(probe.bytes, budget.max_bytes);
        for (const auto& before : plain.probes)
            if (before.sh_share == probe.sh_share && before.sh_degree == probe.sh_degree &&
                before.sh_precision == probe.sh_precision) {
                EXPECT_LE(probe.kept, before.kept) << "share " << probe.sh_share;
                if (probe.sh_share == 0) {  // the noise survives in every band: the file grew
                    ++compared;
                    fewer += probe.kept < before.kept;
                }
            }
    }
    EXPECT_GT(compared, 0u);
    EXPECT_EQ(fewer, compared) << "where the file grew, the candidate keeps fewer";
}

TEST_F(SizeBudget, RefusesABudgetBelowTheSmallestModelNamingItsSize) {
    GaussianCloud one = cloud.subset(ranking.keep_best(1)).with_sh_degree(0);
    const size_t smallest = prune::scene_file_bytes(one, "spz");
    EXPECT_EQ(fit(smallest, "spz").kept, 1u);
    try {
        fit(smallest - 1, "spz");
        FAIL() << "a budget below one Gaussian must be refused";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("one Gaussian at SH degree 0, takes " + std::to_string(smallest) + " bytes"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace vksplat::test
