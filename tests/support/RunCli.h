#pragma once
// Running the scanpick-cli executable from a test, as an integrator's script would.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace scanpick::test {

inline const std::filesystem::path kCli =
    std::filesystem::path(SCANPICK_BINARY_DIR) / "bin" / "scanpick-cli";

/// `path` in double quotes, for the shell. (Built with append: GCC 12 warns wrongly about
/// `"literal" + std::string` under -O3.)
inline std::string quoted(const std::filesystem::path& path) {
  std::string out(1, '"');
  out.append(path.string());
  out.push_back('"');
  return out;
}

/// Runs scanpick-cli with `args` (already quoted), its output written to `output` (discarded
/// when empty); returns the wait status of std::system (0 on success).
inline int runCli(const std::vector<std::string>& args, const std::filesystem::path& output = {}) {
  std::string command = quoted(kCli);
  for (const auto& a : args) {
    command.push_back(' ');
    command.append(a);
  }
  command.append(" > ");
  command.append(output.empty() ? std::string("/dev/null") : quoted(output));
  command.append(" 2>&1");
  return std::system(command.c_str());
}

/// The exit code of a runCli status, or -1 when the process did not exit (a signal).
inline int exitCode(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace scanpick::test
