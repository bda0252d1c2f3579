// Siconos NumericsMatrix reading (see siconos_matrix_reader.hpp and the layouts documented in
// lcprelax/io/siconos_reader.hpp). Nothing is allocated from a declared size before the data
// it describes has been read, so a truncated or lying file fails fast without large memory.
#include "siconos_matrix_reader.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <lcprelax/core/errors.hpp>
#include <sstream>

namespace lcprelax::io::detail {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

std::string trim_trailing_comma(std::string s) {
  if (!s.empty() && s.back() == ',') s.pop_back();
  return s;
}

}  // namespace

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
  return fields;
}

void SiconosTokenizer::require_values(std::uint64_t count, const std::string& what) const {
  if (!text::values_fit(count, input_bytes_))
    fail(what + " needs " + std::to_string(count) + " values, more than the " + std::to_string(input_bytes_) +
         " bytes of the file can hold (a size in the header is wrong or the file is truncated)");
}

bool SiconosTokenizer::fetch_line() {
  if (!lines_.next(text_)) return false;
  pos_ = 0;
  return true;
}

std::string SiconosTokenizer::token(const std::string& what) {
  for (;;) {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    if (pos_ < text_.size()) break;
    if (!fetch_line()) fail("unexpected end of file while reading " + what);
  }
  const std::size_t start = pos_;
  while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
  return text_.substr(start, pos_ - start);
}

long long SiconosTokenizer::parse_integer(const std::string& text, const std::string& what, long long lo,
                                          long long hi) const {
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size())
    fail("expected an integer for " + what + ", found " + text::quote(text));
  if (errno == ERANGE || v < lo || v > hi) {
    if (lo >= 0 && (v < 0 || text[0] == '-')) fail("negative value " + text::truncate(text) + " for " + what);
    fail(what + " " + text::truncate(text) + " out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v;
}

double SiconosTokenizer::parse_real(const std::string& text, const std::string& what) const {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size())
    fail("expected a number for " + what + ", found " + text::quote(text));
  if (!std::isfinite(v)) fail("non-finite value " + text::quote(text) + " for " + what);
  if (errno == ERANGE && std::fabs(v) > 1.0) fail("value " + text::quote(text) + " for " + what + " overflows a double");
  return v;
}

long long SiconosTokenizer::integer(const std::string& what, long long lo, long long hi) {
  return parse_integer(token(what), what, lo, hi);
}

long long SiconosTokenizer::size(const std::string& what, long long hi) {
  const std::string t = token(what);
  const long long v = parse_integer(t, what, 0, hi);
  if (v == 0) fail(what + " must be positive, got 0");
  return v;
}

double SiconosTokenizer::real(const std::string& what) { return parse_real(token(what), what); }

std::string SiconosTokenizer::rest_of_line() {
  std::string rest = text_.substr(pos_ < text_.size() ? pos_ : text_.size());
  pos_ = text_.size();
  return rest;
}

std::string SiconosTokenizer::line(const std::string& what) {
  if (!fetch_line()) fail("unexpected end of file while reading " + what);
  pos_ = text_.size();
  return text_;
}

namespace {

constexpr long long kMaxIndex = 0x7fffffff;

MatrixEntries build(Index rows, Index cols, std::vector<Triplet>& entries) {
  return MatrixEntries{rows, cols, std::move(entries)};
}

// Reads a size and checks it against the expected one ("dimension mismatch" otherwise).
void expect_size(SiconosTokenizer& tok, const std::string& what, const std::string& noun, Index expected) {
  const long long v = tok.integer(what, 0, kMaxIndex);
  if (v != expected)
    tok.fail("dimension mismatch: " + what.substr(0, what.find(' ')) + " declares " + std::to_string(v) + " " +
             noun + ", expected " + std::to_string(expected));
}

// Storage 0: "size0<TAB>size1" repeated, then size0*size1 values in column-major order.
MatrixEntries read_dense(SiconosTokenizer& tok, Index rows, Index cols) {
  expect_size(tok, "dense row count", "rows", rows);
  expect_size(tok, "dense column count", "columns", cols);
  std::uint64_t count = 0;  // rows, cols < 2^31: no overflow, checked all the same
  if (!text::checked_mul(static_cast<std::uint64_t>(rows), static_cast<std::uint64_t>(cols), count))
    tok.fail("dense matrix size overflows");
  tok.require_values(count, "the dense " + std::to_string(rows) + "x" + std::to_string(cols) + " matrix");
  std::vector<Triplet> entries;
  for (Index j = 0; j < cols; ++j)
    for (Index i = 0; i < rows; ++i) {
      const double v = tok.real("dense entry (" + std::to_string(i) + ", " + std::to_string(j) + ")");
      if (v != 0.0) entries.emplace_back(i, j, v);
    }
  return build(rows, cols, entries);
}

/// Reads `count` cumulative block sizes; strictly increasing, the last one equal to `total`.
std::vector<long long> read_block_sizes(SiconosTokenizer& tok, long long count, Index total,
                                        const std::string& what) {
  std::vector<long long> sizes;
  for (long long k = 0; k < count; ++k) {
    const long long prev = k == 0 ? 0 : sizes.back();
    const long long v = tok.integer(what + "[" + std::to_string(k) + "]", 0, total);
    if (v <= prev)
      tok.fail(what + " must be strictly increasing cumulative sizes, got " + std::to_string(v) + " after " +
               std::to_string(prev));
    sizes.push_back(v);
  }
  if (sizes.back() != total)
    tok.fail("dimension mismatch: " + what + " ends at " + std::to_string(sizes.back()) +
             ", matrix dimension is " + std::to_string(total));
  return sizes;
}

// Storage 1 (SparseBlockStructuredMatrix): nbblocks; if > 0: blocknumber0, blocknumber1,
// cumulative blocksize0[], blocksize1[], filled1 (= blocknumber0+1), filled2 (= nbblocks),
// index1_data[] (block-row pointers), index2_data[] (block columns), then per block in
// storage order its number followed by its entries in column-major order.
MatrixEntries read_sparse_block(SiconosTokenizer& tok, Index rows, Index cols) {
  const long long nblocks = tok.integer("number of blocks", 0, kMaxIndex);
  if (nblocks == 0) return MatrixEntries{rows, cols, {}};
  const long long bn0 = tok.size("number of block rows", rows);
  const long long bn1 = tok.size("number of block columns", cols);
  const std::vector<long long> bs0 = read_block_sizes(tok, bn0, rows, "row block sizes");
  const std::vector<long long> bs1 = read_block_sizes(tok, bn1, cols, "column block sizes");
  const long long filled1 = tok.integer("filled1", 0, kMaxIndex);
  if (filled1 != bn0 + 1)
    tok.fail("filled1 is " + std::to_string(filled1) +
             ", expected number of block rows + 1 = " + std::to_string(bn0 + 1));
  const long long filled2 = tok.integer("filled2", 0, kMaxIndex);
  if (filled2 != nblocks)
    tok.fail("filled2 is " + std::to_string(filled2) + ", expected the number of blocks " +
             std::to_string(nblocks));
  std::vector<long long> row_ptr;
  for (long long k = 0; k < filled1; ++k) {
    const long long v = tok.integer("block row pointer " + std::to_string(k), 0, kMaxIndex);
    if (v > nblocks)
      tok.fail("block row pointer " + std::to_string(v) + " out of range [0, " + std::to_string(nblocks) +
               "]");
    if ((k == 0 && v != 0) || (k > 0 && v < row_ptr.back()))
      tok.fail("block row pointers must start at 0 and not decrease, got " + std::to_string(v));
    row_ptr.push_back(v);
  }
  if (row_ptr.back() != nblocks)
    tok.fail("last block row pointer is " + std::to_string(row_ptr.back()) + ", expected " +
             std::to_string(nblocks));
  std::vector<long long> block_col;
  for (long long k = 0; k < filled2; ++k) {
    const std::string t = tok.token("block column index " + std::to_string(k));
    const long long v = tok.parse_integer(t, "block column index", -kMaxIndex, kMaxIndex);
    if (v < 0 || v >= bn1)
      tok.fail("block column index " + text::truncate(t) + " out of range [0, " + std::to_string(bn1) + ")");
    block_col.push_back(v);
  }
  std::vector<Triplet> entries;
  std::vector<long long> seen(static_cast<std::size_t>(bn1), -1);  // bn1 <= cols: columns are declared data
  for (long long br = 0; br < bn0; ++br) {
    const long long r0 = br == 0 ? 0 : bs0[br - 1];
    const long long nr = bs0[br] - r0;
    for (long long b = row_ptr[br]; b < row_ptr[br + 1]; ++b) {
      const long long bc = block_col[b];
      if (seen[bc] == br)
        tok.fail("block (" + std::to_string(br) + ", " + std::to_string(bc) + ") stored twice");
      seen[bc] = br;
      const long long c0 = bc == 0 ? 0 : bs1[bc - 1];
      const long long nc = bs1[bc] - c0;
      const long long number = tok.integer("block number", 0, kMaxIndex);
      if (number != b)
        tok.fail("block number " + std::to_string(number) + " found where block " + std::to_string(b) +
                 " was expected");
      for (long long jj = 0; jj < nc; ++jj)
        for (long long ii = 0; ii < nr; ++ii) {
          const double v = tok.real("entry (" + std::to_string(ii) + ", " + std::to_string(jj) +
                                    ") of block " + std::to_string(b));
          entries.emplace_back(static_cast<Index>(r0 + ii), static_cast<Index>(c0 + jj), v);
        }
    }
  }
  return build(rows, cols, entries);
}

// Storage 2: NumericsSparseMatrix origin id, then CSparse's cs_print text: a banner line,
// a header "M-by-N, nzmax: X nnz: Y, 1-norm: Z" (compressed column) or "triplet: M-by-N,
// nzmax: X nnz: Y", then "col j : locations a to b" + "i : x" lines, or "i j : x" lines.
MatrixEntries read_csparse(SiconosTokenizer& tok, Index rows, Index cols) {
  const long long origin = tok.integer("sparse origin id", 0, kMaxIndex);
  if (!split_fields(tok.rest_of_line()).empty()) tok.fail("unexpected text after the sparse origin id");
  const std::string banner = tok.line("CSparse banner line");
  if (banner.find("CSparse") == std::string::npos)
    tok.fail("expected the CSparse banner line, found " + text::quote(banner));
  std::vector<std::string> h = split_fields(tok.line("CSparse header line"));
  const bool triplet = !h.empty() && h[0] == "triplet:";
  if (triplet) h.erase(h.begin());
  if (h.size() < 5 || h[1] != "nzmax:" || h[3] != "nnz:")
    tok.fail("malformed CSparse header (expected 'M-by-N, nzmax: X nnz: Y')");
  const std::string dims = trim_trailing_comma(h[0]);
  const std::size_t by = dims.find("-by-");
  if (by == std::string::npos) tok.fail("malformed CSparse dimensions " + text::quote(h[0]));
  const long long m = tok.parse_integer(dims.substr(0, by), "CSparse row count", 0, kMaxIndex);
  const long long n = tok.parse_integer(dims.substr(by + 4), "CSparse column count", 0, kMaxIndex);
  if (m != rows || n != cols)
    tok.fail("dimension mismatch: CSparse matrix is " + text::truncate(dims) + ", expected " + std::to_string(rows) + "-by-" +
             std::to_string(cols));
  const long long nzmax = tok.parse_integer(h[2], "nzmax", 0, kMaxIndex);
  const long long nnz = tok.parse_integer(trim_trailing_comma(h[4]), "nnz", 0, nzmax);
  if (triplet && origin != 1)
    tok.fail("triplet CSparse dump with sparse origin id " + std::to_string(origin) + " (expected 1)");
  if (!triplet && origin != 2 && origin != 3)
    tok.fail("compressed CSparse dump with sparse origin id " + std::to_string(origin) +
             " (expected 2 or 3, compressed column)");
  std::vector<Triplet> entries;
  if (triplet) {
    for (long long p = 0; p < nnz; ++p) {
      const std::vector<std::string> f = split_fields(tok.line("triplet entry " + std::to_string(p)));
      if (f.size() != 4 || f[2] != ":") tok.fail("malformed triplet entry (expected 'i j : value')");
      const auto i = tok.parse_integer(f[0], "row index", 0, m - 1);
      const auto j = tok.parse_integer(f[1], "column index", 0, n - 1);
      entries.emplace_back(static_cast<Index>(i), static_cast<Index>(j), tok.parse_real(f[3], "entry value"));
    }
    return build(rows, cols, entries);
  }
  long long next = 0;  // first location of the next column
  for (long long j = 0; j < n; ++j) {
    const std::vector<std::string> f = split_fields(tok.line("column " + std::to_string(j) + " header"));
    if (f.size() != 7 || f[0] != "col" || f[2] != ":" || f[3] != "locations" || f[5] != "to")
      tok.fail("malformed column header (expected 'col j : locations a to b')");
    if (tok.parse_integer(f[1], "column number", 0, kMaxIndex) != j)
      tok.fail("column " + text::truncate(f[1]) + " found where column " + std::to_string(j) + " was expected");
    const long long a = tok.parse_integer(f[4], "first location", 0, kMaxIndex);
    const long long b = tok.parse_integer(f[6], "last location", -1, kMaxIndex);
    if (a != next || b < a - 1 || b >= nnz)
      tok.fail("column " + std::to_string(j) + " locations " + text::truncate(f[4]) + " to " + text::truncate(f[6]) +
               " inconsistent (expected to start at " + std::to_string(next) + " and stay below nnz " +
               std::to_string(nnz) + ")");
    for (long long p = a; p <= b; ++p) {
      const std::vector<std::string> e = split_fields(tok.line("entry " + std::to_string(p)));
      if (e.size() != 3 || e[1] != ":") tok.fail("malformed column entry (expected 'i : value')");
      const auto i = tok.parse_integer(e[0], "row index", 0, m - 1);
      entries.emplace_back(static_cast<Index>(i), static_cast<Index>(j), tok.parse_real(e[2], "entry value"));
    }
    next = b + 1;
  }
  if (next != nnz)
    tok.fail("columns hold " + std::to_string(next) + " entries, header declares nnz " + std::to_string(nnz));
  return build(rows, cols, entries);
}

}  // namespace

SparseMatrix MatrixEntries::build() const {
  SparseMatrix m(rows, cols);
  m.setFromTriplets(entries.begin(), entries.end());
  m.makeCompressed();
  return m;
}

MatrixEntries read_numerics_matrix(SiconosTokenizer& tok, Index rows, Index cols) {
  const std::string t = tok.token("matrix storage type");
  const long long storage = tok.parse_integer(t, "matrix storage type", -kMaxIndex, kMaxIndex);
  if (storage < 0 || storage > 2)
    tok.fail("unknown matrix storage type " + text::truncate(t) + " (expected 0 dense, 1 sparse-block or 2 CSparse)");
  expect_size(tok, "matrix row count", "rows", rows);
  expect_size(tok, "matrix column count", "columns", cols);
  switch (storage) {
    case 0:
      return read_dense(tok, rows, cols);
    case 1:
      return read_sparse_block(tok, rows, cols);
    default:
      return read_csparse(tok, rows, cols);
  }
}

}  // namespace lcprelax::io::detail
