#include "core/common/AtomicFile.h"

#include "core/common/Error.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace scanpick::core {
namespace fs = std::filesystem;

namespace {
fs::path temporaryPathFor(const fs::path& path) {
  static std::atomic<unsigned> counter{0};
  fs::path tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return tmp;
}
} // namespace

void writeFileAtomicWith(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  if (path.has_parent_path() && !fs::is_directory(path.parent_path()))
    throw Error("cannot write '" + path.string() + "': folder '" + path.parent_path().string() +
                "' does not exist");
  const fs::path tmp = temporaryPathFor(path);
  try {
    write(tmp);
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec)
      throw Error("cannot write '" + path.string() + "': " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

void writeFileAtomic(const fs::path& path, std::string_view contents) {
  writeFileAtomicWith(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw Error("cannot write '" + path.string() + "': " + std::strerror(errno));
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.close();
    if (out.fail())
      throw Error("cannot write '" + path.string() + "': write failed (disk full?)");
  });
}

void checkWritable(const fs::path& path) {
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(folder))
    throw Error("cannot write '" + path.string() + "': folder '" + folder.string() +
                "' does not exist");
  if (fs::is_directory(path))
    throw Error("cannot write '" + path.string() + "': it is a folder, give a file name");
  if (::access(folder.c_str(), W_OK) != 0)
    throw Error("cannot write '" + path.string() + "': folder '" + folder.string() +
                "' is not writable (" + std::strerror(errno) + ")");
}

std::string readFile(const fs::path& path, const ProgressFn& progress) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw Error("cannot read '" + path.string() +
                "': " + (fs::exists(path) ? std::string(std::strerror(errno)) : "no such file"));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size < 0 || !in) {
    std::ostringstream ss; // not seekable (a pipe, a device): read it whole
    in.clear();
    ss << in.rdbuf();
    return ss.str();
  }
  std::string bytes(static_cast<std::size_t>(size), '\0');
  constexpr std::streamoff kBlock = std::streamoff{1} << 20;
  for (std::streamoff done = 0; done < size;) {
    const std::streamoff n = std::min(kBlock, size - done);
    if (!in.read(bytes.data() + done, n))
      throw Error("cannot read '" + path.string() + "': it ended after " +
                  std::to_string(done + in.gcount()) + " of " + std::to_string(size) + " bytes");
    done += n;
    reportProgress(progress, static_cast<double>(done) / static_cast<double>(size));
  }
  return bytes;
}

} // namespace scanpick::core
