#pragma once
// Internal to the Siconos .dat readers (not a public header): a whitespace tokenizer that
// keeps line numbers and can switch to whole lines (the CSparse dump is line-oriented), and
// the reader of one Siconos NumericsMatrix (storage 0 dense, 1 sparse-block, 2 CSparse dump;
// layouts documented in lcprelax/io/siconos_reader.hpp). Errors are lcprelax::InputError
// "SOURCE:LINE: message". Lines are read through text::LineInput (core/text_input.hpp): at
// most 1 MiB per line, no NUL bytes, a leading UTF-8 BOM skipped; echoed tokens are cut to
// 64 characters. When the input's size in bytes is known, a declared count of values is
// checked against it (require_values) before those values are read.
#include <lcprelax/core/text_input.hpp>
#include <lcprelax/sparse/types.hpp>

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

namespace lcprelax::io::detail {

class SiconosTokenizer {
 public:
  /// `input_bytes`: size of the whole input, text::kUnknownSize when not known.
  SiconosTokenizer(std::istream& in, std::string source, std::uint64_t input_bytes = text::kUnknownSize)
      : lines_(in, std::move(source)), input_bytes_(input_bytes) {}

  /// Fails unless `count` more values (of WHAT) can fit in the input ("the file has only N
  /// bytes"); `count` is computed by the caller with checked arithmetic (text::checked_*).
  void require_values(std::uint64_t count, const std::string& what) const;

  /// Next whitespace-separated token (crossing line ends); throws "unexpected end of file
  /// while reading WHAT" at end of input.
  std::string token(const std::string& what);
  /// A decimal integer token in [lo, hi]; the message names WHAT.
  long long integer(const std::string& what, long long lo, long long hi);
  /// A size token: an integer in [1, hi].
  long long size(const std::string& what, long long hi);
  /// A finite floating-point token (NaN, ±Inf, overflow and trailing garbage rejected).
  double real(const std::string& what);

  /// The unread rest of the current line; the line then counts as consumed.
  std::string rest_of_line();
  /// The whole next line (the current one must be consumed first); throws at end of input.
  std::string line(const std::string& what);

  /// Parses text (a field of a line read with line()) as an integer in [lo, hi] or a finite
  /// double; errors are reported at the current line.
  long long parse_integer(const std::string& text, const std::string& what, long long lo,
                          long long hi) const;
  double parse_real(const std::string& text, const std::string& what) const;

  /// Line of the last token or line returned (1-based; the last line at end of input).
  long current_line() const { return lines_.line(); }
  [[noreturn]] void fail(const std::string& message) const { lines_.fail(message); }

 private:
  bool fetch_line();

  text::LineInput lines_;
  std::uint64_t input_bytes_;
  std::string text_;
  std::size_t pos_ = 0;
};

/// Splits a line on whitespace.
std::vector<std::string> split_fields(const std::string& line);

/// The entries of a matrix as read; build() makes the compressed SparseMatrix (duplicates
/// summed, as cs_compress does). Building is left to the caller so that nothing of the size
/// of a declared dimension is allocated before the file has proved it holds that much data.
struct MatrixEntries {
  Index rows = 0;
  Index cols = 0;
  std::vector<Triplet> entries;
  SparseMatrix build() const;
};

/// Reads "storage size0 size1 <data>" and checks size0 == rows, size1 == cols. Exact zeros of
/// dense storage are dropped; sparse storages keep their stored entries.
MatrixEntries read_numerics_matrix(SiconosTokenizer& tok, Index rows, Index cols);

}  // namespace lcprelax::io::detail
