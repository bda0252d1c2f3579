#pragma once
// Writer of Siconos numerics 2-D frictional contact (fc2d) `.dat` files, the layout that
// siconos_reader.hpp reads (and Siconos' frictionContact_newFromFile): dim = 2, nc, W in
// storage 2 (CSparse compressed-column dump, origin 2), q and μ. Values are written with
// 17 significant digits, so a file read back gives W, q and μ bit for bit (Siconos itself
// prints W with %g, 6 digits). Per contact the normal row comes first: u = W r + q.
#include <lcprelax/sparse/types.hpp>

#include <iosfwd>
#include <string>

namespace lcprelax::io {

/// Writes (W 2nc×2nc, q 2nc, μ nc); throws InputError on inconsistent sizes, non-finite
/// values or an unwritable path.
void write_siconos_fc2d(const std::string& path, const SparseMatrix& W, const Vector& q, const Vector& mu);
void write_siconos_fc2d(std::ostream& out, const SparseMatrix& W, const Vector& q, const Vector& mu);

}  // namespace lcprelax::io
