// SPDX-License-Identifier: MIT
// shapestruct: the command-line tool. Subcommands live in cmd_<name>.cpp and register themselves (command.hpp);
// CLI11 parses the command line. Exit codes: 0 success, 1 failure (unreadable input, ...), 2 usage error.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "command.hpp"
#include "huge_pages.hpp"
#include "process_group.hpp"
#include "shapestruct/config.hpp"
#include "shapestruct/core/errors.hpp"

namespace {

int run_tool(int argc, char** argv) {
  using namespace shapestruct::cli;
  CLI::App app{std::string("shapestruct ") + SHAPESTRUCT_VERSION_STRING + ": structure in collections of 3D shapes",
               "shapestruct"};
  app.footer("'shapestruct COMMAND --help' shows a command's options.");
  app.require_subcommand(0, 1);
  bool version = false;
  app.add_flag("--version", version, "Print the version and exit");
  std::map<const CLI::App*, command_fn> runners;
  for (const auto& [name, info] : registry()) {
    CLI::App* sub = app.add_subcommand(name, info.summary);
    runners[sub] = info.setup(*sub);
  }

  const std::vector<std::string> all(argv + 1, argv + argc);
  if (all.empty()) {
    std::cout << app.help();
    return 2;
  }
  if (all[0] == "help") {
    std::cout << app.help();
    return 0;
  }
  if (all[0][0] != '-' && registry().count(all[0]) == 0) {
    std::cerr << "shapestruct: unknown command '" << all[0] << "'\nRun 'shapestruct --help' for the commands.\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);  // --help, -h
    const auto parsed = app.get_subcommands();
    const std::string who = parsed.empty() ? "shapestruct" : "shapestruct " + parsed.front()->get_name();
    std::cerr << who << ": " << e.what() << "\nRun '" << who << " --help' for more information.\n";
    return 2;
  }
  if (version) {
    std::cout << SHAPESTRUCT_VERSION_STRING << "\n";
    return 0;
  }
  const auto parsed = app.get_subcommands();
  if (parsed.empty()) {
    std::cout << app.help();
    return 2;
  }
  const std::string name = parsed.front()->get_name();
  if (run_share().distributed() && !process_session::runs_across_processes(name)) {
    std::cerr << "shapestruct: '" << name << "' runs in one process; of the commands only 'analyze' runs across "
              << "MPI ranks (run '" << name << "' without mpirun)\n";
    return 2;
  }
  try {
    return runners.at(parsed.front())();
  } catch (const usage_error& e) {
    std::cerr << "shapestruct " << name << ": " << e.what() << "\nRun 'shapestruct " << name
              << " --help' for more information.\n";
    return 2;
  } catch (const shapestruct::io_error& e) {
    std::cerr << "shapestruct " << name << ": " << e.what() << "\n";
    return 1;
  } catch (const shapestruct::invalid_input& e) {
    std::cerr << "shapestruct " << name << ": invalid input (" << shapestruct::to_string(e.reason())
              << "): " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "shapestruct " << name << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  shapestruct::cli::restart_with_huge_pages(argv);
  shapestruct::cli::process_session session(argc, argv);
  return session.finish(run_tool(argc, argv));
}
