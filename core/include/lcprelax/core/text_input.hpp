#pragma once
// Shared limits and helpers of lcprelax's text-file readers (QPS, Siconos .dat, Matrix
// Market, trajectory and block CSV, scene JSON). Header only, so that every layer's reader
// can use it. Limits (docs/formats.md, "Limits of the readers"):
// - a line holds at most kMaxLineBytes = 1 MiB (1,048,576 bytes, without its '\n'); a
//   longer line is an InputError "SOURCE:LINE: line longer than 1048576 bytes ...", raised
//   after reading at most that many bytes, so /dev/zero or a binary file fails fast and
//   without large memory;
// - a NUL byte in a line is an InputError naming its column (text formats never hold one);
// - a leading UTF-8 byte-order mark (EF BB BF) of the first line is skipped;
// - tokens echoed into error messages are cut to kMaxEchoChars = 64 characters followed by
//   "...", non-printable bytes written as \xNN (quote()); a whole message is cut to
//   kMaxMessageChars (clip_message()), so no input makes an error message large;
// - sizes are multiplied and added with checked arithmetic (checked_mul/checked_add), and
//   size claims are compared with the input's byte count when it is known
//   (regular_file_size()).
#include <lcprelax/core/errors.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <istream>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>

namespace lcprelax::text {

inline constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;
inline constexpr std::size_t kMaxEchoChars = 64;
inline constexpr std::size_t kMaxMessageChars = 1024;
/// Byte count of an input whose size is not known (a pipe, a device, an unseekable stream).
inline constexpr std::uint64_t kUnknownSize = std::numeric_limits<std::uint64_t>::max();

/// TOKEN cut for an error message: at most kMaxEchoChars characters, then "..."; bytes
/// outside printable ASCII (except bytes ≥ 0x80, i.e. UTF-8) written as \xNN.
inline std::string truncate(std::string_view token) {
  std::string out;
  const std::size_t n = token.size() < kMaxEchoChars ? token.size() : kMaxEchoChars;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if ((c >= 0x20 && c < 0x7f) || c >= 0x80) {
      out += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (token.size() > n) out += "...";
  return out;
}

/// 'TOKEN' for an error message, cut as by truncate().
inline std::string quote(std::string_view token) { return "'" + truncate(token) + "'"; }

/// The message itself when at most kMaxMessageChars long, else its first part and "...".
inline std::string clip_message(std::string message) {
  if (message.size() > kMaxMessageChars) {
    message.resize(kMaxMessageChars);
    message += "...";
  }
  return message;
}

/// Removes a leading UTF-8 byte-order mark; true when there was one.
inline bool strip_bom(std::string& text) {
  if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) {
    text.erase(0, 3);
    return true;
  }
  return false;
}

/// a·b and a+b for sizes ≥ 0; false (result untouched) when the result exceeds `limit`.
inline bool checked_mul(std::uint64_t a, std::uint64_t b, std::uint64_t& out,
                        std::uint64_t limit = std::numeric_limits<std::uint64_t>::max()) {
  std::uint64_t r = 0;
  if (__builtin_mul_overflow(a, b, &r) || r > limit) return false;
  out = r;
  return true;
}
inline bool checked_add(std::uint64_t a, std::uint64_t b, std::uint64_t& out,
                        std::uint64_t limit = std::numeric_limits<std::uint64_t>::max()) {
  std::uint64_t r = 0;
  if (__builtin_add_overflow(a, b, &r) || r > limit) return false;
  out = r;
  return true;
}

/// Size in bytes of the regular file `path`; kUnknownSize for anything else (a device such
/// as /dev/zero, a FIFO, a missing file).
inline std::uint64_t regular_file_size(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || ec) return kUnknownSize;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  return ec ? kUnknownSize : static_cast<std::uint64_t>(size);
}

/// Whether `count` whitespace-separated values fit in `bytes` (each takes at least one
/// character and one separator, the last one no separator).
inline bool values_fit(std::uint64_t count, std::uint64_t bytes) {
  if (bytes == kUnknownSize || count == 0) return true;
  std::uint64_t need = 0;
  return checked_mul(count, 2, need) && need - 1 <= bytes;
}

/// Line-by-line reading with the limits above. Errors are InputError
/// "SOURCE:LINE: message" (clipped to kMaxMessageChars).
class LineInput {
 public:
  LineInput(std::istream& in, std::string source, std::size_t max_line = kMaxLineBytes)
      : in_(in), source_(std::move(source)), max_line_(max_line) {}

  /// The next line without its '\n' (a '\r' is kept: readers treat it as they see fit);
  /// false at end of input. Throws for a line longer than the limit or holding a NUL byte.
  bool next(std::string& line) {
    line.clear();
    std::streambuf* sb = in_.rdbuf();
    if (sb == nullptr || !in_.good()) return false;
    bool any = false;
    for (;;) {
      const int c = sb->sbumpc();
      if (c == std::char_traits<char>::eof()) {
        in_.setstate(std::ios::eofbit);
        if (!any) return false;
        break;
      }
      any = true;
      ++bytes_;
      if (c == '\n') break;
      if (line.size() >= max_line_) {
        ++line_;
        fail("line longer than " + std::to_string(max_line_) +
             " bytes (the limit of a line; not a text file?)");
      }
      line.push_back(static_cast<char>(c));
    }
    ++line_;
    if (line_ == 1) strip_bom(line);
    const std::size_t nul = line.find('\0');
    if (nul != std::string::npos)
      fail("NUL byte in column " + std::to_string(nul + 1) + " (binary data in a text file?)");
    return true;
  }

  /// 1-based number of the last line read (0 before the first).
  long line() const { return line_; }
  /// Bytes consumed so far (line ends included).
  std::uint64_t bytes_read() const { return bytes_; }
  const std::string& source() const { return source_; }

  [[noreturn]] void fail(const std::string& message) const { fail_at(line_, message); }
  [[noreturn]] void fail_at(long line, const std::string& message) const {
    throw InputError(clip_message(source_ + ":" + std::to_string(line > 0 ? line : 1) + ": " + message));
  }

 private:
  std::istream& in_;
  std::string source_;
  std::size_t max_line_;
  long line_ = 0;
  std::uint64_t bytes_ = 0;
};

}  // namespace lcprelax::text
