// The stiff-and-extreme report: every case of the validation suites
// run once more, each with its outcome, the largest solver residual and the run time, as
// a CSV (suite,case,model,status,residual,seconds,detail) and a Markdown table on stdout.
//
//   run_stiff_report [--csv bench/results/stiff_report.csv]
//
// Cases (the tests under tests/ assert the physics, tests/models_stiff_cases_test.cpp the
// hardest rows; this report only measures), each with both contact models:
//   mass ratio    a plank 1e3×, 1e6× and 1e9× heavier than the two boxes it rests on, 200
//                 steps (drift); convex also at 1e6× and 1e9× with the lifted formulation
//                 and ρ = 1/ratio (SimulatorSettings::convex_formulation)
//   friction      μ = 0: a box sliding 2 m/s for 500 steps (speed kept?); μ = 1000 and
//                 μ = 1e6: a box sliding 0.4 m/s (stopped, |v| < 1e-7, for 100 steps?)
//   time step     a resting box for 0.5 s (≤ 2,000 steps) at Δt = 1e-6 … 1e-1 (drift)
//   stack         10 and 50 unit boxes stacked, 20 steps (drift)
//   thin          three 1 m × 1e-6 m boxes (1 kg) stacked, 100 steps (drift)
//   redundant     a resting box with every contact listed twice (rank-deficient J)
//   pyramid       210 boxes (20 rows), 20 steps (lcp) or 2 (convex), drift
//   murty         Murty's LCP (n = 8, 12, 16): Lemke's pivots (exponential in n)
//   infeasible    a primal-infeasible and a dual-infeasible (unbounded) QP; an LCP with
//                 no solution (Lemke's ray)
//   invalid       NaN in a QP, an LCP and a scene: the exception's message
// Residual: StepStats::max_residual (contact solves) or the solver's own; "status" is
// "ok" when the physics outcome stated in the case holds and every island solved to
// tolerance, "ok, N inaccurate islands" when some ended solved_inaccurate (usable, outside
// the tolerance), else what went wrong, named: "failed islands: N" (a fallback's answer was
// used, detail gives the first message), "physics check failed", "non-finite state" or
// "exception: …" (the simulator threw). No case may crash the runner.
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/core/errors.hpp>

#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;

struct Row {
  std::string suite, name, model, status;
  double residual = 0.0, seconds = 0.0;
  std::string detail;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

RigidBody box(double w, double h, double mass, const Vec3& pose) {
  RigidBody b;
  b.shape.vertices = {Vec2(-w / 2, -h / 2), Vec2(w / 2, -h / 2), Vec2(w / 2, h / 2), Vec2(-w / 2, h / 2)};
  b.mass = mass;
  b.inertia = mass * (w * w + h * h) / 12.0;
  b.pose = pose;
  return b;
}

Scene ground_scene(std::vector<RigidBody> bodies, double mu, double dt, ContactModel model) {
  Scene s;
  s.world.bodies = std::move(bodies);
  s.world.half_planes.push_back(HalfPlane{Vec2(0.0, 1.0), 0.0, 0});
  s.world.friction.default_mu = mu;
  s.settings.dt = dt;
  s.settings.model = model;
  s.settings.margin = 1e-2;
  return s;
}

struct RunStats {
  int failed = 0, inaccurate = 0;
  double residual = 0.0, drift = 0.0, seconds = 0.0;
  bool finite = true;
  std::string first_failure, error;
};

RunStats run(Simulator& sim, int steps, const std::vector<Vec3>& applied = {}) {
  std::vector<Vec3> start;
  for (const RigidBody& b : sim.world().bodies) start.push_back(b.pose);
  RunStats r;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    for (int k = 0; k < steps && r.finite; ++k) {
      const StepStats st = sim.step(applied);
      r.failed += st.failed_islands;
      r.inaccurate += st.inaccurate_islands;
      r.residual = std::max(r.residual, st.max_residual);
      if (r.first_failure.empty()) r.first_failure = st.first_failure;
      if (r.first_failure.empty()) r.first_failure = st.first_inaccurate;
      for (std::size_t i = 0; i < start.size(); ++i) {
        const RigidBody& b = sim.world().bodies[i];
        r.finite = r.finite && b.pose.allFinite() && b.velocity.allFinite();
        r.drift = std::max(r.drift, (b.pose.head<2>() - start[i].head<2>()).norm());
      }
    }
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  r.seconds = seconds_since(t0);
  return r;
}

std::string outcome(bool physics_ok, const RunStats& r) {
  if (!r.error.empty()) return "exception: " + r.error;
  if (!r.finite) return "non-finite state";
  if (r.failed > 0) return "failed islands: " + std::to_string(r.failed);
  if (!physics_ok) return "physics check failed";
  return r.inaccurate > 0 ? "ok, " + std::to_string(r.inaccurate) + " inaccurate islands" : "ok";
}

// The detail column: `what`, then the first failure or inaccuracy message if any.
std::string detail_of(const std::string& what, const RunStats& r) {
  return r.first_failure.empty() ? what : what + "; first: " + r.first_failure;
}

void dynamics_cases(std::vector<Row>& rows) {
  char detail[160];
  for (ContactModel model : {ContactModel::lcp, ContactModel::convex}) {
    const std::string m = to_string(model);
    for (double ratio : {1e3, 1e6, 1e9}) {
      Simulator sim = make_simulator(ground_scene({box(0.2, 0.2, 1.0, Vec3(-0.8, 0.1, 0.0)), box(0.2, 0.2, 1.0, Vec3(0.8, 0.1, 0.0)),
                                  box(2.0, 0.2, ratio, Vec3(0.0, 0.3, 0.0))},
                                 0.5, 1e-2, model));
      const RunStats r = run(sim, 200);
      std::snprintf(detail, sizeof detail, "drift %.2g m over 200 steps", r.drift);
      rows.push_back({"mass ratio", "plank " + std::to_string(static_cast<long long>(ratio)) + "x on boxes", m,
                      outcome(r.drift < 1e-6, r), r.residual, r.seconds, detail_of(detail, r)});
    }
    if (model == ContactModel::convex) {
      // The advice of SimulatorSettings::convex_formulation: lifted QPs, ρ·ratio ≤ 1.
      for (double ratio : {1e6, 1e9}) {
        SimulatorSettings settings;
        settings.convex_formulation = ConvexFormulation::lifted;
        settings.convex_rho = 1.0 / ratio;
        Simulator sim = make_simulator(ground_scene({box(0.2, 0.2, 1.0, Vec3(-0.8, 0.1, 0.0)), box(0.2, 0.2, 1.0, Vec3(0.8, 0.1, 0.0)),
                                    box(2.0, 0.2, ratio, Vec3(0.0, 0.3, 0.0))},
                                   0.5, 1e-2, model),
                                   settings);
        const RunStats r = run(sim, 200);
        std::snprintf(detail, sizeof detail, "lifted, rho %.0e; drift %.2g m over 200 steps", settings.convex_rho, r.drift);
        rows.push_back({"mass ratio", "plank " + std::to_string(static_cast<long long>(ratio)) + "x on boxes (lifted, rho = 1/ratio)",
                        m, outcome(r.drift < 1e-6, r), r.residual, r.seconds, detail_of(detail, r)});
      }
    }
    {
      Scene s = ground_scene({box(1.0, 0.2, 1.0, Vec3(0.0, 0.1, 0.0))}, 0.0, 1e-2, model);
      s.world.bodies[0].velocity = Vec3(2.0, 0.0, 0.0);
      Simulator sim = make_simulator(s);
      const RunStats r = run(sim, 500);
      const double v = sim.world().bodies[0].velocity.x();
      std::snprintf(detail, sizeof detail, "speed after 500 steps %.12g m/s (2 expected)", v);
      rows.push_back({"friction", "mu = 0 slides", m, outcome(std::abs(v - 2.0) < 1e-9, r), r.residual, r.seconds,
                      detail_of(detail, r)});
    }
    for (double mu : {1e3, 1e6}) {
      Scene s = ground_scene({box(1.0, 0.2, 1.0, Vec3(0.0, 0.1, 0.0))}, mu, 1e-2, model);
      s.world.bodies[0].velocity = Vec3(0.4, 0.0, 0.0);
      SimulatorSettings settings;
      settings.convex_rho = 1e-9;
      settings.qp.eps_abs = 1e-11;
      Simulator sim = make_simulator(s, settings);
      const RunStats r = run(sim, 100);
      const double v = sim.world().bodies[0].velocity.norm();
      std::snprintf(detail, sizeof detail, "speed after 100 steps %.2g m/s", v);
      rows.push_back({"friction", mu == 1e3 ? "mu = 1000 sticks" : "mu = 1e6 sticks", m, outcome(v < 1e-7, r), r.residual,
                      r.seconds, detail_of(detail, r)});
    }
    for (double dt : {1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1}) {
      Simulator sim = make_simulator(ground_scene({box(1.0, 1.0, 1.0, Vec3(0.0, 0.5, 0.0))}, 0.5, dt, model));
      const int steps = std::min(2000, static_cast<int>(std::lround(0.5 / dt)));
      const RunStats r = run(sim, steps);
      char name[64];
      std::snprintf(name, sizeof name, "resting box, dt = %g s", dt);
      std::snprintf(detail, sizeof detail, "drift %.2g m over %d steps", r.drift, steps);
      rows.push_back({"time step", name, m, outcome(r.drift < 1e-6, r), r.residual, r.seconds, detail_of(detail, r)});
    }
    for (int height : {10, 50}) {
      std::vector<RigidBody> bodies;
      for (int i = 0; i < height; ++i) bodies.push_back(box(1.0, 1.0, 1.0, Vec3(0.0, 0.5 + i, 0.0)));
      Simulator sim = make_simulator(ground_scene(std::move(bodies), 0.5, 1e-2, model));
      const RunStats r = run(sim, 20);
      std::snprintf(detail, sizeof detail, "drift %.2g m over 20 steps", r.drift);
      rows.push_back({"stack", std::to_string(height) + " boxes", m, outcome(r.drift < 1e-6, r), r.residual, r.seconds,
                      detail_of(detail, r)});
    }
    {
      const double h = 1e-6;
      std::vector<RigidBody> bodies;
      for (int i = 0; i < 3; ++i) bodies.push_back(box(1.0, h, 1.0, Vec3(0.0, h / 2 + i * h, 0.0)));
      Simulator sim = make_simulator(ground_scene(std::move(bodies), 0.5, 1e-2, model));
      const RunStats r = run(sim, 100);
      std::snprintf(detail, sizeof detail, "drift %.2g m over 100 steps", r.drift);
      rows.push_back({"thin", "3 boxes 1 m x 1e-6 m stacked", m, outcome(r.drift < 1e-6, r), r.residual, r.seconds,
                      detail_of(detail, r)});
    }
    {
      Scene s = make_pyramid_scene(20, 1.0, 0.5);
      s.settings.model = model;
      Simulator pyramid = make_simulator(s);
      const int steps = model == ContactModel::lcp ? 20 : 2;
      const RunStats r = run(pyramid, steps);
      std::snprintf(detail, sizeof detail, "drift %.2g m over %d steps", r.drift, steps);
      rows.push_back({"pyramid", "210 boxes (20 rows)", m, outcome(r.drift < 1e-3, r), r.residual, r.seconds,
                      detail_of(detail, r)});
    }
  }
  // Redundant contacts: every contact of a resting box listed twice.
  const Scene s = ground_scene({box(1.0, 1.0, 1.0, Vec3(0.0, 0.5, 0.0))}, 0.5, 1e-2, ContactModel::lcp);
  std::vector<Contact> contacts;
  for (const Contact& c : find_contacts(s.world, CollisionSettings{1e-2})) {
    contacts.push_back(c);
    contacts.push_back(c);
  }
  Island island;
  island.bodies = {0};
  island.contacts.resize(contacts.size());
  std::iota(island.contacts.begin(), island.contacts.end(), 0);
  const ContactSystem sys = assemble_contact_system(s.world, contacts, island, 1e-2);
  for (ContactModel model : {ContactModel::lcp, ContactModel::convex}) {
    const auto t0 = std::chrono::steady_clock::now();
    const ContactSolution sol = model == ContactModel::lcp ? solve_lcp_model(sys, 1e-2, LemkeSettings{})
                                                           : solve_convex_model(sys, 1e-2, QpSettings{});
    const double t = seconds_since(t0);
    char detail[128];
    std::snprintf(detail, sizeof detail, "%d contacts (rank 3), |v+| = %.2g m/s", static_cast<int>(contacts.size()),
                  has_solution(sol.status) ? sol.v_next.norm() : NAN);
    rows.push_back({"redundant", "box, duplicated contacts", to_string(model),
                    has_solution(sol.status) ? (sol.v_next.norm() < 1e-7 ? "ok" : "moves") : "failed: " + sol.message, sol.residual, t,
                    detail});
  }
}

SparseMatrix sparse_of(const DenseMatrix& D) { return D.sparseView(); }

void solver_cases(std::vector<Row>& rows) {
  for (int n : {8, 12, 16}) {
    DenseMatrix M = DenseMatrix::Zero(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j <= i; ++j) M(i, j) = i == j ? 1.0 : 2.0;
    LemkeSolver lemke;
    lemke.setup(sparse_of(M), -Vector::Ones(n));
    const auto t0 = std::chrono::steady_clock::now();
    const LcpResult& r = lemke.solve();
    rows.push_back({"murty", "n = " + std::to_string(n), "lemke", to_string(r.info.status), r.info.complementarity,
                    seconds_since(t0), std::to_string(r.info.pivots) + " pivots"});
  }
  {
    LemkeSolver lemke;
    lemke.setup(sparse_of(-DenseMatrix::Identity(2, 2)), -Vector::Ones(2));
    const auto t0 = std::chrono::steady_clock::now();
    const LcpResult& r = lemke.solve();
    rows.push_back({"infeasible", "LCP w = -z - 1", "lemke", to_string(r.info.status), r.info.complementarity,
                    seconds_since(t0), r.info.message});
  }
  auto qp_case = [&](const std::string& name, QpProblem p) {
    QpSolver solver;
    const auto t0 = std::chrono::steady_clock::now();
    std::string status, detail;
    double residual = NAN;
    try {
      solver.setup(p);
      const QpResult& r = solver.solve();
      status = to_string(r.info.status);
      residual = std::max(r.info.primal_residual, r.info.dual_residual);
      detail = r.info.message;
    } catch (const InputError& e) {
      status = "invalid input";
      detail = e.what();
    }
    rows.push_back({name.rfind("NaN", 0) == 0 ? "invalid" : "infeasible", name, "qp", status, residual,
                    seconds_since(t0), detail});
  };
  {
    QpProblem p(2);  // x1 + x2 ≥ 3 and x1, x2 ≤ 1: primal infeasible
    p.G = sparse_of((DenseMatrix(1, 2) << 1.0, 1.0).finished());
    p.l = Vector::Constant(1, 3.0);
    p.u = Vector::Constant(1, std::numeric_limits<double>::infinity());
    p.xu = Vector::Ones(2);
    qp_case("QP x1 + x2 >= 3, x <= 1", p);
  }
  {
    QpProblem p(2);  // min −x1 with x ≥ 0 and P = 0: unbounded (dual infeasible)
    p.q << -1.0, 0.0;
    p.xl = Vector::Zero(2);
    qp_case("QP min -x1, x >= 0", p);
  }
  {
    QpProblem p(2);
    p.q << std::numeric_limits<double>::quiet_NaN(), 0.0;
    qp_case("NaN in q", p);
  }
  {
    LemkeSolver lemke;
    const auto t0 = std::chrono::steady_clock::now();
    std::string detail;
    try {
      lemke.setup(sparse_of(DenseMatrix::Identity(2, 2)), Vector::Constant(2, std::numeric_limits<double>::quiet_NaN()));
      detail = "accepted";
    } catch (const InputError& e) {
      detail = e.what();
    }
    rows.push_back({"invalid", "NaN in an LCP's q", "lemke", detail == "accepted" ? "accepted (!)" : "invalid input", NAN,
                    seconds_since(t0), detail});
  }
  {
    const auto t0 = std::chrono::steady_clock::now();
    std::string detail;
    try {
      PileOptions o;
      o.dt = std::numeric_limits<double>::quiet_NaN();
      make_pile_scene(o);
      detail = "accepted";
    } catch (const InputError& e) {
      detail = e.what();
    }
    rows.push_back({"invalid", "NaN time step in a scene", "scene", detail == "accepted" ? "accepted (!)" : "invalid input",
                    NAN, seconds_since(t0), detail});
  }
}

std::string csv_field(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"stiff-and-extreme report: every validation case with status, residual and time"};
  std::string csv = "stiff_report.csv";
  app.add_option("--csv", csv, "output CSV");
  CLI11_PARSE(app, argc, argv);

  std::vector<Row> rows;
  dynamics_cases(rows);
  solver_cases(rows);

  std::ofstream out(csv);
  if (!out) {
    std::fprintf(stderr, "cannot write %s\n", csv.c_str());
    return 2;
  }
  out << "suite,case,model,status,residual,seconds,detail\n";
  out.precision(6);
  std::printf("| suite | case | model | status | residual | seconds | detail |\n|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    out << csv_field(r.suite) << ',' << csv_field(r.name) << ',' << r.model << ',' << csv_field(r.status) << ','
        << r.residual << ',' << r.seconds << ',' << csv_field(r.detail) << '\n';
    std::printf("| %s | %s | %s | %s | %.2g | %.3g | %s |\n", r.suite.c_str(), r.name.c_str(), r.model.c_str(),
                r.status.c_str(), r.residual, r.seconds, r.detail.c_str());
  }
  return 0;
}
