#pragma once
// Internal to the QPS reader: line splitting, section names, number parsing and
// "FILE:LINE: message" errors (lcprelax::InputError). Not a public header.
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
  QpsLexer(std::istream& in, std::string source) : in_(in), source_(std::move(source)) {}

  /// Reads the next line that is neither blank nor a '*' comment and splits it on
  /// whitespace into `fields`; false at end of input.
  bool next(std::vector<std::string>& fields);
  /// True when the current line starts in column 1 (a section header in free MPS).
  bool is_header() const { return header_; }
  /// 1-based number of the current line (the last line read at end of input).
  long line() const { return line_; }

  [[noreturn]] void fail(const std::string& message) const { fail_at(line_, message); }
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

 private:
  std::istream& in_;
  std::string source_;
  std::string text_;
  long line_ = 0;
  bool header_ = false;
};

}  // namespace lcprelax::io
