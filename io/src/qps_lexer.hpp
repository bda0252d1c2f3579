#pragma once
// Internal to the QPS reader: line splitting, section names, number parsing and
// "FILE:LINE: message" errors (lcprelax::InputError). Not a public header. Lines are read
// through text::LineInput (core/text_input.hpp): at most 1 MiB per line, no NUL bytes, a
// leading UTF-8 BOM skipped; tokens echoed in messages go through quote() (64 characters).
#include <lcprelax/core/text_input.hpp>

#include <istream>
#include <string>
#include <vector>

namespace lcprelax::io {

/// Sections of a QPS file; QSECTION maps to qmatrix (both triangles of P are listed).
enum class QpsSection { none, name, objsense, rows, columns, rhs, ranges, bounds, quadobj, qmatrix, endata };

/// The section a header keyword names, or QpsSection::none when it is not a section.
QpsSection section_from_name(const std::string& keyword);

class QpsLexer {
 public:
  QpsLexer(std::istream& in, std::string source) : lines_(in, std::move(source)) {}

  /// Reads the next line that is neither blank nor a '*' comment and splits it on
  /// whitespace into `fields`; false at end of input.
  bool next(std::vector<std::string>& fields);
  /// True when the current line starts in column 1 (a section header in free MPS).
  bool is_header() const { return header_; }
  /// 1-based number of the current line (the last line read at end of input).
  long line() const { return lines_.line(); }

  [[noreturn]] void fail(const std::string& message) const { fail_at(lines_.line(), message); }
  [[noreturn]] void fail_at(long line, const std::string& message) const;
  /// Fails unless lo ≤ fields.size() ≤ hi, naming `what`.
  void expect_fields(const std::vector<std::string>& fields, std::size_t lo, std::size_t hi,
                     const std::string& what) const;
  /// A decimal number (±inf allowed, NaN and trailing garbage rejected).
  double number(const std::string& token) const;
  /// number() that also rejects ±inf (matrix entries, RHS, RANGES).
  double finite_number(const std::string& token) const;
  /// Text of a value for messages (12 significant digits).
  static std::string format(double value);
  /// A token for messages: 'TOKEN', cut to 64 characters (text::quote).
  static std::string quote(const std::string& token) { return text::quote(token); }

 private:
  text::LineInput lines_;
  std::string text_;
  bool header_ = false;
};

}  // namespace lcprelax::io
