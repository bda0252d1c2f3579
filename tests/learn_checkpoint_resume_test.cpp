// Training checkpoints through the C++ API (learn/checkpoint.hpp, trainer.hpp). Expected
// behaviour: N epochs uninterrupted and k epochs with a checkpoint followed by a resume to N
// (each part with a FRESH objective and θ, as a new process would have) end with bitwise
// equal parameters (memcmp), equal epoch losses and the same stop reason, for the block
// (hard, relaxed with QP warm starts, convex), polygon (hard, relaxed) and scene (relaxed
// with its proximal centres, hard with its stored Lemke bases) learning problems, with
// mini-batches and Adam or SGD, and with another thread count on the resumed part (the
// reduction is in a fixed order, batch.hpp).
// A run resumed at its end (converged) stays as it was. A checkpoint of another problem
// (other parameter count, other seed, other training set) is rejected with a message naming
// the field; the CSV log of a resumed run equals the uninterrupted one's apart from times.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/block_losses.hpp>
#include <lcprelax/learn/checkpoint.hpp>
#include <lcprelax/learn/polygon_objective.hpp>
#include <lcprelax/learn/scene_objective.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>

namespace lcprelax::learn {
namespace {

namespace fs = std::filesystem;

bool same_bits(const Vector& a, const Vector& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

std::string temp_file(const std::string& name) {
  return (fs::temp_directory_path() / ("lcprelax_ckpt_" + std::to_string(::getpid()) + "_" + name)).string();
}

// A problem: a factory of fresh objectives, the initial θ and the sample split.
struct Problem {
  std::function<std::unique_ptr<Objective>()> objective;
  ParameterSet theta;
  std::vector<Index> training, validation;
};

// Trains `epochs` epochs uninterrupted, then again stopping after each of `stops` with a
// checkpoint and resuming (fresh objective and θ each time); compares θ bitwise.
void expect_resume_is_bitwise(const Problem& p, TrainSettings ts, int epochs, const std::vector<int>& stops,
                              int resumed_threads, bool expect_converged = false) {
  ts.epochs = epochs;
  ParameterSet reference = p.theta;
  const TrainResult full = train(*p.objective(), reference, p.training, p.validation, ts);
  ASSERT_LE(static_cast<int>(full.history.size()), epochs);
  const int done = static_cast<int>(full.history.size());  // < epochs when the run converged

  const std::string file = temp_file("resume.ckpt");
  ParameterSet theta = p.theta;
  TrainResult part;
  for (std::size_t k = 0; k <= stops.size(); ++k) {
    TrainSettings s = ts;
    s.epochs = k < stops.size() ? stops[k] : epochs;
    s.checkpoint = file;
    s.resume = k == 0 ? "" : file;
    if (k > 0) s.threads = resumed_threads;
    theta = p.theta;  // a new process: θ and the objective start from scratch
    part = train(*p.objective(), theta, p.training, p.validation, s);
    ASSERT_EQ(static_cast<int>(part.history.size()), std::min(s.epochs, done));
  }
  EXPECT_TRUE(same_bits(theta.values(), reference.values())) << "resumed " << theta.values().transpose() << "\nfull    "
                                                             << reference.values().transpose();
  for (int e = 0; e < done; ++e) {
    const auto& a = full.history[static_cast<std::size_t>(e)];
    const auto& b = part.history[static_cast<std::size_t>(e)];
    EXPECT_TRUE(same_bits(Vector::Constant(1, a.loss), Vector::Constant(1, b.loss))) << "epoch " << e + 1;
    EXPECT_TRUE(same_bits(a.theta, b.theta)) << "epoch " << e + 1;
  }
  EXPECT_EQ(part.stop_reason, full.stop_reason);
  EXPECT_EQ(part.converged, full.converged);
  EXPECT_EQ(full.converged, expect_converged);
  EXPECT_EQ(part.failed, full.failed);
  fs::remove(file);
}

Problem block_problem(BlockMethod method) {
  BlockDataSettings g;
  g.truth = Block1d{1.0, 1.0, 0.1};
  g.samples = 40;
  g.seed = 3;
  g.noise = 0.05;
  const auto data = std::make_shared<BlockDataset>(generate_block_dataset(g));
  BlockLossSettings s;
  s.warm_start_qp = true;  // exercise the QP warm starts in the checkpoint too
  Problem p;
  p.objective = [data, method, s] { return make_block_objective(method, *data, s); };
  p.theta = block_parameters(0.6, 1.0, 1.0, true, false);
  split_samples(40, 0.2, 5, p.training, p.validation);
  return p;
}

TrainSettings mini_batch_adam() {
  TrainSettings ts;
  ts.batch = 7;
  ts.seed = 9;
  ts.threads = 1;
  ts.patience = 0;
  ts.optimizer.kind = OptimizerKind::adam;
  ts.optimizer.learning_rate = 0.05;
  ts.optimizer.decay = 0.01;
  return ts;
}

TEST(LearnCheckpointResume, BlockEveryMethodIsBitwise) {
  for (BlockMethod m : {BlockMethod::hard, BlockMethod::relaxed, BlockMethod::convex}) {
    SCOPED_TRACE(to_string(m));
    expect_resume_is_bitwise(block_problem(m), mini_batch_adam(), 12, {3, 7}, 2);
  }
}

TEST(LearnCheckpointResume, BlockSgdFullBatchWithConvergenceTest) {
  TrainSettings ts;
  ts.optimizer.kind = OptimizerKind::sgd;
  ts.optimizer.learning_rate = 0.1;
  ts.patience = 3;
  ts.rel_loss_tol = 3e-4;  // converges within the cap, streaks broken and built across resumes
  ts.grad_tol = 2e-2;
  expect_resume_is_bitwise(block_problem(BlockMethod::relaxed), ts, 60, {5, 30}, 1, true);
}

TEST(LearnCheckpointResume, BlockLbfgsKeepsItsPairsAcrossResumes) {
  // L-BFGS stores its (s, y) pairs in the optimizer state: a resumed run must rebuild the
  // same quasi-Newton directions, so θ after the cap is bitwise that of one run.
  TrainSettings ts;
  ts.optimizer.kind = OptimizerKind::lbfgs;
  ts.optimizer.learning_rate = 0.1;
  ts.optimizer.memory = 3;  // pairs dropped and replaced across the resumes
  ts.patience = 0;
  expect_resume_is_bitwise(block_problem(BlockMethod::relaxed), ts, 12, {4, 9}, 1);
}

Problem polygon_problem(PolygonMethod method) {
  const PolygonModel truth = reference_polygon_model();
  PolygonDataSettings ds;
  ds.trajectories = 2;
  ds.steps = 40;
  ds.seed = 11;
  const auto data = std::make_shared<PolygonDataset>(generate_polygon_dataset(truth, ds));
  const PolygonLearnFlags flags{true, true, true, true, false};
  PolygonLossSettings ls;
  ls.method = method;
  Problem p;
  p.objective = [data, truth, ls] { return std::make_unique<PolygonObjective>(*data, truth, ls); };
  p.theta = make_polygon_parameters(perturb_polygon_model(truth, flags, 0.2, 5), flags);
  split_samples(static_cast<Index>(data->transitions.size()), 0.2, 1, p.training, p.validation);
  return p;
}

TEST(LearnCheckpointResume, PolygonHardAndRelaxedAreBitwise) {
  for (PolygonMethod m : {PolygonMethod::hard, PolygonMethod::relaxed}) {
    SCOPED_TRACE(to_string(m));
    TrainSettings ts = mini_batch_adam();
    ts.batch = 16;
    ts.optimizer.learning_rate = 0.01;
    expect_resume_is_bitwise(polygon_problem(m), ts, 5, {2}, 2);
  }
}

// Relaxed with its proximal centres, hard with its stored Lemke bases (both saved in the
// checkpoint as the scene's per-contact values).
TEST(LearnCheckpointResume, SceneRelaxedAndHardWithStoredValuesAreBitwise) {
  LearningPileOptions po;
  po.bodies = 6;
  po.classes = 2;
  SceneDatasetSettings ds;
  ds.steps = 25;
  const auto data = std::make_shared<SceneDataset>(generate_scene_dataset(make_learning_pile(po), ds));
  const auto map = std::make_shared<SceneParameterMap>(data->scene.world, SceneParameterSettings{});
  for (LossMethod method : {LossMethod::relaxed, LossMethod::hard}) {
    SCOPED_TRACE(to_string(method));
    SceneLossSettings ls;
    ls.method = method;
    Problem p;
    p.objective = [data, map, ls] { return std::make_unique<SceneObjective>(*data, *map, ls); };
    p.theta = perturb_scene_parameters(map->parameters(data->scene.world), *map, 0.2, 3);
    split_samples(static_cast<Index>(data->transitions.size()), 0.2, 1, p.training, p.validation);
    TrainSettings ts = mini_batch_adam();
    ts.batch = 8;
    ts.optimizer.learning_rate = 0.01;
    expect_resume_is_bitwise(p, ts, 4, {1, 3}, 2);
  }
}

TEST(LearnCheckpointResume, FinishedRunResumesToTheSameResult) {
  const Problem p = block_problem(BlockMethod::hard);
  TrainSettings ts = mini_batch_adam();
  ts.epochs = 6;
  ts.checkpoint = temp_file("finished.ckpt");
  ParameterSet a = p.theta, b = p.theta;
  const TrainResult done = train(*p.objective(), a, p.training, p.validation, ts);
  ts.resume = ts.checkpoint;
  const TrainResult again = train(*p.objective(), b, p.training, p.validation, ts);
  EXPECT_TRUE(same_bits(a.values(), b.values()));
  EXPECT_EQ(again.history.size(), done.history.size());
  ts.epochs = 5;  // below the epochs already done
  ParameterSet c = p.theta;
  EXPECT_THROW(train(*p.objective(), c, p.training, p.validation, ts), InputError);
  fs::remove(ts.checkpoint);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(LearnCheckpointResume, CheckpointOfAnotherRunIsRejected) {
  const Problem p = block_problem(BlockMethod::hard);
  TrainSettings ts = mini_batch_adam();
  ts.epochs = 3;
  ts.checkpoint = temp_file("other.ckpt");
  ParameterSet theta = p.theta;
  train(*p.objective(), theta, p.training, p.validation, ts);
  TrainSettings r = ts;
  r.epochs = 6;
  r.resume = ts.checkpoint;
  r.checkpoint = temp_file("other2.ckpt");
  // Another parameter count.
  ParameterSet more = block_parameters(0.6, 1.0, 1.0, true, false);
  more.add(Parameter{"extra", 1.0});
  std::string e = error_of([&] { train(*p.objective(), more, p.training, p.validation, r); });
  EXPECT_NE(e.find("belongs to another run: parameter count is '3' in the checkpoint but '4'"), std::string::npos) << e;
  // Another seed.
  TrainSettings seed = r;
  seed.seed = 10;
  theta = p.theta;
  e = error_of([&] { train(*p.objective(), theta, p.training, p.validation, seed); });
  EXPECT_NE(e.find("seed is '9' in the checkpoint but '10'"), std::string::npos) << e;
  // Another training set, another problem description.
  std::vector<Index> fewer(p.training.begin() + 1, p.training.end());
  e = error_of([&] { train(*p.objective(), theta, fewer, p.validation, r); });
  EXPECT_NE(e.find("training set"), std::string::npos) << e;
  TrainSettings other = r;
  other.problem = "--method=convex\n";
  e = error_of([&] { train(*p.objective(), theta, p.training, p.validation, other); });
  EXPECT_NE(e.find("problem (line 1) is '(nothing)' in the checkpoint but '--method=convex'"), std::string::npos) << e;
  // The objective state of another loss.
  const auto relaxed = block_problem(BlockMethod::relaxed);
  e = error_of([&] { train(*relaxed.objective(), theta, p.training, p.validation, r); });
  EXPECT_NE(e.find("objective state: holds the state of 'block hard: Lemke bases'"), std::string::npos) << e;
  fs::remove(ts.checkpoint);
  fs::remove(r.checkpoint);
}

TEST(LearnCheckpointResume, ResumedCsvLogHasEveryEpochOnce) {
  const Problem p = block_problem(BlockMethod::hard);
  TrainSettings ts = mini_batch_adam();
  ts.epochs = 3;
  ts.checkpoint = temp_file("log.ckpt");
  ts.log_csv = temp_file("log.csv");
  ParameterSet theta = p.theta;
  train(*p.objective(), theta, p.training, p.validation, ts);
  ts.epochs = 5;
  ts.resume = ts.checkpoint;
  theta = p.theta;
  train(*p.objective(), theta, p.training, p.validation, ts);
  std::ifstream in(ts.log_csv);
  std::string line;
  std::vector<std::string> epochs;
  while (std::getline(in, line)) epochs.push_back(line.substr(0, line.find(',')));
  EXPECT_EQ(epochs, (std::vector<std::string>{"epoch", "1", "2", "3", "4", "5"}));
  fs::remove(ts.checkpoint);
  fs::remove(ts.log_csv);
}

}  // namespace
}  // namespace lcprelax::learn
