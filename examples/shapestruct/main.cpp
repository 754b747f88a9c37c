// SPDX-License-Identifier: MIT
// shapestruct: the command-line tool. Subcommands live in cmd_<name>.cpp and register themselves.
#include <exception>
#include <iostream>

#include "command.hpp"
#include "process_group.hpp"
#include "shapestruct/config.hpp"
#include "shapestruct/core/errors.hpp"

namespace {

int run_tool(int argc, char** argv) {
  using namespace shapestruct::cli;
  const std::vector<std::string> all(argv + 1, argv + argc);
  auto print_help = [] {
    std::cout << "shapestruct " << SHAPESTRUCT_VERSION_STRING
              << ": structure in collections of 3D shapes\n\nusage: shapestruct COMMAND [ARGS...]\n\ncommands:\n";
    for (const auto& [name, info] : registry()) std::cout << "  " << name << "  " << info.summary << "\n";
    std::cout << "\n'shapestruct COMMAND --help' shows a command's options.\n";
  };
  if (all.empty() || all[0] == "--help" || all[0] == "-h" || all[0] == "help") {
    print_help();
    return all.empty() ? 2 : 0;
  }
  if (all[0] == "--version") {
    std::cout << SHAPESTRUCT_VERSION_STRING << "\n";
    return 0;
  }
  const auto it = registry().find(all[0]);
  if (it == registry().end()) {
    std::cerr << "shapestruct: unknown command '" << all[0] << "'\n";
    print_help();
    return 2;
  }
  if (run_share().distributed() && !process_session::runs_across_processes(all[0])) {
    std::cerr << "shapestruct: '" << all[0] << "' runs in one process; of the commands only 'analyze' runs across "
              << "MPI ranks (run '" << all[0] << "' without mpirun)\n";
    return 2;
  }
  const std::vector<std::string> args(all.begin() + 1, all.end());
  for (const auto& a : args)
    if (a == "--help" || a == "-h") {
      std::cout << it->second.usage << "\n";
      return 0;
    }
  try {
    return it->second.run(args);
  } catch (const usage_error& e) {
    std::cerr << "shapestruct " << all[0] << ": " << e.what() << "\n\n" << it->second.usage << "\n";
    return 2;
  } catch (const shapestruct::io_error& e) {
    std::cerr << "shapestruct " << all[0] << ": " << e.what() << "\n";
    return 1;
  } catch (const shapestruct::invalid_input& e) {
    std::cerr << "shapestruct " << all[0] << ": invalid input (" << shapestruct::to_string(e.reason())
              << "): " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "shapestruct " << all[0] << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  shapestruct::cli::process_session session(argc, argv);
  return session.finish(run_tool(argc, argv));
}
