#pragma once
// Shared by the tests that drive the real `weft` executable (WEFT_EXECUTABLE, set by CMake).

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace weft::app::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

// Runs `weft ARGS` through the shell and collects its output and exit code; `env` (e.g.
// "PATH=/dir") is put before the command.
inline CommandResult run_weft(const std::string& args, const std::string& env = "") {
  const std::string command =
      (env.empty() ? "" : env + " ") + std::string(WEFT_EXECUTABLE) + " " + args + " 2>&1";
  CommandResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer{};
  std::size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace weft::app::test
