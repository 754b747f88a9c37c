// SPDX-License-Identifier: MIT
// The subcommand registry of the shapestruct command-line tool.
#pragma once

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace shapestruct::cli {

/// A subcommand gets its arguments (after the subcommand name) and returns the process exit code.
using command_fn = std::function<int(const std::vector<std::string>& args)>;

struct command_info {
  std::string summary;  ///< one line for `shapestruct --help`
  std::string usage;    ///< full usage text for `shapestruct CMD --help`
  command_fn run;
};

inline std::map<std::string, command_info>& registry() {
  static std::map<std::string, command_info> commands;
  return commands;
}

/// Defined at namespace scope in each cmd_<name>.cpp: `static const register_command reg{"inspect", {...}};`
struct register_command {
  register_command(const std::string& name, command_info info) { registry().emplace(name, std::move(info)); }
};

/// A command-line usage mistake: printed with the command's usage, exit code 2.
struct usage_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Small helpers for parsing "-o DIR", "--seed S" style options.
class arg_reader {
 public:
  explicit arg_reader(const std::vector<std::string>& args) : args_(args) {}
  /// True (and consumed) if the flag is present.
  bool flag(const std::string& name) {
    for (std::size_t i = 0; i < args_.size(); ++i)
      if (args_[i] == name) {
        args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i));
        return true;
      }
    return false;
  }
  /// The value after `name` (or after any of its aliases), consumed; `fallback` if absent.
  std::string option(const std::vector<std::string>& names, const std::string& fallback = {}) {
    for (std::size_t i = 0; i < args_.size(); ++i)
      for (const auto& n : names)
        if (args_[i] == n) {
          if (i + 1 >= args_.size()) throw usage_error("option " + n + " needs a value");
          std::string v = args_[i + 1];
          args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i), args_.begin() + static_cast<std::ptrdiff_t>(i) + 2);
          return v;
        }
    return fallback;
  }
  long long integer(const std::vector<std::string>& names, long long fallback) {
    const std::string v = option(names);
    if (v.empty()) return fallback;
    try {
      std::size_t used = 0;
      const long long x = std::stoll(v, &used);
      if (used != v.size()) throw std::invalid_argument(v);
      return x;
    } catch (const std::exception&) {
      throw usage_error("option " + names.front() + " needs an integer, got '" + v + "'");
    }
  }
  double real(const std::vector<std::string>& names, double fallback) {
    const std::string v = option(names);
    if (v.empty()) return fallback;
    try {
      std::size_t used = 0;
      const double x = std::stod(v, &used);
      if (used != v.size()) throw std::invalid_argument(v);
      return x;
    } catch (const std::exception&) {
      throw usage_error("option " + names.front() + " needs a number, got '" + v + "'");
    }
  }
  /// The remaining positional arguments; throws on a leftover unknown option.
  std::vector<std::string> positionals() const {
    for (const auto& a : args_)
      if (a.size() > 1 && a[0] == '-' && !(a[1] >= '0' && a[1] <= '9')) throw usage_error("unknown option " + a);
    return args_;
  }

 private:
  std::vector<std::string> args_;
};

}  // namespace shapestruct::cli
