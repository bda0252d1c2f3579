#pragma once
// The one sparse matrix currency of lcprelax and the dense types that go with it.
//
// SparseMatrix is compressed-column (CSC) with 32-bit indices, the layout CHOLMOD and KLU
// read directly, so factorizations view its arrays without copying. Code that hands a
// SparseMatrix to SuiteSparse must call makeCompressed() first (or receive it compressed).
#include <Eigen/Dense>
#include <Eigen/SparseCore>

namespace lcprelax {

using Index = int;
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, Index>;
using Triplet = Eigen::Triplet<double, Index>;
using Vector = Eigen::VectorXd;
using DenseMatrix = Eigen::MatrixXd;

}  // namespace lcprelax
