#pragma once
// A time step's whole contact problem as 2-D frictional contact data (io::Fc2dData), so that
// real many-contact problems feed the Lemke benchmarks (io/siconos_writer.hpp writes it).
//
// For the contacts of `contacts` (all islands together, in their order): rows (2i: normal,
// 2i+1: tangent t = (−n_y, n_x)) of J, W = J M⁻¹ Jᵀ, and q = J v* + (max(φ,0)/Δt on normal
// rows), the same data as the lcp model of contact_step.hpp, with a tangent row for every
// contact (fc2d has one even where μ = 0). u = W r + q is the contact-point velocity after
// the step for impulses r (N·s).
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/world/world.hpp>

#include <vector>

namespace lcprelax {

io::Fc2dData export_fc2d(const World& world, const std::vector<Contact>& contacts, double dt);

}  // namespace lcprelax
