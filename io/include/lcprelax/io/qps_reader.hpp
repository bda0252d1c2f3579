#pragma once
// Reader for QPS files (free-format MPS with QUADOBJ/QMATRIX quadratic sections), as used
// by the Maros–Meszaros test set. Conventions:
// - objective ½xᵀPx + qᵀx + r; the objective row's RHS entry is −r;
// - QUADOBJ lists the lower triangle of P (one entry per off-diagonal pair), QMATRIX the
//   full symmetric matrix (both entries of each pair; they must agree); P is returned as
//   its upper triangle (QpProblem convention);
// - rows: N (first N row is the objective, further N rows are dropped), E, L, G; RANGES
//   per the MPS rules (E row with R > 0: [rhs, rhs+|R|], R < 0: [rhs−|R|, rhs]; L row:
//   [rhs−|R|, rhs]; G row: [rhs, rhs+|R|]);
// - BOUNDS types LO, UP, FX, FR, MI, PL (FR/MI/PL with or without a value field); default
//   bounds [0, +∞); an UP bound < 0 on a variable whose lower bound is still the default 0
//   sets the lower bound to −∞ (the classic MPS rule); integer bound types are rejected;
// - every constraint row becomes a row of QpProblem::G with bounds [l, u] (A stays empty),
//   in file order, so QpResult::z holds one multiplier per constraint row, in file order.
// Malformed input throws lcprelax::InputError "FILE:LINE: message".
// Limits (core/text_input.hpp, docs/formats.md): lines of at most 1 MiB, no NUL bytes (an
// error naming the line and column), a leading UTF-8 BOM skipped, tokens echoed in messages
// cut to 64 characters; at most 2^31 − 1 columns, rows and entries; a file without any
// variable is an error ("no variables"). Memory grows with the lines read, never with a
// declared size.
#include <lcprelax/kkt/qp_problem.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace lcprelax::io {

struct QpsModel {
  std::string name;                         ///< NAME section value
  QpProblem problem;                        ///< data in lcprelax's convention
  std::vector<std::string> variable_names;  ///< column names, in order of first appearance
  std::vector<std::string> row_names;       ///< constraint row names, in file order
  std::string objective_name;               ///< the objective row's name
};

QpsModel read_qps(const std::string& path);
/// Parses from a stream; source_name is used in error messages.
QpsModel parse_qps(std::istream& in, const std::string& source_name);

}  // namespace lcprelax::io
