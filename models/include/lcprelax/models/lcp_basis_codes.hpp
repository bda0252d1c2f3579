#pragma once
// A Stewart–Trinkle Lemke basis as one value per contact row, so that it can be kept per
// contact between steps (the Simulator's warm start) or between learning evaluations (the
// hard scene loss) and matched to the contacts of a later island.
//
// Layout: the LCP's unknowns are z = [λn (nc); β⁺ (nf); β⁻ (nf); γ (nf)] (lcp_model.hpp),
// and z_basic says which of them are basic. The codes are a vector [nc; nf]:
//   code(c)      = 1 if λn of contact c is basic, else 0;
//   code(nc + f) = b⁺ + 2 b⁻ + 4 bγ for friction row f (bits of β⁺, β⁻, γ being basic).
// A code that is not such a value (a relaxed centre, NaN) decodes to some basis: a warm
// basis only ever costs pivots, never a wrong answer (the attempts check the residual).
#include <lcprelax/sparse/types.hpp>

#include <vector>

namespace lcprelax {

/// Friction-row code bits.
enum LcpFrictionBasisBit : int { kBasisPlus = 1, kBasisMinus = 2, kBasisSlide = 4 };

/// z_basic (size nc + 3nf) → codes (size nc + nf). Throws std::invalid_argument on a size
/// mismatch.
void encode_lcp_basis(const std::vector<bool>& z_basic, Index nc, Index nf, Vector& code);

/// codes (size nc + nf) → z_basic (size nc + 3nf). Throws std::invalid_argument on a size
/// mismatch.
void decode_lcp_basis(const Vector& code, Index nc, Index nf, std::vector<bool>& z_basic);

/// The bits of one friction-row code, rounded; 0 (nothing basic) for a value that is not
/// finite or outside [0, 7].
int friction_basis_bits(double code);

}  // namespace lcprelax
