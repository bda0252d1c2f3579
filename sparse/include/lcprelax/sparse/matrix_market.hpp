#pragma once
// Matrix Market (https://math.nist.gov/MatrixMarket/formats.html) read and write.
// Reading: "matrix coordinate real|integer|pattern general|symmetric|skew-symmetric" and
// "matrix array real|integer general"; symmetric files are expanded to both triangles.
// Malformed input throws lcprelax::InputError naming the file and the 1-based line.
#include <lcprelax/sparse/types.hpp>

#include <string>

namespace lcprelax::sparse {

SparseMatrix read_matrix_market(const std::string& path);
/// Dense vector from an "array" file with one column (or a coordinate file with one column).
Vector read_matrix_market_vector(const std::string& path);
/// Writes "coordinate real general" with 17 significant digits (round-trips exactly).
void write_matrix_market(const std::string& path, const SparseMatrix& A);
/// Writes "array real general" with one column.
void write_matrix_market(const std::string& path, const Vector& v);

}  // namespace lcprelax::sparse
