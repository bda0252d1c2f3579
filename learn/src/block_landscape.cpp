// Loss landscape of the 1-D block over μ (learn/block_landscape.hpp).
#include <lcprelax/learn/block_landscape.hpp>
#include <lcprelax/scenes/line_plot.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace lcprelax::learn {

BlockLandscape block_landscape(const BlockDataset& data, const BlockLossSettings& settings,
                               const std::vector<BlockMethod>& methods, double mu_min, double mu_max, int points,
                               int threads) {
  if (!(mu_min > 0.0) || !(mu_max > mu_min) || !std::isfinite(mu_max))
    throw InputError("landscape: need 0 < mu_min < mu_max < inf");
  if (points < 2) throw InputError("landscape: need at least 2 points");
  BlockLandscape L;
  L.methods = methods;
  for (int k = 0; k < points; ++k)
    L.mu.push_back(mu_min * std::pow(mu_max / mu_min, static_cast<double>(k) / (points - 1)));
  std::vector<Index> all(static_cast<std::size_t>(data.size()));
  for (Index i = 0; i < data.size(); ++i) all[static_cast<std::size_t>(i)] = i;
  for (BlockMethod m : methods) {
    std::unique_ptr<BlockObjective> objective = make_block_objective(m, data, settings);
    L.loss.emplace_back();
    L.gradient.emplace_back();
    L.failed.emplace_back();
    for (double mu : L.mu) {
      const ParameterSet theta = block_parameters(mu, data.mass, data.mg);
      const BatchResult r = evaluate_mean(*objective, theta, all, threads);
      const bool any = r.evaluated > 0;
      L.loss.back().push_back(any ? r.loss : std::nan(""));
      L.gradient.back().push_back(any ? r.gradient(theta.index("mu")) : std::nan(""));
      L.failed.back().push_back(r.failed);
    }
  }
  return L;
}

void write_landscape_csv(const std::string& path, const BlockLandscape& L) {
  std::ofstream out(path);
  if (!out) throw InputError("cannot write the landscape CSV '" + path + "'");
  out.precision(17);
  out << "mu";
  for (BlockMethod m : L.methods) out << ',' << to_string(m) << "_loss," << to_string(m) << "_gradient";
  out << '\n';
  for (std::size_t k = 0; k < L.mu.size(); ++k) {
    out << L.mu[k];
    for (std::size_t j = 0; j < L.methods.size(); ++j) out << ',' << L.loss[j][k] << ',' << L.gradient[j][k];
    out << '\n';
  }
  if (!out) throw InputError("writing the landscape CSV '" + path + "' failed");
}

std::vector<std::string> write_landscape_plot(const std::string& path, const BlockLandscape& L, double true_mu) {
  std::vector<LineSeries> losses, gradients;
  for (std::size_t j = 0; j < L.methods.size(); ++j) {
    const std::string name = to_string(L.methods[j]);
    losses.push_back(LineSeries{name, L.mu, L.loss[j]});
    gradients.push_back(LineSeries{name, L.mu, L.gradient[j]});
  }
  LinePlotOptions o;
  o.x_label = "mu";
  o.log_x = true;
  if (std::isfinite(true_mu) && true_mu > 0.0) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& s : L.loss)
      for (double v : s)
        if (v > 0.0 && std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (lo < hi) {
      LineSeries t{"true mu", {true_mu, true_mu}, {lo, hi}};
      t.dashed = true;
      losses.push_back(t);
    }
  }
  o.title = "block: mean loss over the samples";
  o.y_label = "loss";
  o.log_y = true;
  write_line_plot(path, losses, o);
  const std::filesystem::path p(path);
  const std::string gpath = (p.parent_path() / (p.stem().string() + "_gradient" + p.extension().string())).string();
  o.title = "block: mean d loss / d mu";
  o.y_label = "d loss / d mu";
  o.log_y = false;
  write_line_plot(gpath, gradients, o);
  return {path, gpath};
}

const char* to_string(GradientSign s) {
  switch (s) {
    case GradientSign::correct: return "correct";
    case GradientSign::wrong: return "wrong";
    case GradientSign::zero: return "zero";
    case GradientSign::failed: return "failed";
  }
  return "unknown";
}

GradientSign classify_gradient(const Vector& theta, const Vector& truth, const Vector& gradient, double loss,
                               double zero_tolerance) {
  if (theta.size() != truth.size() || theta.size() != gradient.size())
    throw InputError("classify_gradient: theta, truth and gradient differ in size");
  if (!std::isfinite(loss) || !gradient.allFinite()) return GradientSign::failed;
  double dot = 0.0, largest = 0.0;
  for (Index k = 0; k < theta.size(); ++k) {
    const double g_xi = theta(k) * gradient(k);  // ∂ℓ/∂log θ_k
    largest = std::max(largest, std::abs(g_xi));
    dot += g_xi * (std::log(truth(k)) - std::log(theta(k)));
  }
  if (largest <= zero_tolerance * std::abs(loss)) return GradientSign::zero;
  return dot < 0.0 ? GradientSign::correct : GradientSign::wrong;
}

namespace {
// The counter of `s` in `c`.
template <class Counts>
auto& counter(Counts& c, GradientSign s) {
  switch (s) {
    case GradientSign::correct: return c.correct;
    case GradientSign::wrong: return c.wrong;
    case GradientSign::zero: return c.zero;
    case GradientSign::failed: break;
  }
  return c.failed;
}
}  // namespace

double GradientSignCounts::fraction(GradientSign s) const {
  if (points() == 0) return std::nan("");
  return static_cast<double>(counter(*this, s)) / points();
}

void GradientSignCounts::add(GradientSign s) { ++counter(*this, s); }

GradientSignCounts count_gradient_signs(const BlockLandscape& L, std::size_t j, double true_mu, double zero_tolerance) {
  if (j >= L.methods.size()) throw InputError("count_gradient_signs: no method " + std::to_string(j));
  GradientSignCounts c;
  for (std::size_t k = 0; k < L.mu.size(); ++k) {
    if (std::abs(L.mu[k] - true_mu) <= 1e-9 * true_mu) continue;
    const Vector theta = Vector::Constant(1, L.mu[k]), truth = Vector::Constant(1, true_mu);
    const Vector g = Vector::Constant(1, L.gradient[j][k]);
    c.add(L.failed[j][k] > 0 ? GradientSign::failed : classify_gradient(theta, truth, g, L.loss[j][k], zero_tolerance));
  }
  return c;
}

}  // namespace lcprelax::learn
