// Scene learning at scale (learn/scene_objective.hpp): loss + gradient per transition
// against contacts, against the simulator step on the same state, peak memory, and the
// 2-thread / 1-thread throughput of a batched evaluation.
//
//   run_learn_scene [--bodies 10,30,100,300,1000,2000] [--settle 80] [--methods relaxed,hard,convex]
//                   [--throughput-bodies 100] [--throughput-steps 40] [--csv OUT.csv]
//
// Scaling: for each N a learning pile of N bodies (3 shape classes, seed 1, convex model) is
// simulated `settle` steps with pushes (SceneDatasetSettings defaults); the last transition
// is the state measured. Per method: the wall time of SceneObjective::evaluate at the true θ
// (median of 3 after one warm-up; every island's loss and gradient, pulled back to θ), and
// the wall time of one Simulator::step from the same state with the same model (median of
// 3); the peak resident set size (getrusage) after the run of N. The log-log slope of
// evaluate time against contacts is fitted by least squares over the N with ≥ 50 contacts.
// Throughput: the transitions of a `throughput-bodies` pile, evaluate_batch over all of them
// with 1 and with 2 threads (best of 3 each, warm: every contact has its proximal centre),
// the ratio in one run; bitwise equality of 1 and 2 threads from the same (empty) centres.
#include <lcprelax/learn/batch.hpp>
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/models/simulator.hpp>

#include <CLI/CLI.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

using namespace lcprelax;
using namespace lcprelax::learn;

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux: kB
}

template <class F>
double median_seconds(int runs, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < runs; ++r) {
    const double t0 = now();
    f();
    t.push_back(now() - t0);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"scene learning: loss + gradient against contacts, simulator step, memory, threads"};
  std::string bodies_list = "10,30,100,300,1000,2000", methods_list = "relaxed,hard,convex", csv_path;
  int settle = 80, tp_bodies = 100, tp_steps = 40;
  app.add_option("--bodies", bodies_list, "pile sizes")->capture_default_str();
  app.add_option("--settle", settle, "simulated steps before the measured state")->capture_default_str();
  app.add_option("--methods", methods_list, "loss methods")->capture_default_str();
  app.add_option("--throughput-bodies", tp_bodies, "pile of the thread study (0: skip)")->capture_default_str();
  app.add_option("--throughput-steps", tp_steps, "steps of the thread study")->capture_default_str();
  app.add_option("--csv", csv_path, "CSV output");
  CLI11_PARSE(app, argc, argv);

  std::ofstream csv;
  if (!csv_path.empty()) {
    csv.open(csv_path);
    csv << "bodies,contacts,islands,method,status,evaluate_s,step_s,ratio,peak_rss_mb\n";
  }
  std::printf("%7s %8s %7s %8s %10s %12s %10s %7s %9s\n", "bodies", "contacts", "islands", "method", "status",
              "loss+grad s", "step s", "ratio", "rss MB");
  std::vector<std::pair<double, double>> points;  // relaxed: (contacts, seconds)
  for (const std::string& n_text : split(bodies_list)) {
    const int n = std::stoi(n_text);
    LearningPileOptions po;
    po.bodies = n;
    po.model = ContactModel::convex;
    Scene scene = make_learning_pile(po);
    SceneDatasetSettings ds;
    ds.steps = settle;
    ds.drop_without_contact = false;
    ds.allow_failed_islands = true;
    SceneDataset data = generate_scene_dataset(scene, ds);
    data.transitions.erase(data.transitions.begin(), data.transitions.end() - 1);
    const SceneParameterMap map(data.scene.world, SceneParameterSettings{});
    const ParameterSet theta = map.parameters(data.scene.world);

    // The simulator step from the same state.
    World state = data.scene.world;
    const SceneTransition& t = data.transitions.back();
    for (std::size_t b = 0; b < state.bodies.size(); ++b) state.bodies[b].pose = t.pose[b], state.bodies[b].velocity = t.velocity[b];
    SimulatorSettings sim = data.scene.settings;
    sim.threads = 1;
    const double step_s = median_seconds(3, [&] {
      Simulator s(state, sim);
      s.step(t.applied);
    });

    for (const std::string& m : split(methods_list)) {
      SceneLossSettings ls;
      ls.method = parse_loss_method(m);
      SceneObjective objective(data, map, ls);
      objective.prepare(theta, 1);
      SampleResult r = objective.evaluate(0, theta, 0);  // warm-up
      const double eval_s = median_seconds(3, [&] { r = objective.evaluate(0, theta, 0); });
      const SceneObjectiveStats st = objective.stats();
      const long contacts = st.contacts / std::max(1L, st.transitions);
      const long islands = st.islands / std::max(1L, st.transitions);
      const double rss = peak_rss_mb();
      std::printf("%7d %8ld %7ld %8s %10s %12.4g %10.4g %7.2f %9.1f\n", n, contacts, islands, m.c_str(),
                  r.ok ? "ok" : "failed", eval_s, step_s, eval_s / step_s, rss);
      if (!r.ok) std::printf("        (%s)\n", r.message.c_str());
      if (csv.is_open())
        csv << n << ',' << contacts << ',' << islands << ',' << m << ',' << (r.ok ? "ok" : "failed") << ',' << eval_s
            << ',' << step_s << ',' << eval_s / step_s << ',' << rss << '\n';
      if (m == "relaxed" && r.ok && contacts >= 50) points.emplace_back(std::log(double(contacts)), std::log(eval_s));
    }
  }
  if (points.size() >= 2) {
    double mx = 0, my = 0;
    for (auto& p : points) mx += p.first / points.size(), my += p.second / points.size();
    double sxy = 0, sxx = 0;
    for (auto& p : points) sxy += (p.first - mx) * (p.second - my), sxx += (p.first - mx) * (p.first - mx);
    std::printf("relaxed: log-log slope of loss+gradient time against contacts = %.3f (%zu sizes with >= 50 contacts)\n",
                sxy / sxx, points.size());
  }

  if (tp_bodies > 0) {
    LearningPileOptions po;
    po.bodies = tp_bodies;
    po.model = ContactModel::convex;
    SceneDatasetSettings ds;
    ds.steps = tp_steps;
    const SceneDataset data = generate_scene_dataset(make_learning_pile(po), ds);
    const SceneParameterMap map(data.scene.world, SceneParameterSettings{});
    const ParameterSet theta = map.parameters(data.scene.world);
    std::vector<Index> all(data.transitions.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
    SceneLossSettings ls;
    SceneObjective objective(data, map, ls);
    double best[3] = {1e300, 1e300, 1e300};
    BatchResult results[3];
    for (int rep = 0; rep < 3; ++rep)
      for (int threads : {1, 2}) {
        objective.prepare(theta, threads);
        const double t0 = now();
        results[threads] = evaluate_batch(all, theta.size(), threads,
                                          [&](Index i, int thread) { return objective.evaluate(i, theta, thread); });
        best[threads] = std::min(best[threads], now() - t0);
      }
    // Bitwise: the relaxed objective keeps each contact's proximal centre between
    // evaluations, so both thread counts start from no centres and evaluate twice (the
    // second evaluation warm); the timed runs above are warm evaluations.
    BatchResult twice[3];
    for (int threads : {1, 2}) {
      objective.reset_centers();
      objective.prepare(theta, threads);
      for (int k = 0; k < 2; ++k)
        twice[threads] = evaluate_batch(all, theta.size(), threads,
                                        [&](Index i, int thread) { return objective.evaluate(i, theta, thread); });
    }
    (void)results;
    const bool same = twice[1].loss == twice[2].loss && twice[1].gradient == twice[2].gradient;
    std::printf("throughput (%d bodies, %zu transitions, relaxed): 1 thread %.4g s, 2 threads %.4g s, ratio %.2f, "
                "bitwise equal: %s\n",
                tp_bodies, all.size(), best[1], best[2], best[1] / best[2], same ? "yes" : "no");
  }
  return 0;
}
