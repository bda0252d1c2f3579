#pragma once
// Internal (not installed): KLU's symbolic analysis of a matrix with column singletons,
// which peels the singletons first and runs klu_analyze on the rest only.
//
// A column with a single entry (row i) is a 1×1 diagonal block of the block upper
// triangular form when it is put first: nothing lies below it. Peeling every column
// singleton, each on its own row, leaves the square submatrix K of the other rows and
// columns, and
//     A(P, Q) = [ D  F ]     D diagonal (the singletons' entries), F their rows' other
//               [ 0  K ]     entries, K in KLU's own block triangular form (BTF + AMD/COLAMD),
// is a block triangular form of A with K's blocks and the singletons as its diagonal
// blocks: the same strongly connected components that KLU's BTF of the whole of A would
// find (Duff & Reid, "An implementation of Tarjan's algorithm for the block
// triangularization of a matrix", ACM TOMS 4, 1978: a 1×1 block is a node in no cycle).
// Only the order of independent blocks and AMD's tie-breaks inside K's blocks (its input
// comes in K's order) may differ, and with them the fill and the roundoff. The work of
// the analysis (maximum transversal, strongly connected components, AMD) is then that of
// K: on a Lemke basis most columns are slack columns e_i, and K is the much smaller block
// of the basic z columns.
//
// The result is an ordinary klu_symbolic (allocated as KLU allocates it, freed by
// klu_free_symbolic), so klu_factor, klu_refactor, klu_solve, klu_extract and klu_rcond use
// it unchanged.
#include <klu.h>

#include <vector>

namespace lcprelax::sparse::detail {

/// Scratch of analyze_singletons_first (kept between calls to avoid reallocation).
struct SingletonAnalysisWork {
  std::vector<int> reduced_row, kept_row, kept_col, Kp, Ki;
};

/// Symbolic analysis of the n×n CSC pattern (Ap, Ai) with its column singletons as the
/// leading 1×1 blocks and klu_analyze's analysis (with common's settings) of the remaining
/// square submatrix; `peeled` is the number of singletons put first. Returns nullptr, with
/// `peeled` = 0, when A has no column singleton, when two singletons share a row (A is
/// structurally singular), when a column's row indices are not increasing or lie outside
/// [0, n), when the rest is structurally singular, when common asks for no BTF or an
/// ordering other than AMD or COLAMD, or when KLU fails (out of memory): the caller then runs
/// klu_analyze on A, which reports each of these cases as it does for any matrix.
klu_symbolic* analyze_singletons_first(int n, const int* Ap, const int* Ai, klu_common* common,
                                       SingletonAnalysisWork& work, int& peeled);

}  // namespace lcprelax::sparse::detail
