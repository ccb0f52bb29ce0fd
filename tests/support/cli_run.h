// Runs the built `raylane` program as a user would, for the CLI tests.
#pragma once

#include <string>

namespace raylane::testing {

struct CliRun {
  int status = -1;  // the exit status; -1 if the program did not exit normally
  std::string out;  // stdout and stderr together
};

// Runs `raylane <args>` (shell words) in `dir`. A run that takes longer than `timeout_seconds`
// is killed (coreutils timeout) and reports status 124: a hang fails its test, not the suite.
CliRun run_cli(const std::string& args, const std::string& dir, int timeout_seconds = 120);

// The same under `ulimit -v` (the address space, in KiB), as a machine with less memory.
CliRun run_cli_within(const std::string& args, const std::string& dir, uint64_t address_space_kib);

}  // namespace raylane::testing
