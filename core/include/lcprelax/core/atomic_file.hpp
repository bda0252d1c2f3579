#pragma once
// Crash-safe replacement of a file's contents (learning checkpoints, the simulator's
// frames and fc2d exports, the fc2d writer).
//
// write_file_atomically(path, bytes): writes `bytes` to "<path>.tmp" in the same directory,
// fsync()s it, rename()s it over `path` (atomic on POSIX file systems) and fsync()s the
// directory, so that after a crash or SIGKILL at any instant `path` holds either its
// previous complete contents or the new complete contents, never a mixture or a prefix.
// A leftover "<path>.tmp" from a killed writer is simply overwritten by the next write.
// check_writable(path) creates and removes "<path>.tmp" to find an unwritable location
// before any work is done. Both throw InputError naming the path and the system's reason.
#include <string>

namespace lcprelax {

void write_file_atomically(const std::string& path, const std::string& bytes);
void check_writable(const std::string& path);
/// The whole file; throws InputError naming the path if it cannot be read.
std::string read_whole_file(const std::string& path);

}  // namespace lcprelax
