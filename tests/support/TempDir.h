#pragma once
// A temporary folder removed at the end of a test.
#include <filesystem>
#include <random>
#include <string>

namespace scanpick::test {

class TempDir {
public:
  TempDir() {
    std::random_device rd;
    m_path = std::filesystem::temp_directory_path() /
             ("scanpick-test-" + std::to_string(rd()) + "-" + std::to_string(rd()));
    std::filesystem::create_directories(m_path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(m_path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return m_path; }
  std::filesystem::path operator/(const std::string& name) const { return m_path / name; }

private:
  std::filesystem::path m_path;
};

/// Path of a file in ../shared/data, or empty when the folder is absent.
inline std::filesystem::path sharedData(const std::string& relative) {
  const std::filesystem::path p = std::filesystem::path(SCANPICK_SHARED_DATA_DIR) / relative;
  return std::filesystem::exists(p) ? p : std::filesystem::path{};
}

/// Number of files in a folder.
inline std::size_t fileCount(const std::filesystem::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir))
    ++n;
  return n;
}

} // namespace scanpick::test
