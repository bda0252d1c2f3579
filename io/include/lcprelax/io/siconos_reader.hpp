#pragma once
// Readers for the Siconos numerics `.dat` problem files: linear complementarity
// problems (LCP) and 2-D frictional contact problems (fc2d), as written by Siconos'
// linearComplementarity_printInFile / frictionContact_printInFile and read by its
// linearComplementarity_newFromFile / frictionContact_newFromFile.
//
// File layouts (whitespace-separated tokens unless a line structure is stated):
//   LCP:  n, MATRIX (n×n), q (n values).                      0 ≤ z ⊥ w = M z + q ≥ 0
//   fc2d: dim (must be 2), nc, MATRIX (2nc×2nc), q (2nc values), μ (nc values ≥ 0);
//         per contact the normal component comes first: (r_N, r_T), u = W r + q.
//   MATRIX (a Siconos NumericsMatrix) = storage, size0 (rows), size1 (columns), then:
//   - storage 0, dense: "size0<TAB>size1" again (must agree), then size0·size1 values in
//     COLUMN-MAJOR order (Siconos prints them size1 per line, so each printed "row" of a
//     square matrix is a column: the line "0 2 -1" is M(:,0) = (0, 2, −1)).
//   - storage 1, sparse-block (SparseBlockStructuredMatrix): nbblocks (0 ⇒ zero matrix, no
//     more data); blocknumber0, blocknumber1; blocknumber0 CUMULATIVE row-block ends
//     (e.g. "2 4 6" = three 2-row blocks; the last must equal size0); blocknumber1 cumulative
//     column-block ends (last = size1); filled1 (= blocknumber0 + 1); filled2 (= nbblocks);
//     filled1 block-row pointers (CSR style, first 0, last nbblocks); filled2 block-column
//     indices; then for every block in storage order: its number (0, 1, ...) followed by its
//     rows·cols entries in column-major order within the block.
//   - storage 2, CSparse dump (NumericsSparseMatrix): the origin id on its own line, then
//     CSparse's cs_print text, line by line: a banner ("CSparse Version ..."), a header, and
//       compressed column (origin 2; 3 also accepted, the CSC id in newer Siconos):
//         "M-by-N, nzmax: X nnz: Y, 1-norm: Z", then for j = 0..N−1
//         "col j : locations a to b" followed by b−a+1 lines "i : value";
//       triplet (origin 1): "triplet: M-by-N, nzmax: X nnz: Y", then Y lines "i j : value".
//     Indices are 0-based; duplicate entries are summed (cs_compress semantics). Values were
//     printed by Siconos with %g, so such files carry only 6 significant digits.
// Conventions of this reader:
// - Dense storage drops exact zeros; sparse storages keep their stored entries.
// - Reading stops after the last declared value: trailing content (the test collection has
//   comment lines after q and, in old fc2d files, an extra "isComplete" flag) is ignored
//   and never parsed. Nothing is allocated from a declared size before its data is read.
// - Stricter than Siconos: block numbers and CSparse column numbers/locations must match
//   their position, block indices must be in range and unique, sizes must agree.
// - Malformed input throws lcprelax::InputError "PATH:LINE: message" (non-numeric tokens,
//   NaN/Inf or overflowing values, negative or zero sizes, truncated files, unknown storage
//   type, dimension mismatches, out-of-range indices, dim ≠ 2, negative μ).
// - Limits (core/text_input.hpp): lines of at most 1 MiB, no NUL bytes, a leading UTF-8 BOM
//   skipped, echoed tokens cut to 64 characters; n (LCP) and 2nc (fc2d) at most 2^31 − 1;
//   when the file size is known, a header whose sizes need more values (q, μ, a dense
//   matrix's n² entries) than the file's bytes can hold is rejected right after the header,
//   naming the size; counts use checked arithmetic.
#include <lcprelax/core/text_input.hpp>
#include <lcprelax/sparse/types.hpp>

#include <cstdint>
#include <iosfwd>
#include <string>

namespace lcprelax::io {

/// LCP data: find z with 0 ≤ z ⊥ w = M z + q ≥ 0.
struct LcpData {
  SparseMatrix M;  ///< n×n, compressed
  Vector q;        ///< n
};

/// 2-D frictional contact data: u = W r + q; contact i owns rows (2i: normal, 2i+1: tangent).
struct Fc2dData {
  Index contacts = 0;  ///< nc
  SparseMatrix W;      ///< 2nc×2nc Delassus operator, compressed
  Vector q;            ///< 2nc
  Vector mu;           ///< nc friction coefficients (≥ 0)
};

LcpData read_siconos_lcp(const std::string& path);
Fc2dData read_siconos_fc2d(const std::string& path);

/// Parse from a stream; source_name is used in error messages. `input_bytes`, when known,
/// is the size of the input: a header declaring more values than that many bytes can hold
/// is rejected before the values are read (read_siconos_* pass the size of a regular file).
LcpData parse_siconos_lcp(std::istream& in, const std::string& source_name,
                          std::uint64_t input_bytes = text::kUnknownSize);
Fc2dData parse_siconos_fc2d(std::istream& in, const std::string& source_name,
                            std::uint64_t input_bytes = text::kUnknownSize);

}  // namespace lcprelax::io
