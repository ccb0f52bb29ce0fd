#include "support/cli_run.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>

#include "support/paths.h"

namespace raylane::testing {

CliRun run_cli(const std::string& args, const std::string& dir, int timeout_seconds) {
  std::string cmd = "cd '" + dir + "' && timeout -k 5 " + std::to_string(timeout_seconds) + " '" +
                    cli_path() + "' " + args + " 2>&1";
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

}  // namespace raylane::testing
