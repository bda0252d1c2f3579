// Stewart–Trinkle basis ↔ per-contact codes (lcp_basis_codes.hpp).
#include <lcprelax/models/lcp_basis_codes.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

namespace lcprelax {
namespace {

void check_sizes(const char* what, Index got, Index nc, Index nf, Index expected) {
  if (nc < 0 || nf < 0 || got != expected)
    throw std::invalid_argument(std::string(what) + ": size " + std::to_string(got) + " for nc = " +
                                std::to_string(nc) + ", nf = " + std::to_string(nf) + " (expected " +
                                std::to_string(expected) + ")");
}

}  // namespace

int friction_basis_bits(double code) {
  if (!(code >= 0.0 && code < 7.5)) return 0;  // NaN too
  return static_cast<int>(std::lround(code));
}

void encode_lcp_basis(const std::vector<bool>& z_basic, Index nc, Index nf, Vector& code) {
  check_sizes("encode_lcp_basis", static_cast<Index>(z_basic.size()), nc, nf, nc + 3 * nf);
  code.setZero(nc + nf);
  const auto bit = [&](Index i) { return z_basic[static_cast<std::size_t>(i)] ? 1 : 0; };
  for (Index c = 0; c < nc; ++c) code(c) = bit(c);
  for (Index f = 0; f < nf; ++f)
    code(nc + f) = kBasisPlus * bit(nc + f) + kBasisMinus * bit(nc + nf + f) + kBasisSlide * bit(nc + 2 * nf + f);
}

void decode_lcp_basis(const Vector& code, Index nc, Index nf, std::vector<bool>& z_basic) {
  check_sizes("decode_lcp_basis", static_cast<Index>(code.size()), nc, nf, nc + nf);
  z_basic.assign(static_cast<std::size_t>(nc + 3 * nf), false);
  for (Index c = 0; c < nc; ++c) z_basic[static_cast<std::size_t>(c)] = code(c) > 0.5;
  for (Index f = 0; f < nf; ++f) {
    const int bits = friction_basis_bits(code(nc + f));
    z_basic[static_cast<std::size_t>(nc + f)] = (bits & kBasisPlus) != 0;
    z_basic[static_cast<std::size_t>(nc + nf + f)] = (bits & kBasisMinus) != 0;
    z_basic[static_cast<std::size_t>(nc + 2 * nf + f)] = (bits & kBasisSlide) != 0;
  }
}

}  // namespace lcprelax
