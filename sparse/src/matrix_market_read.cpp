// Matrix Market reader: banner, comments, size line and entries, strictly validated.
// Every malformed input throws lcprelax::InputError("path:line: message") with the
// 1-based line number; nothing is read past the declared entries but blank lines.
// Duplicate coordinate entries are summed; explicit zeros in coordinate files are kept
// (they are part of the pattern), zeros of array files are dropped.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/sparse/matrix_market.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <fstream>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

namespace lcprelax::sparse {
namespace {

enum class Field { real, integer, pattern };
enum class Symmetry { general, symmetric, skew };

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool is_blank(std::string_view line) { return split(line).empty(); }

// Reads a stream line by line (text::LineInput: 1 MiB lines, no NUL, BOM skipped), keeping
// the 1-based number of the last line read.
class LineReader {
 public:
  LineReader(std::istream& in, const std::string& source) : lines_(in, source) {}
  bool next(std::string& line) {
    if (!lines_.next(line)) return false;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }
  long line_no() const { return lines_.line(); }
  std::uint64_t bytes_read() const { return lines_.bytes_read(); }
  [[noreturn]] void fail(long line, const std::string& message) const { lines_.fail_at(line, message); }
  [[noreturn]] void fail(const std::string& message) const { fail(line_no(), message); }

 private:
  text::LineInput lines_;
};

std::ifstream open(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open file");
  return in;
}

// Largest dimension a matrix of an input of `bytes` bytes may declare (header comment).
std::uint64_t max_dimension(std::uint64_t bytes) {
  constexpr std::uint64_t floor = std::uint64_t{1} << 20;
  return bytes == text::kUnknownSize ? INT_MAX : std::min<std::uint64_t>(INT_MAX, std::max(floor, bytes));
}

long long parse_int(const LineReader& r, std::string_view tok, const char* what) {
  long long v = 0;
  const char* first = tok.data();
  const char* last = tok.data() + tok.size();
  if (first != last && *first == '+') ++first;
  auto [end, ec] = std::from_chars(first, last, v);
  if (ec != std::errc() || end != last) {
    r.fail("bad " + std::string(what) + " " + text::quote(tok));
  }
  return v;
}

double parse_value(const LineReader& r, std::string_view tok, Field field) {
  if (field == Field::integer) return static_cast<double>(parse_int(r, tok, "integer value"));
  const std::string s(tok);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size()) r.fail("bad real value " + text::quote(s));
  if (!std::isfinite(v)) r.fail("non-finite value " + text::quote(s));
  return v;
}

struct Parsed {
  Index rows = 0;
  Index cols = 0;
  long size_line = 0;
  std::vector<Triplet> entries;
};

struct Header {
  bool coordinate = true;
  Field field = Field::real;
  Symmetry symmetry = Symmetry::general;
};

Header parse_banner(LineReader& r) {
  std::string line;
  if (!r.next(line)) r.fail(1, "empty file, expected a %%MatrixMarket banner");
  const auto t = split(line);
  if (t.empty() || lower(t[0]) != "%%matrixmarket") {
    r.fail("bad banner, expected '%%MatrixMarket matrix <format> <field> <symmetry>'");
  }
  if (t.size() != 5) r.fail("bad banner, expected 5 words, found " + std::to_string(t.size()));
  if (lower(t[1]) != "matrix") r.fail("unsupported object " + text::quote(t[1]));
  Header h;
  const std::string format = lower(t[2]), field = lower(t[3]), symmetry = lower(t[4]);
  if (format == "coordinate") {
    h.coordinate = true;
  } else if (format == "array") {
    h.coordinate = false;
  } else {
    r.fail("unsupported format " + text::quote(t[2]));
  }
  if (field == "real" || field == "double") {
    h.field = Field::real;
  } else if (field == "integer") {
    h.field = Field::integer;
  } else if (field == "pattern" && h.coordinate) {
    h.field = Field::pattern;
  } else {
    r.fail("unsupported field " + text::quote(t[3]) + " for format " + text::quote(format));
  }
  if (symmetry == "general") {
    h.symmetry = Symmetry::general;
  } else if (symmetry == "symmetric") {
    h.symmetry = Symmetry::symmetric;
  } else if (symmetry == "skew-symmetric") {
    h.symmetry = Symmetry::skew;
  } else {
    r.fail("unsupported symmetry " + text::quote(t[4]));
  }
  return h;
}

// Number of stored entries an array file holds.
long long array_count(const Header& h, long long m, long long n) {
  if (h.symmetry == Symmetry::general) return m * n;
  if (h.symmetry == Symmetry::symmetric) return n * (n + 1) / 2;
  return n * (n - 1) / 2;
}

// Reads the next non-blank line into `line`; false at end of file.
bool next_nonblank(LineReader& r, std::string& line) {
  while (r.next(line)) {
    if (!is_blank(line)) return true;
  }
  return false;
}

Parsed parse(std::istream& in, const std::string& source, std::uint64_t input_bytes) {
  LineReader r(in, source);
  const Header h = parse_banner(r);
  std::string line;
  do {  // comments and blank lines before the size line
    if (!r.next(line)) r.fail(r.line_no() + 1, "missing size line");
  } while (is_blank(line) || line[line.find_first_not_of(" \t")] == '%');

  const auto t = split(line);
  const std::size_t want = h.coordinate ? 3 : 2;
  if (t.size() != want) {
    r.fail("bad size line, expected " + std::string(h.coordinate ? "'rows cols entries'"
                                                                 : "'rows cols'"));
  }
  const long long m = parse_int(r, t[0], "row count");
  const long long n = parse_int(r, t[1], "column count");
  if (m < 0 || n < 0 || m > INT_MAX || n > INT_MAX) r.fail("matrix size out of range");
  const std::uint64_t max_dim = max_dimension(input_bytes);
  if (static_cast<std::uint64_t>(std::max(m, n)) > max_dim)
    r.fail("matrix size " + std::to_string(m) + "x" + std::to_string(n) + " exceeds the limit " +
           std::to_string(max_dim) + " = max(2^20, file size in bytes)");
  if (h.symmetry != Symmetry::general && m != n) r.fail("symmetric matrix must be square");
  const long long count = h.coordinate ? parse_int(r, t[2], "entry count") : array_count(h, m, n);
  const long long capacity = h.symmetry == Symmetry::general ? m * n : n * (n + 1) / 2;
  if (count < 0 || count > capacity) r.fail("entry count out of range");
  if (count * (h.symmetry == Symmetry::general ? 1 : 2) > INT_MAX) r.fail("too many entries");
  if (!text::values_fit(static_cast<std::uint64_t>(count), input_bytes))
    r.fail("entry count " + std::to_string(count) + " is more than the " + std::to_string(input_bytes) +
           " bytes of the file can hold");

  Parsed p;
  p.rows = static_cast<Index>(m);
  p.cols = static_cast<Index>(n);
  p.size_line = r.line_no();
  // Reserve only what the input has proved it can hold (values_fit above) or a little.
  const long long provable = input_bytes == text::kUnknownSize ? 4096 : static_cast<long long>(input_bytes / 2);
  p.entries.reserve(static_cast<std::size_t>(std::min({count, provable, 1LL << 24})));
  long long i = 0, j = 0;  // array files: next position, column-major
  if (!h.coordinate) i = h.symmetry == Symmetry::skew ? 1 : 0;
  for (long long k = 0; k < count; ++k) {
    if (!next_nonblank(r, line)) {
      r.fail(r.line_no() + 1, "file ends after " + std::to_string(k) + " of " +
                                  std::to_string(count) + " entries");
    }
    const auto e = split(line);
    double v = 1.0;
    if (h.coordinate) {
      const std::size_t words = h.field == Field::pattern ? 2 : 3;
      if (e.size() != words) r.fail("bad entry, expected " + std::to_string(words) + " words");
      i = parse_int(r, e[0], "row index") - 1;
      j = parse_int(r, e[1], "column index") - 1;
      if (i < 0 || i >= m || j < 0 || j >= n) r.fail("index out of range");
      if (h.symmetry == Symmetry::symmetric && i < j) {
        r.fail("entry above the diagonal in a symmetric file");
      }
      if (h.symmetry == Symmetry::skew && i <= j) {
        r.fail("entry on or above the diagonal in a skew-symmetric file");
      }
      if (h.field != Field::pattern) v = parse_value(r, e[2], h.field);
    } else {
      if (e.size() != 1) r.fail("bad entry, expected one value");
      v = parse_value(r, e[0], h.field);
    }
    if (h.coordinate || v != 0.0) {
      p.entries.emplace_back(static_cast<Index>(i), static_cast<Index>(j), v);
      if (h.symmetry != Symmetry::general && i != j) {
        p.entries.emplace_back(static_cast<Index>(j), static_cast<Index>(i),
                               h.symmetry == Symmetry::skew ? -v : v);
      }
    }
    if (!h.coordinate && ++i == m) {  // advance column-major (lower triangle if symmetric)
      ++j;
      i = h.symmetry == Symmetry::general ? 0 : (h.symmetry == Symmetry::skew ? j + 1 : j);
    }
  }
  if (next_nonblank(r, line)) {
    r.fail("more entries than the " + std::to_string(count) + " declared");
  }
  // Sizes against the bytes actually read (an input of unknown size), before any allocation.
  const std::uint64_t read_limit = max_dimension(r.bytes_read());
  if (static_cast<std::uint64_t>(std::max(m, n)) > read_limit)
    r.fail(p.size_line, "matrix size " + std::to_string(m) + "x" + std::to_string(n) + " exceeds the limit " +
                            std::to_string(read_limit) + " = max(2^20, bytes read)");
  return p;
}

}  // namespace

SparseMatrix parse_matrix_market(std::istream& in, const std::string& source_name, std::uint64_t input_bytes) {
  Parsed p = parse(in, source_name, input_bytes);
  SparseMatrix A(p.rows, p.cols);
  A.setFromTriplets(p.entries.begin(), p.entries.end());
  A.makeCompressed();
  return A;
}

Vector parse_matrix_market_vector(std::istream& in, const std::string& source_name, std::uint64_t input_bytes) {
  Parsed p = parse(in, source_name, input_bytes);
  if (p.cols != 1) {
    throw InputError(source_name + ":" + std::to_string(p.size_line) +
                     ": expected one column, found " + std::to_string(p.cols));
  }
  Vector v = Vector::Zero(p.rows);
  for (const Triplet& t : p.entries) v[t.row()] += t.value();
  return v;
}

SparseMatrix read_matrix_market(const std::string& path) {
  std::ifstream in = open(path);
  return parse_matrix_market(in, path, text::regular_file_size(path));
}

Vector read_matrix_market_vector(const std::string& path) {
  std::ifstream in = open(path);
  return parse_matrix_market_vector(in, path, text::regular_file_size(path));
}

}  // namespace lcprelax::sparse
