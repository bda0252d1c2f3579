// A step's contact problem as fc2d data (fc2d_export.hpp).
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/fc2d_export.hpp>

#include <algorithm>

namespace lcprelax {

io::Fc2dData export_fc2d(const World& world, const std::vector<Contact>& contacts, double dt) {
  // Every contact gets a tangent row: assemble with μ > 0 everywhere, keep the real μ.
  std::vector<Contact> all = contacts;
  for (Contact& c : all) c.mu = 1.0;
  Island island;
  for (const Contact& c : contacts) {
    island.bodies.push_back(c.body_a);
    if (c.body_b >= 0 && !world.bodies[c.body_b].is_static) island.bodies.push_back(c.body_b);
  }
  std::sort(island.bodies.begin(), island.bodies.end());
  island.bodies.erase(std::unique(island.bodies.begin(), island.bodies.end()), island.bodies.end());
  for (int i = 0; i < static_cast<int>(contacts.size()); ++i) island.contacts.push_back(i);
  const ContactSystem s = assemble_contact_system(world, all, island, dt);
  const Index nc = s.num_contacts();
  std::vector<Triplet> t;
  for (Index j = 0; j < s.Jn.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(s.Jn, j); it; ++it) t.emplace_back(2 * it.row(), j, it.value());
  for (Index j = 0; j < s.Jt.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(s.Jt, j); it; ++it) t.emplace_back(2 * it.row() + 1, j, it.value());
  SparseMatrix J(2 * nc, s.num_dofs());
  J.setFromTriplets(t.begin(), t.end());
  io::Fc2dData d;
  d.contacts = nc;
  d.W = (SparseMatrix(J * s.minv.asDiagonal()) * J.transpose()).pruned();
  d.W.makeCompressed();
  d.q = J * s.v_star;
  d.mu.resize(nc);
  for (Index i = 0; i < nc; ++i) {
    d.q(2 * i) += std::max(s.phi(i), 0.0) / dt;
    d.mu(i) = contacts[i].mu;
  }
  return d;
}

}  // namespace lcprelax
