// Runs the built `raylane` program as a user would, for the CLI tests.
#pragma once

#include <string>

namespace raylane::testing {

struct CliRun {
  int status = -1;  // the exit status; -1 if the program did not exit normally
  std::string out;  // stdout and stderr together
};

// Runs `raylane <args>` (shell words) in `dir`.
CliRun run_cli(const std::string& args, const std::string& dir);

}  // namespace raylane::testing
