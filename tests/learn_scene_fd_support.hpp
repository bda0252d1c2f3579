#pragma once
// Central differences of one SceneObjective sample against its adjoint gradient, parameter
// by parameter, for the scene gradient tests (learn_scene_gradient_test.cpp,
// learn_scene_gap_test.cpp, learn_scene_velocity_residual_test.cpp). One-sided differences at h and h/2 tell a kink (forward − backward does not halve with h)
// from a smooth stretch; on a kink the adjoint must equal one of the one-sided derivatives,
// elsewhere the central difference to `tolerance` relative to the parameter's own derivative
// (floor 1e-3 of the largest), plus the differences' own error (their change from h to h/2).
#include <lcprelax/learn/scene_objective.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace lcprelax::learn::test {

struct FdReport {
  int checked = 0;     ///< parameters compared on smooth stretches
  int kinks = 0;       ///< parameters on kinks
  double worst = 0.0;  ///< largest |adjoint − central difference| / scale over the checked ones
};

/// The sample of `objective` with the most contacts at θ (and that count in `contacts`).
inline Index sample_with_most_contacts(SceneObjective& objective, const ParameterSet& theta, long& contacts) {
  objective.prepare(theta, 1);
  Index best = 0;
  contacts = -1;
  for (Index i = 0; i < objective.num_samples(); ++i) {
    objective.reset_stats();
    objective.evaluate(i, theta, 0);
    if (objective.stats().contacts > contacts) contacts = objective.stats().contacts, best = i;
  }
  return best;
}

/// The samples of `objective` at θ with at least `min_contacts` contacts on which every
/// parameter of `params` has a nonzero ∂ℓ/∂θ_k, by decreasing Σ_k |∂ℓ/∂θ_k| over `params`.
inline std::vector<Index> samples_by_gradient(SceneObjective& objective, const ParameterSet& theta,
                                              const std::vector<Index>& params, long min_contacts) {
  objective.prepare(theta, 1);
  std::vector<std::pair<double, Index>> found;
  for (Index i = 0; i < objective.num_samples(); ++i) {
    objective.reset_stats();
    const SampleResult r = objective.evaluate(i, theta, 0);
    if (!r.ok || objective.stats().contacts < min_contacts) continue;
    double sum = 0.0;
    bool all = true;
    for (Index k : params) sum += std::abs(r.gradient(k)), all = all && r.gradient(k) != 0.0;
    if (all) found.emplace_back(-sum, i);
  }
  std::sort(found.begin(), found.end());
  std::vector<Index> out;
  for (const auto& f : found) out.push_back(f.second);
  return out;
}

/// Compares ∂ℓ/∂θ_k of sample `sample` with central differences for each k in `params`
/// (GoogleTest expectations); h = 1e-5·max(length scale, |θ_k|), 1e-5 rad for angles.
inline FdReport compare_with_central_differences(SceneObjective& objective, const SceneParameterMap& map,
                                                 const ParameterSet& theta, Index sample,
                                                 const std::vector<Index>& params, const std::string& label,
                                                 double tolerance = 1e-5) {
  auto eval = [&](const ParameterSet& at) {
    objective.prepare(at, 1);
    return objective.evaluate(sample, at, 0);
  };
  const SampleResult r = eval(theta);
  FdReport report;
  EXPECT_TRUE(r.ok) << r.message;
  if (!r.ok || r.gradient.size() != theta.size()) return report;
  double gmax = 0.0;
  for (Index k : params) gmax = std::max(gmax, std::abs(r.gradient(k)));
  EXPECT_GT(gmax, 0.0) << label << ": the checked parameters have a zero gradient";
  auto loss_at = [&](Index k, double step) {
    Vector v = theta.values();
    v(k) += step;
    ParameterSet at = theta;
    at.set_values(v);
    const SampleResult rs = eval(at);
    EXPECT_TRUE(rs.ok) << theta[k].name << ": " << rs.message;
    return rs.loss;
  };
  for (Index k : params) {
    const double h = 1e-5 * (map.kind(k) == SceneParameterMap::Kind::angle
                                 ? 1.0
                                 : std::max(map.length_scale(k), std::abs(theta[k].value)));
    const double p1 = loss_at(k, h), m1 = loss_at(k, -h), p2 = loss_at(k, h / 2), m2 = loss_at(k, -h / 2);
    const double fwd1 = (p1 - r.loss) / h, bwd1 = (r.loss - m1) / h;
    const double fwd2 = (p2 - r.loss) / (h / 2), bwd2 = (r.loss - m2) / (h / 2);
    const double fd = (p2 - m2) / h, fd_h = (p1 - m1) / (2 * h);
    const double scale = std::max(std::abs(fd), 1e-3 * gmax);
    const double jump1 = std::abs(fwd1 - bwd1), jump2 = std::abs(fwd2 - bwd2);
    if (jump2 > 1e-4 * scale && jump2 > 0.75 * jump1) {
      ++report.kinks;
      const double one_sided = std::min(std::abs(r.gradient(k) - fwd2), std::abs(r.gradient(k) - bwd2));
      std::printf("%s: kink at %s, one-sided %.9g / %.9g, adjoint %.9g\n", label.c_str(), theta[k].name.c_str(), fwd2,
                  bwd2, r.gradient(k));
      EXPECT_LE(one_sided, 1e-3 * std::max(std::abs(fwd2), std::abs(bwd2)) + 1e-6 * gmax)
          << label << " " << theta[k].name << ": the adjoint is neither one-sided derivative";
      continue;
    }
    EXPECT_LE(std::abs(fd - fd_h), 1e-4 * scale) << label << " " << theta[k].name << ": a kink within ±h";
    // The differences' own error (roundoff of the solves over h, truncation), estimated by
    // their move from h to h/2, is allowed on top of the relative tolerance.
    const double noise = 2.0 * std::abs(fd - fd_h);
    EXPECT_LE(std::abs(r.gradient(k) - fd), tolerance * scale + noise)
        << label << " " << theta[k].name << ": adjoint " << r.gradient(k) << ", central difference " << fd;
    report.worst = std::max(report.worst, std::abs(r.gradient(k) - fd) / scale);
    ++report.checked;
  }
  std::printf("%s: %d parameters compared (largest relative error %.2e), %d on kinks\n", label.c_str(), report.checked,
              report.worst, report.kinks);
  return report;
}

/// Loss settings of the gradient tests: QP tolerances 1e-12 absolute (the convex loss's
/// 1e-14: its adjoint runs through two interior-point solves and agrees with the differences
/// to 1.3e-5 at 1e-12, to 1.0e-6 at 1e-14), and every probe centred at 0 (a stored proximal
/// centre would make ℓ depend on the previous probe).
inline SceneLossSettings fd_loss_settings(LossMethod method) {
  SceneLossSettings ls;
  ls.method = method;
  ls.relaxed.qp.eps_abs = 1e-12;
  ls.relaxed.qp.eps_rel = ls.convex.qp.eps_rel = 0.0;
  ls.convex.qp.eps_abs = 1e-14;
  ls.relaxed_warm_center = false;
  return ls;
}

/// Over the first five of `samples`, the first on which `params` compare with `accept`ed
/// kinks (accept(report) true); there the other learned parameters of θ are compared too
/// (at most one of them on a kink). Expects such a sample to exist.
template <class Accept>
void check_first_smooth_sample(SceneObjective& objective, const SceneParameterMap& map, const ParameterSet& theta,
                               const std::vector<Index>& samples, const std::vector<Index>& params,
                               const std::string& label, Accept accept) {
  std::vector<Index> others;
  for (Index k = 0; k < theta.size(); ++k)
    if (theta[k].learn && std::find(params.begin(), params.end(), k) == params.end()) others.push_back(k);
  const std::size_t tried = std::min<std::size_t>(5, samples.size());
  for (std::size_t n = 0; n < tried; ++n) {
    const std::string at = label + ", transition " + std::to_string(samples[n]);
    if (!accept(compare_with_central_differences(objective, map, theta, samples[n], params, at))) continue;
    const FdReport o = compare_with_central_differences(objective, map, theta, samples[n], others, at + ": others");
    EXPECT_GE(o.checked, static_cast<int>(others.size()) - 1) << "at most one parameter on a kink";
    return;
  }
  ADD_FAILURE() << label << ": too many kinks at each of " << tried << " steps";
}

/// Indices of θ's parameters whose name contains `part`.
inline std::vector<Index> parameters_named(const ParameterSet& theta, const std::string& part) {
  std::vector<Index> out;
  for (Index k = 0; k < theta.size(); ++k)
    if (theta[k].name.find(part) != std::string::npos) out.push_back(k);
  return out;
}

}  // namespace lcprelax::learn::test
