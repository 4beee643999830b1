// Process plumbing for the CLI: the only place that spawns commands.
#include "cli.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace ap::cli {

int& exit_status() {
  static int status = 0;
  return status;
}

std::string source_dir() { return AP_SOURCE_DIR; }
std::string build_dir(const std::string& preset) { return source_dir() + "/build/" + preset; }

static int decode_status(int raw) {
  if (raw == -1) return 127;
  if (WIFEXITED(raw)) return WEXITSTATUS(raw);
  if (WIFSIGNALED(raw)) return 128 + WTERMSIG(raw);
  return 1;
}

int run(const std::string& command_line) {
  std::fflush(stdout);
  std::fflush(stderr);
  return decode_status(std::system(command_line.c_str()));
}

std::string run_capture(const std::string& command_line, int* status) {
  std::fflush(stdout);
  std::string out;
  FILE* pipe = popen(command_line.c_str(), "r");
  if (pipe == nullptr) {
    if (status != nullptr) *status = 127;
    return out;
  }
  std::array<char, 4096> buf{};
  size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  const int raw = pclose(pipe);
  if (status != nullptr) *status = decode_status(raw);
  return out;
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') q += "'\\''";
    else q += c;
  }
  return q + "'";
}

bool ensure_built(const std::string& preset, const std::vector<std::string>& targets, bool quiet) {
  const std::string src = quote(source_dir());
  const std::string sink = quiet ? " >/dev/null" : " >&2";
  if (!std::filesystem::exists(build_dir(preset) + "/CMakeCache.txt")) {
    std::fprintf(stderr, "axisproof: configuring build/%s\n", preset.c_str());
    if (run("cd " + src + " && cmake --preset " + preset + sink) != 0) return false;
  }
  std::string cmd = "cd " + src + " && cmake --build --preset " + preset;
  if (!targets.empty()) {
    cmd += " --target";
    for (const auto& t : targets) cmd += " " + t;
  }
  // Build output is shown only when it fails in quiet mode, so gate logs stay readable.
  if (quiet) {
    int status = 0;
    const std::string out = run_capture(cmd + " 2>&1", &status);
    if (status != 0) std::fputs(out.c_str(), stderr);
    return status == 0;
  }
  return run(cmd + sink) == 0;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace ap::cli
