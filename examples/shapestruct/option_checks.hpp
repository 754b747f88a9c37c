// SPDX-License-Identifier: MIT
// CLI11 validators for the shapestruct tool's option values. A failed check is a usage error (exit code 2)
// whose message names the option: "--threads: must be >= 0, got -1". Every integer option has one: they read
// the value as a decimal integer (CLI11 alone would read "010" as octal 8 and "0x10" as 16).
#pragma once

#include <CLI/CLI.hpp>
#include <charconv>
#include <initializer_list>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace shapestruct::cli {

namespace option_check_detail {

template <class T>
std::string number_text(T x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

/// Reads `value` as a T: integers in decimal (a leading '+' allowed), other numbers as CLI11 does.
template <class T>
bool read_number(const std::string& value, T& x) {
  if constexpr (std::is_integral_v<T>) {
    const char* begin = value.data() + (!value.empty() && value[0] == '+' ? 1 : 0);
    const char* end = value.data() + value.size();
    const auto [ptr, ec] = std::from_chars(begin, end, x, 10);
    return ec == std::errc() && ptr == end && begin != end;
  } else {
    return CLI::detail::lexical_cast(value, x);
  }
}

/// A validator of numbers of type T in [lo, hi] (either end optional), its message given by `expected`. An
/// integer is handed on to CLI11 in its plain decimal form.
template <class T>
CLI::Validator number_check(bool has_lo, T lo, bool has_hi, T hi, std::string expected) {
  return CLI::Validator(
      [=](std::string& value) -> std::string {
        T x{};
        if (!read_number(value, x))
          return std::string(std::is_integral_v<T> ? "needs an integer" : "needs a number") + ", got '" + value + "'";
        if ((has_lo && !(x >= lo)) || (has_hi && !(x <= hi))) return "must be " + expected + ", got " + value;
        if constexpr (std::is_integral_v<T>) value = std::to_string(x);
        return {};
      },
      "");  // no description: the option's help text states the range
}

}  // namespace option_check_detail

/// A decimal integer, any value.
inline CLI::Validator integer() {
  return option_check_detail::number_check<long long>(false, 0, false, 0, "");
}

/// The value is at least `min`.
template <class T>
CLI::Validator at_least(T min) {
  return option_check_detail::number_check<T>(true, min, false, T{}, ">= " + option_check_detail::number_text(min));
}

/// The value is in min..max.
template <class T>
CLI::Validator in_range(T min, T max) {
  return option_check_detail::number_check<T>(
      true, min, true, max,
      "in " + option_check_detail::number_text(min) + ".." + option_check_detail::number_text(max));
}

/// An up axis 0, 1 or 2, or "none" (handed on as -1: the shapes share no up direction).
inline CLI::Validator up_axis_or_none() {
  const CLI::Validator axis = in_range(0LL, 2LL);
  return CLI::Validator(
      [axis](std::string& value) -> std::string {
        if (value == "none") {
          value = "-1";
          return {};
        }
        const std::string problem = axis(value);
        return problem.empty() ? problem : "must be 0, 1, 2 or none, got '" + value + "'";
      },
      "");
}

/// The value is one of `choices` (exactly).
inline CLI::Validator one_of(std::initializer_list<const char*> choices) {
  std::vector<std::string> c(choices.begin(), choices.end());
  std::string expected;
  for (std::size_t i = 0; i < c.size(); ++i) expected += (i == 0 ? "" : i + 1 == c.size() ? " or " : ", ") + c[i];
  return CLI::Validator(
      [c, expected](std::string& value) -> std::string {
        for (const auto& x : c)
          if (value == x) return {};
        return "must be " + expected + ", got '" + value + "'";
      },
      "");
}

}  // namespace shapestruct::cli
