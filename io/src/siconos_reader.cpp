// Siconos numerics .dat readers for LCP and 2-D frictional contact problems. The file layouts
// and conventions are documented in lcprelax/io/siconos_reader.hpp; the NumericsMatrix part is
// read by detail::read_numerics_matrix (siconos_matrix_reader.cpp).
#include <fstream>
#include <istream>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/core/errors.hpp>
#include <vector>

#include "siconos_matrix_reader.hpp"

namespace lcprelax::io {
namespace {

// Largest n such that an n×n matrix still has int indices (Index is 32-bit).
constexpr long long kMaxDim = 0x7fffffff;

// Values are collected as they are read (no allocation of the declared size up front).
Vector read_vector(detail::SiconosTokenizer& tok, Index n, const char* name) {
  std::vector<double> values;
  for (Index i = 0; i < n; ++i) values.push_back(tok.real(std::string(name) + "[" + std::to_string(i) + "]"));
  return Eigen::Map<const Vector>(values.data(), n);
}

std::ifstream open(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file");
  return in;
}

}  // namespace

LcpData parse_siconos_lcp(std::istream& in, const std::string& source_name, std::uint64_t input_bytes) {
  detail::SiconosTokenizer tok(in, source_name, input_bytes);
  const auto n = static_cast<Index>(tok.size("LCP size n", kMaxDim));
  tok.require_values(static_cast<std::uint64_t>(n), "LCP size n = " + std::to_string(n) + ": q");
  const detail::MatrixEntries M = detail::read_numerics_matrix(tok, n, n);
  LcpData data;
  // Siconos reads size1 values of q; size1 == n is checked by read_numerics_matrix.
  data.q = read_vector(tok, n, "q");
  data.M = M.build();  // only now: the file has shown it holds n values of q
  return data;
}

Fc2dData parse_siconos_fc2d(std::istream& in, const std::string& source_name, std::uint64_t input_bytes) {
  detail::SiconosTokenizer tok(in, source_name, input_bytes);
  const std::string dim_text = tok.token("problem dimension");
  const long long dim = tok.parse_integer(dim_text, "problem dimension", -kMaxDim, kMaxDim);
  if (dim != 2)
    tok.fail("contact dimension " + text::truncate(dim_text) +
             " not supported: only 2-D frictional contact (dim = 2) is read");
  const auto nc = static_cast<Index>(tok.size("number of contacts", kMaxDim / 2));
  const Index n = 2 * nc;  // nc <= kMaxDim / 2: no overflow
  tok.require_values(3 * static_cast<std::uint64_t>(nc), "number of contacts " + std::to_string(nc) + ": q and mu");
  const detail::MatrixEntries W = detail::read_numerics_matrix(tok, n, n);
  Fc2dData data;
  data.contacts = nc;
  data.q = read_vector(tok, n, "q");
  std::vector<double> mu;
  for (Index i = 0; i < nc; ++i) {
    const std::string what = "mu[" + std::to_string(i) + "]";
    const std::string text = tok.token(what);
    mu.push_back(tok.parse_real(text, what));
    if (mu.back() < 0.0) tok.fail("negative friction coefficient " + what + " = " + text::truncate(text));
  }
  data.mu = Eigen::Map<const Vector>(mu.data(), nc);
  data.W = W.build();
  return data;
}

LcpData read_siconos_lcp(const std::string& path) {
  std::ifstream in = open(path);
  return parse_siconos_lcp(in, path, text::regular_file_size(path));
}

Fc2dData read_siconos_fc2d(const std::string& path) {
  std::ifstream in = open(path);
  return parse_siconos_fc2d(in, path, text::regular_file_size(path));
}

}  // namespace lcprelax::io
