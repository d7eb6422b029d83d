#pragma once
// Checks for the numeric options of every subcommand. CLI11's own let bad numbers through: Range,
// PositiveNumber and NonNegativeNumber compare, and every comparison with NaN is false, so "nan"
// passes them (and NonNegativeNumber's message prints DBL_MAX as its upper bound); an unsigned
// option reads "-3" as 2^64 - 3 (strtoull wraps) and "010" as octal 8. These read the text
// themselves, so a bad value is refused with the option's name before any work starts.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace vksplat::cli {

// `text` as a finite number (decimal or exponent notation, nothing after it); nullopt for
// anything else, "nan" and "inf" included.
std::optional<double> finite_number(const std::string& text);

// A finite number in [min, max]; a bound of -/+infinity (the default) leaves that side open.
CLI::Validator number_in(double min = -std::numeric_limits<double>::infinity(),
                         double max = std::numeric_limits<double>::infinity());
// A finite number above 0 and at most `max`.
CLI::Validator positive_number(double max = std::numeric_limits<double>::infinity());
// A whole number in [min, max], written in decimal digits: no sign, exponent or leading zero.
CLI::Validator count_in(uint64_t min, uint64_t max = std::numeric_limits<uint64_t>::max());

}  // namespace vksplat::cli
