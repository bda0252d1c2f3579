// The polygon learning Objective and the method settings (polygon_objective.hpp,
// polygon_losses.hpp).
#include "polygon_solvers.hpp"

#include <lcprelax/learn/polygon_objective.hpp>
#include <lcprelax/core/errors.hpp>

#include <chrono>
#include <cmath>

namespace lcprelax::learn {

const char* to_string(PolygonMethod m) {
  switch (m) {
    case PolygonMethod::hard: return "hard";
    case PolygonMethod::relaxed: return "relaxed";
    case PolygonMethod::convex: return "convex";
  }
  return "unknown";
}

PolygonMethod parse_polygon_method(const std::string& s) {
  if (s == "hard") return PolygonMethod::hard;
  if (s == "relaxed") return PolygonMethod::relaxed;
  if (s == "convex") return PolygonMethod::convex;
  throw InputError("--method: unknown method '" + s + "' (expected hard, relaxed or convex)");
}

PolygonLossSettings::PolygonLossSettings() {
  relaxed.nonconvex = NonconvexPolicy::shift;
  relaxed.a2 = 0.1;
  relaxed.regularization = 1e-6;
}

std::string PolygonLossSettings::validation_error() const {
  std::string e = lemke.validation_error();
  if (!e.empty()) return "lemke: " + e;
  e = relaxed.validation_error();
  if (!e.empty()) return "relaxed: " + e;
  if (!(std::isfinite(convex_rho) && convex_rho >= 0)) return "convex_rho: must be finite and >= 0";
  if (!(std::isfinite(convex_deviation) && convex_deviation >= 0)) return "convex_deviation: must be finite and >= 0";
  if (!(std::isfinite(candidate_margin) && candidate_margin >= 0)) return "candidate_margin: must be finite and >= 0";
  return {};
}

struct PolygonObjective::Workspace {
  explicit Workspace(const PolygonLossSettings& s) : relaxed(s.relaxed, s.qp), solvers(s) {}
  RelaxedLcpSolver relaxed;
  PolygonSolvers solvers;
  PolygonAssembly assembly;
  PolygonLossTimes times;
};

PolygonObjective::PolygonObjective(const PolygonDataset& data, PolygonLossSettings settings)
    : data_(data), settings_(std::move(settings)) {
  const std::string e = settings_.validation_error();
  if (!e.empty()) throw InputError("polygon loss settings: " + e);
  if (data_.transitions.empty()) throw InputError("polygon dataset: no transitions");
  warm_.resize(data_.transitions.size());
  warm_vertices_.resize(data_.transitions.size());
}

PolygonObjective::~PolygonObjective() = default;

Index PolygonObjective::num_samples() const { return static_cast<Index>(data_.transitions.size()); }

void PolygonObjective::prepare(const ParameterSet& /*theta*/, int threads) {
  const int t = resolve_threads(threads);
  // Each workspace is made by its thread on its first sample (evaluate): its memory then
  // comes from that thread's malloc arena and shares no cache line with another thread's.
  if (static_cast<int>(workspaces_.size()) < t) workspaces_.resize(static_cast<std::size_t>(t));
}

SampleResult PolygonObjective::evaluate(Index sample, const ParameterSet& theta, int thread) {
  if (thread < 0 || thread >= static_cast<int>(workspaces_.size()))
    throw std::logic_error("PolygonObjective::evaluate: prepare() was not called for this thread count");
  std::unique_ptr<Workspace>& slot = workspaces_[static_cast<std::size_t>(thread)];
  if (!slot) slot = std::make_unique<Workspace>(settings_);
  Workspace& ws = *slot;
  const PolygonTransition& s = data_.transitions[static_cast<std::size_t>(sample)];
  const auto t0 = std::chrono::steady_clock::now();
  const PolygonModel model = polygon_model(theta);
  const std::vector<int> vertices = polygon_active_vertices(model, s, data_, settings_.candidate_margin);
  assemble_polygon(model, vertices, s, data_, ws.assembly);
  ws.times.assembly += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  PolygonWarmStart& warm = warm_[static_cast<std::size_t>(sample)];
  std::vector<int>& previous = warm_vertices_[static_cast<std::size_t>(sample)];
  if (previous != vertices) {
    warm = PolygonWarmStart();
    previous = vertices;
  }
  switch (settings_.method) {
    case PolygonMethod::hard: return polygon_hard_loss(ws.assembly, s.v_next, data_.dt, settings_, warm, ws.times, &ws.solvers);
    case PolygonMethod::relaxed:
      return polygon_relaxed_loss(ws.assembly, s.v_next, data_.dt, settings_, ws.relaxed, warm, ws.times);
    case PolygonMethod::convex: return polygon_convex_loss(ws.assembly, s.v_next, data_.dt, settings_, warm, ws.times, &ws.solvers);
  }
  throw std::logic_error("PolygonObjective: unknown method");
}

PolygonLossTimes PolygonObjective::times() const {
  PolygonLossTimes sum;
  for (const auto& w : workspaces_) {
    if (!w) continue;
    sum.assembly += w->times.assembly;
    sum.solve += w->times.solve;
    sum.backward += w->times.backward;
    sum.samples += w->times.samples;
  }
  return sum;
}

void PolygonObjective::reset_times() {
  for (auto& w : workspaces_)
    if (w) w->times = PolygonLossTimes();
}

void PolygonObjective::save_state(StateWriter& out) const {
  out.put_string("polygon: warm starts");
  out.put_u64(warm_.size());
  for (std::size_t i = 0; i < warm_.size(); ++i) {
    const PolygonWarmStart& w = warm_[i];
    out.put_ints(warm_vertices_[i]);
    out.put_bools(w.lemke_basis);
    out.put_bool(w.relaxed_valid);
    out.put_vector(w.relaxed.lambda);  // its size tells the relaxed loss that the start fits
    out.put_vector(w.relaxed.qp_x);
    out.put_vector(w.relaxed.qp_z);
    out.put_vector(w.relaxed.qp_z_bounds);
  }
}

void PolygonObjective::load_state(StateReader& in) {
  in.expect_tag("polygon: warm starts");
  in.get_count(warm_.size(), false, "samples");
  for (std::size_t i = 0; i < warm_.size(); ++i) {
    PolygonWarmStart w;
    warm_vertices_[i] = in.get_ints();
    w.lemke_basis = in.get_bools();
    w.relaxed_valid = in.get_bool();
    w.relaxed.lambda = in.get_vector();
    w.relaxed.qp_x = in.get_vector();
    w.relaxed.qp_z = in.get_vector();
    w.relaxed.qp_z_bounds = in.get_vector();
    warm_[i] = std::move(w);
  }
}

void PolygonObjective::reset_warm_starts() {
  for (PolygonWarmStart& w : warm_) w = PolygonWarmStart();
  for (auto& v : warm_vertices_) v.clear();
}

}  // namespace lcprelax::learn
