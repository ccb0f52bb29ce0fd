#include "support/cli_run.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>

#include "support/paths.h"

namespace raylane::testing {

namespace {

CliRun run_shell(const std::string& cmd) {
  CliRun r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0)
    r.out.append(buf.data(), n);
  int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::string command_line(const std::string& args, const std::string& dir, int timeout_seconds) {
  return "cd '" + dir + "' && timeout -k 5 " + std::to_string(timeout_seconds) + " '" + cli_path() +
         "' " + args + " 2>&1";
}

}  // namespace

CliRun run_cli(const std::string& args, const std::string& dir, int timeout_seconds) {
  return run_shell(command_line(args, dir, timeout_seconds));
}

CliRun run_cli_within(const std::string& args, const std::string& dir, uint64_t address_space_kib) {
  return run_shell("ulimit -v " + std::to_string(address_space_kib) + " && " +
                   command_line(args, dir, 120));
}

}  // namespace raylane::testing
