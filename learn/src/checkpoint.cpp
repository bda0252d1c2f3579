// Training checkpoints: identity, binary encoding with version and checksum, atomic files
// (checkpoint.hpp).
#include <lcprelax/learn/checkpoint.hpp>
#include <lcprelax/learn/state_stream.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include <lcprelax/core/atomic_file.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace lcprelax::learn {

namespace {

constexpr char kMagic[8] = {'L', 'C', 'P', 'R', 'C', 'K', 'P', 'T'};
constexpr std::uint64_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 8 + 8 + 8, kChecksumBytes = 8;

std::uint64_t fnv1a(const char* data, std::size_t n, std::uint64_t h = 0xcbf29ce484222325ull) {
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 0x100000001b3ull;
  }
  return h;
}

std::string hex_double(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%a", v);
  return b;
}

std::string describe_samples(const std::vector<Index>& s) {
  StateWriter w;
  w.put_indices(s);
  char b[64];
  std::snprintf(b, sizeof b, " (FNV-1a %016llx)", static_cast<unsigned long long>(fnv1a(w.bytes().data(), w.bytes().size())));
  return std::to_string(s.size()) + " samples" + b;
}

void put_record(StateWriter& w, const EpochRecord& r) {
  w.put_i64(r.epoch);
  for (double x : {r.loss, r.validation_loss, r.gradient_norm, r.seconds, r.samples_per_second, r.full_loss,
                   r.full_gradient_norm, r.relative_loss_change})
    w.put_double(x);
  w.put_vector(r.theta);
  w.put_i64(r.failed);
  w.put_i64(r.streak);
}

EpochRecord get_record(StateReader& in) {
  EpochRecord r;
  r.epoch = static_cast<int>(in.get_int(1, std::numeric_limits<int>::max(), "history epoch"));
  for (double* x : {&r.loss, &r.validation_loss, &r.gradient_norm, &r.seconds, &r.samples_per_second, &r.full_loss,
                    &r.full_gradient_norm, &r.relative_loss_change})
    *x = in.get_double();
  r.theta = in.get_vector();
  r.failed = static_cast<int>(in.get_int(0, std::numeric_limits<int>::max(), "history failed"));
  r.streak = static_cast<int>(in.get_int(0, std::numeric_limits<int>::max(), "history streak"));
  return r;
}

// First line in which a and b differ (1-based), or 0.
std::size_t first_differing_line(const std::string& a, const std::string& b, std::string& la, std::string& lb) {
  std::istringstream sa(a), sb(b);
  for (std::size_t line = 1;; ++line) {
    const bool ga = static_cast<bool>(std::getline(sa, la)), gb = static_cast<bool>(std::getline(sb, lb));
    if (!ga) la = "(nothing)";
    if (!gb) lb = "(nothing)";
    if (!ga && !gb) return 0;
    if (!ga || !gb || la != lb) return line;
  }
}

}  // namespace

CheckpointIdentity checkpoint_identity(const Objective& objective, const ParameterSet& theta,
                                       const std::vector<Index>& training, const std::vector<Index>& validation,
                                       const TrainSettings& settings) {
  CheckpointIdentity id;
  id.emplace_back("problem", settings.problem);
  id.emplace_back("number of samples", std::to_string(objective.num_samples()));
  id.emplace_back("parameter count", std::to_string(theta.size()));
  std::string params;
  for (Index i = 0; i < theta.size(); ++i) {
    const Parameter& p = theta[i];
    params += p.name + (p.transform == Transform::log ? " log" : " identity") + " [" + hex_double(p.lower) + ", " +
              hex_double(p.upper) + "] scale " + hex_double(p.scale) + (p.learn ? " learned" : " fixed") + "\n";
  }
  id.emplace_back("parameters", params);
  id.emplace_back("training set", describe_samples(training));
  id.emplace_back("validation set", describe_samples(validation));
  id.emplace_back("batch", std::to_string(settings.batch));
  id.emplace_back("shuffle", settings.shuffle ? "on" : "off");
  id.emplace_back("seed", std::to_string(settings.seed));
  const OptimizerSettings& o = settings.optimizer;
  id.emplace_back("optimizer", std::string(to_string(o.kind)) + " learning_rate " + hex_double(o.learning_rate) +
                                   " momentum " + hex_double(o.momentum) + " beta1 " + hex_double(o.beta1) + " beta2 " +
                                   hex_double(o.beta2) + " epsilon " + hex_double(o.epsilon) + " decay " +
                                   hex_double(o.decay) + " clip_norm " + hex_double(o.clip_norm) +
                                   (o.kind == OptimizerKind::lbfgs ? " memory " + std::to_string(o.memory) : "") +
                                   (o.kind == OptimizerKind::lm && o.lm_geodesic_acceleration ? " geodesic" : ""));
  id.emplace_back("convergence test", "rel_loss_tol " + hex_double(settings.rel_loss_tol) + " grad_tol " +
                                          hex_double(settings.grad_tol) + " patience " + std::to_string(settings.patience));
  id.emplace_back("MPI ranks", std::to_string(settings.distributed ? mpi::mpi_size() : 1));
  return id;
}

void check_checkpoint_identity(const CheckpointIdentity& stored, const CheckpointIdentity& current,
                               const std::string& path) {
  const std::string head = "checkpoint '" + path + "' belongs to another run: ";
  for (std::size_t k = 0; k < current.size(); ++k) {
    const std::string& field = current[k].first;
    if (k >= stored.size() || stored[k].first != field)
      throw InputError(head + "it does not record '" + field + "' (written by another version of lcprelax?)");
    std::string was, now;
    const std::size_t line = first_differing_line(stored[k].second, current[k].second, was, now);
    if (line == 0) continue;
    const bool multi = stored[k].second.find('\n') != std::string::npos || current[k].second.find('\n') != std::string::npos;
    throw InputError(head + field + (multi ? " (line " + std::to_string(line) + ")" : std::string()) + " is '" + was +
                     "' in the checkpoint but '" + now + "' in this run");
  }
  if (stored.size() != current.size()) throw InputError(head + "it records other fields (another version of lcprelax?)");
}

std::string encode_checkpoint(const TrainCheckpoint& c) {
  StateWriter w;
  w.put_u64(c.identity.size());
  for (const auto& [field, value] : c.identity) {
    w.put_string(field);
    w.put_string(value);
  }
  w.put_i64(c.epoch);
  w.put_bool(c.converged);
  w.put_i64(c.streak);
  w.put_double(c.previous_full_loss);
  w.put_i64(c.evaluated_total);
  w.put_i64(c.failed);
  w.put_string(c.first_failure);
  w.put_vector(c.theta);
  w.put_vector(c.optimizer.m);
  w.put_vector(c.optimizer.s);
  w.put_i64(c.optimizer.steps);
  w.put_string(c.rng);
  w.put_indices(c.order);
  w.put_u64(c.history.size());
  for (const EpochRecord& r : c.history) put_record(w, r);
  w.put_string(c.objective_state);

  StateWriter file;
  const std::string& payload = w.bytes();
  std::string bytes(kMagic, sizeof kMagic);
  file.put_u64(kVersion);
  file.put_u64(payload.size());
  bytes += file.bytes();
  bytes += payload;
  StateWriter sum;
  sum.put_u64(fnv1a(bytes.data(), bytes.size()));
  bytes += sum.bytes();
  return bytes;
}

TrainCheckpoint decode_checkpoint(const std::string& bytes, const std::string& path) {
  const std::string name = "checkpoint '" + path + "'";
  if (bytes.size() < sizeof kMagic || bytes.compare(0, sizeof kMagic, kMagic, sizeof kMagic) != 0)
    throw InputError(name + ": not an lcprelax training checkpoint (no LCPRCKPT header)");
  if (bytes.size() < kHeaderBytes + kChecksumBytes)
    throw InputError(name + ": truncated (" + std::to_string(bytes.size()) + " bytes)");
  const std::string header = bytes.substr(sizeof kMagic, 16);
  StateReader h(header, name);
  const std::uint64_t version = h.get_u64(), length = h.get_u64();
  if (version != kVersion)
    throw InputError(name + ": format version " + std::to_string(version) + ", this lcprelax reads version " +
                     std::to_string(kVersion));
  if (length != bytes.size() - kHeaderBytes - kChecksumBytes)
    throw InputError(name + ": truncated or extended: the header announces " + std::to_string(length) +
                     " payload bytes, the file holds " + std::to_string(bytes.size() - kHeaderBytes - kChecksumBytes));
  const std::string tail = bytes.substr(bytes.size() - kChecksumBytes);
  StateReader t(tail, name);
  if (t.get_u64() != fnv1a(bytes.data(), bytes.size() - kChecksumBytes))
    throw InputError(name + ": checksum mismatch (the file is corrupt)");

  const std::string payload = bytes.substr(kHeaderBytes, static_cast<std::size_t>(length));
  StateReader in(payload, name);
  TrainCheckpoint c;
  const std::uint64_t fields = in.get_u64();
  if (fields > 1000) in.fail("implausible identity of " + std::to_string(fields) + " fields");
  for (std::uint64_t k = 0; k < fields; ++k) {
    std::string field = in.get_string();
    c.identity.emplace_back(std::move(field), in.get_string());
  }
  const int int_max = std::numeric_limits<int>::max();
  c.epoch = static_cast<int>(in.get_int(0, int_max, "epoch"));
  c.converged = in.get_bool();
  c.streak = static_cast<int>(in.get_int(0, int_max, "streak"));
  c.previous_full_loss = in.get_double();
  c.evaluated_total = static_cast<long>(in.get_int(0, std::numeric_limits<long>::max(), "evaluated samples"));
  c.failed = static_cast<int>(in.get_int(0, int_max, "failed"));
  c.first_failure = in.get_string();
  c.theta = in.get_vector();
  c.optimizer.m = in.get_vector();
  c.optimizer.s = in.get_vector();
  c.optimizer.steps = static_cast<long>(in.get_int(0, std::numeric_limits<long>::max(), "optimizer steps"));
  c.rng = in.get_string();
  c.order = in.get_indices();
  const std::uint64_t records = in.get_u64();
  if (records != static_cast<std::uint64_t>(c.epoch))
    in.fail("the history holds " + std::to_string(records) + " epochs, the checkpoint says " + std::to_string(c.epoch));
  for (std::uint64_t k = 0; k < records; ++k) {
    c.history.push_back(get_record(in));
    if (c.history.back().epoch != static_cast<int>(k + 1)) in.fail("history out of order at record " + std::to_string(k + 1));
  }
  c.objective_state = in.get_string();
  in.expect_end();
  if (!c.theta.allFinite()) in.fail("a parameter value is not finite");
  // sgd/adam: one moment entry per parameter; lbfgs: the stored pairs, a multiple of it;
  // lm: the damping (λ, ν), 2 entries (Optimizer::restore checks them against the kind).
  const Index moments = c.optimizer.m.size();
  if (moments != c.optimizer.s.size() ||
      (moments != 0 && moments != 2 && (c.theta.size() == 0 || moments % c.theta.size() != 0)))
    in.fail("optimizer moments of " + std::to_string(c.optimizer.m.size()) + " and " +
            std::to_string(c.optimizer.s.size()) + " entries for " + std::to_string(c.theta.size()) + " parameters");
  return c;
}

void write_checkpoint(const std::string& path, const TrainCheckpoint& checkpoint) {
  write_file_atomically(path, encode_checkpoint(checkpoint));
}

TrainCheckpoint read_checkpoint(const std::string& path) {
  std::string bytes;
  try {
    bytes = read_whole_file(path);
  } catch (const InputError& e) {
    throw InputError(std::string("checkpoint: ") + e.what());  // "checkpoint: cannot read 'PATH': ..."
  }
  return decode_checkpoint(bytes, path);
}

void check_checkpoint_writable(const std::string& path) {
  try {
    check_writable(path);
  } catch (const InputError& e) {
    throw InputError(std::string("checkpoint: ") + e.what());
  }
}

std::string checkpoint_path_for_rank(const std::string& path, int rank) {
  return rank == 0 ? path : path + ".rank" + std::to_string(rank);
}

}  // namespace lcprelax::learn
