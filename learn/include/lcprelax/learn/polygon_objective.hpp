#pragma once
// The polygon learning problem as a learn::Objective (trainer.hpp): one sample per
// transition of a PolygonDataset, ℓᵢ and ∂ℓᵢ/∂θ by the method of PolygonLossSettings
// (polygon_losses.hpp). θ must have the layout of make_polygon_parameters for the
// dataset's polygon (polygon_params.hpp).
//
// evaluate(i, θ, thread): active set at the sample's pre-state for the current θ
// (polygon_assembly.hpp, widened by PolygonLossSettings::candidate_margin), assembly with tangents, the method's loss. Per-thread
// workspaces (a RelaxedLcpSolver each, created in prepare()) and per-sample warm starts
// from the previous evaluation of the same sample (a sample is never evaluated twice at
// once, trainer.hpp). Warm starts depend only on the sample's own history, so the result
// is the same for every thread count (tests/learn_polygon_threads_test.cpp). A sample
// whose active set changed since its last evaluation starts cold. The warm starts and active
// sets are saved in training checkpoints (save_state, checkpoint.hpp).
#include <lcprelax/learn/polygon_dataset.hpp>
#include <lcprelax/learn/polygon_losses.hpp>
#include <lcprelax/learn/trainer.hpp>

#include <memory>
#include <vector>

namespace lcprelax::learn {

class PolygonObjective : public Objective {
 public:
  /// Keeps a reference to `data` (must outlive the objective); throws InputError on
  /// invalid settings or an empty dataset.
  PolygonObjective(const PolygonDataset& data, PolygonLossSettings settings);
  ~PolygonObjective() override;

  Index num_samples() const override;
  void prepare(const ParameterSet& theta, int threads) override;
  SampleResult evaluate(Index sample, const ParameterSet& theta, int thread) override;
  void save_state(StateWriter& out) const override;
  void load_state(StateReader& in) override;

  const PolygonLossSettings& settings() const { return settings_; }
  /// Time split summed over threads since construction or reset_times().
  PolygonLossTimes times() const;
  void reset_times();
  /// Forgets all warm starts (the next evaluations start cold).
  void reset_warm_starts();

 private:
  struct Workspace;
  const PolygonDataset& data_;
  PolygonLossSettings settings_;
  std::vector<std::unique_ptr<Workspace>> workspaces_;
  std::vector<PolygonWarmStart> warm_;
  std::vector<std::vector<int>> warm_vertices_;
};

}  // namespace lcprelax::learn
