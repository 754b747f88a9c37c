// SPDX-License-Identifier: MIT
// The subcommand registry of the shapestruct command-line tool. Each cmd_<name>.cpp registers a setup function
// that declares its subcommand's options on a CLI11 subcommand (main.cpp creates it, named and described) and
// returns the function that runs the command once the command line has been parsed.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>

namespace shapestruct::cli {

/// Runs a subcommand with the values its setup bound to its options; returns the process exit code.
using command_fn = std::function<int()>;

/// Declares a subcommand's positionals and options on `app` and returns what runs it.
using setup_fn = std::function<command_fn(CLI::App& app)>;

struct command_info {
  std::string summary;  ///< one line, listed by `shapestruct --help` and heading `shapestruct CMD --help`
  setup_fn setup;
};

inline std::map<std::string, command_info>& registry() {
  static std::map<std::string, command_info> commands;
  return commands;
}

/// Defined at namespace scope in each cmd_<name>.cpp: `const register_command reg{"inspect", {summary, setup}};`
struct register_command {
  register_command(const std::string& name, command_info info) { registry().emplace(name, std::move(info)); }
};

/// A command-line mistake found after parsing (e.g. an input folder without shapes): exit code 2, like CLI11's
/// own parse errors.
struct usage_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace shapestruct::cli
