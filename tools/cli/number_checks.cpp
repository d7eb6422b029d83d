// The numeric option checks (number_checks.hpp): each parses the option's text with from_chars,
// which takes decimal only and no NaN comparison tricks, and names the allowed range in words.
#include "number_checks.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace vksplat::cli {
namespace {

std::string shown(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", value);
    return text;
}

// "in [0, 1]", ">= 0", "<= 3" or "" for the bounds; an infinite bound is no bound, and so is
// never printed.
std::string range_words(double min, double max) {
    const bool low = std::isfinite(min), high = std::isfinite(max);
    if (low && high) return "in [" + shown(min) + ", " + shown(max) + "]";
    if (low) return ">= " + shown(min);
    if (high) return "<= " + shown(max);
    return "";
}

// A check whose help text and complaint both say "a <what> <range>".
CLI::Validator numeric_check(const std::string& what, const std::string& range,
                             std::function<bool(const std::string&)> accepts) {
    const std::string wanted = what + (range.empty() ? "" : " " + range);
    return CLI::Validator(
        [wanted, accepts](std::string& text) {
            return accepts(text) ? std::string() : "'" + text + "' is not " + wanted;
        },
        wanted);
}

}  // namespace

std::optional<double> finite_number(const std::string& text) {
    const char* first = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
    const char* last = text.data() + text.size();
    double value = 0;
    const auto [end, error] = std::from_chars(first, last, value);
    if (error != std::errc() || end != last || first == last || !std::isfinite(value)) return std::nullopt;
    return value;
}

CLI::Validator number_in(double min, double max) {
    return numeric_check("a finite number", range_words(min, max), [min, max](const std::string& text) {
        const auto value = finite_number(text);
        return value && *value >= min && *value <= max;
    });
}

CLI::Validator positive_number(double max) {
    const std::string range = std::isfinite(max) ? "in (0, " + shown(max) + "]" : "> 0";
    return numeric_check("a finite number", range, [max](const std::string& text) {
        const auto value = finite_number(text);
        return value && *value > 0 && *value <= max;
    });
}

CLI::Validator count_in(uint64_t min, uint64_t max) {
    const std::string range = max == std::numeric_limits<uint64_t>::max()
                                  ? ">= " + std::to_string(min)
                                  : "in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
    return numeric_check("a whole number", range, [min, max](const std::string& text) {
        uint64_t value = 0;
        const char* last = text.data() + text.size();
        const auto [end, error] = std::from_chars(text.data(), last, value);
        // A leading zero is refused because CLI11 then reads the digits as octal.
        const bool plain = !text.empty() && (text[0] != '0' || text.size() == 1);
        return plain && error == std::errc() && end == last && value >= min && value <= max;
    });
}

}  // namespace vksplat::cli
