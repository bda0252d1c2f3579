// Crash-safe file replacement: temporary file, fsync, rename, fsync of the directory
// (atomic_file.hpp).
#include <lcprelax/core/atomic_file.hpp>

#include <lcprelax/core/errors.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace lcprelax {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, int error) {
  throw InputError("cannot " + what + " '" + path + "': " + std::strerror(error));
}

std::string temporary_of(const std::string& path) { return path + ".tmp"; }

// Opens (creating or truncating) the temporary file of `path` for writing.
int open_temporary(const std::string& path) {
  const std::string tmp = temporary_of(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(path, "write (temporary file '" + tmp + "')", errno);
  return fd;
}

void write_all(int fd, const std::string& bytes, const std::string& path) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      ::close(fd);
      fail(path, "write", e);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

// fsync of the directory holding `path`, so that the rename itself is durable. Some file
// systems refuse fsync on a directory (EINVAL): the rename is still atomic there.
void sync_directory(const std::string& path) {
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (dir.empty()) dir = ".";
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
    const int e = errno;
    ::close(fd);
    fail(dir.string(), "sync the directory", e);
  }
  ::close(fd);
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& bytes) {
  const int fd = open_temporary(path);
  write_all(fd, bytes, temporary_of(path));
  if (::fsync(fd) != 0) {
    const int e = errno;
    ::close(fd);
    fail(temporary_of(path), "sync", e);
  }
  if (::close(fd) != 0) fail(temporary_of(path), "close", errno);
  if (std::rename(temporary_of(path).c_str(), path.c_str()) != 0) fail(path, "rename the temporary file onto", errno);
  sync_directory(path);
}

void check_writable(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) throw InputError("cannot write '" + path + "': it is a directory");
  const int fd = open_temporary(path);
  ::close(fd);
  std::remove(temporary_of(path).c_str());
}

std::string read_whole_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) fail(path, "read", errno);
  if (S_ISDIR(st.st_mode)) throw InputError("cannot read '" + path + "': it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "read", errno);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError("cannot read '" + path + "': read error");
  return bytes;
}

}  // namespace lcprelax
