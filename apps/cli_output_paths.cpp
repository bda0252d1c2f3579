// Output paths of the command line checked before the work starts (cli_common.hpp): a
// training of hours or a simulation of minutes must not end in "cannot write OUT.png".
//
// A file path is writable when it can be opened for writing without truncation (created
// and removed again when it did not exist); a directory when it exists or can be created
// and grants write and search permission. Both throw InputError naming the option and the
// path, so main() exits with status 2 before anything is computed. The check cannot rule
// out a later failure (a full disk, a permission changed meanwhile): those still end in an
// error at the end, naming the path.
#include "cli_common.hpp"

#include <lcprelax/core/errors.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace lcprelax::cli {
namespace {

[[noreturn]] void cannot_write(const std::string& option, const std::string& path, const std::string& why) {
  throw InputError(option + ": cannot write '" + path + "': " + why);
}

}  // namespace

void require_writable_file(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  struct stat st {};
  const bool existed = ::stat(path.c_str(), &st) == 0;
  if (existed && S_ISDIR(st.st_mode)) cannot_write(option, path, "is a directory");
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) cannot_write(option, path, std::strerror(errno));
  ::close(fd);
  if (!existed) ::unlink(path.c_str());
}

void require_writable_directory(const std::string& option, const std::string& dir) {
  if (dir.empty()) return;
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status s = fs::status(dir, ec);
  if (fs::exists(s) && !fs::is_directory(s)) cannot_write(option, dir, "exists and is not a directory");
  if (!fs::exists(s)) {
    fs::create_directories(dir, ec);
    if (ec) cannot_write(option, dir, "cannot create the directory: " + ec.message());
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0) cannot_write(option, dir, std::strerror(errno));
}

}  // namespace lcprelax::cli
