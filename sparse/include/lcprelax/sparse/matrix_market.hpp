#pragma once
// Matrix Market (https://math.nist.gov/MatrixMarket/formats.html) read and write.
// Reading: "matrix coordinate real|integer|pattern general|symmetric|skew-symmetric" and
// "matrix array real|integer general"; symmetric files are expanded to both triangles.
// Malformed input throws lcprelax::InputError naming the file and the 1-based line.
// Limits (core/text_input.hpp, docs/formats.md): lines of at most 1 MiB, no NUL bytes, a
// leading UTF-8 BOM skipped, echoed tokens cut to 64 characters; rows and columns at most
// 2^31 − 1 and, so that a 30-byte file cannot make a reader allocate gigabytes for an empty
// matrix, at most max(2^20, bytes of the input): checked against the file size right after
// the size line when it is known, and against the bytes read before the matrix is built
// otherwise (a pipe); the declared entry count must fit in the input's bytes (each entry
// takes at least 2 bytes) and is checked before anything is reserved for it; all size
// products use checked arithmetic.
#include <lcprelax/core/text_input.hpp>
#include <lcprelax/sparse/types.hpp>

#include <cstdint>
#include <iosfwd>
#include <string>

namespace lcprelax::sparse {

SparseMatrix read_matrix_market(const std::string& path);
/// Dense vector from an "array" file with one column (or a coordinate file with one column).
Vector read_matrix_market_vector(const std::string& path);
/// As above from a stream; `source_name` prefixes messages, `input_bytes` is the input's size
/// when known (text::kUnknownSize otherwise).
SparseMatrix parse_matrix_market(std::istream& in, const std::string& source_name,
                                 std::uint64_t input_bytes = text::kUnknownSize);
Vector parse_matrix_market_vector(std::istream& in, const std::string& source_name,
                                  std::uint64_t input_bytes = text::kUnknownSize);
/// Writes "coordinate real general" with 17 significant digits (round-trips exactly).
void write_matrix_market(const std::string& path, const SparseMatrix& A);
/// Writes "array real general" with one column.
void write_matrix_market(const std::string& path, const Vector& v);

}  // namespace lcprelax::sparse
