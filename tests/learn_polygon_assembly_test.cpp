// Per-sample assembly of a polygon on the ground as a function of θ (polygon_assembly.hpp,
// polygon_lcp.hpp). Expected behaviour:
// - the narrow phase's active set is identified by vertex index (the two lowest vertices
//   of a tilted quadrilateral just above/below the ground);
// - every hand-written derivative of Jn, Jt, φ, μ, M⁻¹, v* with respect to every parameter
//   (μ, mass, inertia, each vertex coordinate, ground height and angle) matches central
//   differences to 1e-7 (relative to the entry scale, step 1e-6), at a state with one
//   positive and one negative gap (away from the kink of max(φ, 0));
// - the dense Stewart–Trinkle LCP equals the library's stewart_trinkle_lcp on the same
//   ContactSystem, and its tangent (M, q, P, p) matches central differences.
#include <lcprelax/learn/polygon_assembly.hpp>
#include <lcprelax/learn/polygon_lcp.hpp>
#include <lcprelax/models/contact_step.hpp>

#include "learn_polygon_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace lcprelax::learn {
namespace {

using test::quad_model;

// A pre-state with the quad's bottom edge nearly on the tilted ground: vertex 0 slightly
// above (φ ≈ +2 mm), vertex 1 slightly below (φ ≈ −1 mm).
PolygonTransition sample_near_ground(const PolygonModel& m) {
  PolygonTransition s;
  const HalfPlane g = ground_half_plane(m.ground_height, m.ground_angle);
  const double theta = m.ground_angle + 0.004;
  s.q = Vec3(0.1, 0.0, theta);
  const Vec2 b0 = m.shape.vertices[1];
  const double c = std::cos(theta), sn = std::sin(theta);
  const Vec2 rb(c * b0.x() - sn * b0.y(), sn * b0.x() + c * b0.y());
  // Choose y so that vertex 1 has gap −1 mm.
  s.q.y() = (g.offset - 0.001 - g.normal.x() * (s.q.x() + rb.x())) / g.normal.y() - rb.y();
  s.v = Vec3(0.4, -0.7, 1.3);
  s.u = Vec3(2.0, -3.0, 0.15);
  return s;
}

PolygonDataset dataset() {
  PolygonDataset d;
  d.dt = 0.01;
  d.margin = 0.01;
  return d;
}

void expect_close(const DenseMatrix& a, const DenseMatrix& b, double tol, const std::string& what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  const double scale = std::max(1.0, b.cwiseAbs().maxCoeff());
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), tol * scale) << what << "\nanalytic\n" << a << "\nfd\n" << b;
}

TEST(LearnPolygonAssembly, ActiveSetIsTheTwoLowestVertices) {
  const PolygonModel m = quad_model();
  const PolygonTransition s = sample_near_ground(m);
  const std::vector<int> active = polygon_active_vertices(m, s, dataset());
  ASSERT_EQ(active.size(), 2u);
  EXPECT_EQ(active[0], 0);
  EXPECT_EQ(active[1], 1);
  PolygonAssembly a;
  assemble_polygon(m, active, s, dataset(), a);
  EXPECT_GT(a.value.phi(0), 0.0);
  EXPECT_NEAR(a.value.phi(1), -0.001, 1e-12);
}

TEST(LearnPolygonAssembly, DerivativesMatchCentralDifferences) {
  const PolygonModel m = quad_model();
  const PolygonTransition s = sample_near_ground(m);
  const PolygonDataset d = dataset();
  const std::vector<int> active = polygon_active_vertices(m, s, d);
  ParameterSet theta = make_polygon_parameters(m, PolygonLearnFlags{});
  PolygonAssembly a;
  assemble_polygon(m, active, s, d, a);
  PolygonLcp lcp, dlcp, lp, lm;
  polygon_lcp(a.value, d.dt, lcp);
  const double h = 1e-6;
  double worst = 0.0;
  for (Index k = 0; k < theta.size(); ++k) {
    PolygonAssembly plus, minus;
    ParameterSet tp = theta, tm = theta;
    tp.set_value(theta[k].name, theta[k].value + h);
    tm.set_value(theta[k].name, theta[k].value - h);
    assemble_polygon(polygon_model(tp), active, s, d, plus);
    assemble_polygon(polygon_model(tm), active, s, d, minus);
    const PolygonContactData& t = a.tangent[static_cast<std::size_t>(k)];
    auto fd = [&](const DenseMatrix& p, const DenseMatrix& q) -> DenseMatrix { return (p - q) / (2 * h); };
    const std::string name = theta[k].name;
    expect_close(t.Jn, fd(plus.value.Jn, minus.value.Jn), 1e-7, name + " Jn");
    expect_close(t.Jt, fd(plus.value.Jt, minus.value.Jt), 1e-7, name + " Jt");
    expect_close(t.phi, fd(plus.value.phi, minus.value.phi), 1e-7, name + " phi");
    expect_close(t.mu, fd(plus.value.mu, minus.value.mu), 1e-7, name + " mu");
    expect_close(t.minv, fd(plus.value.minv, minus.value.minv), 1e-7, name + " minv");
    expect_close(t.v_star, fd(plus.value.v_star, minus.value.v_star), 1e-7, name + " v_star");
    // The LCP's tangent along the same parameter.
    polygon_lcp_tangent(a.value, t, d.dt, dlcp);
    polygon_lcp(plus.value, d.dt, lp);
    polygon_lcp(minus.value, d.dt, lm);
    expect_close(dlcp.M, fd(lp.M, lm.M), 1e-7, name + " lcp M");
    expect_close(dlcp.q, fd(lp.q, lm.q), 1e-7, name + " lcp q");
    expect_close(dlcp.P, fd(lp.P, lm.P), 1e-7, name + " lcp P");
    expect_close(dlcp.p, fd(lp.p, lm.p), 1e-7, name + " lcp p");
    worst = std::max(worst, (dlcp.M - fd(lp.M, lm.M)).cwiseAbs().maxCoeff());
  }
  RecordProperty("worst_lcp_M_fd_error", std::to_string(worst));
}

TEST(LearnPolygonAssembly, DenseLcpEqualsTheLibrarys) {
  const PolygonModel m = quad_model();
  const PolygonTransition s = sample_near_ground(m);
  const PolygonDataset d = dataset();
  PolygonAssembly a;
  assemble_polygon(m, polygon_active_vertices(m, s, d), s, d, a);
  PolygonLcp lcp;
  polygon_lcp(a.value, d.dt, lcp);
  const ContactSystem sys = to_contact_system(a.value);
  const StewartTrinkleLcp ref = stewart_trinkle_lcp(sys, delassus(sys), d.dt);
  expect_close(lcp.M, DenseMatrix(ref.M), 1e-14, "M");
  expect_close(lcp.q, ref.q, 1e-14, "q");
}

}  // namespace
}  // namespace lcprelax::learn
