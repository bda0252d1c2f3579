// Mutation test of the readers (issue 19): real files from tests/data (QPS, Siconos LCP and
// fc2d .dat, Matrix Market, scene JSON, trajectory and block CSV) are mutated by byte flips,
// byte overwrites, truncations, duplicated and deleted lines, seeded, and every mutant must
// either read or throw lcprelax::InputError with a non-empty message under 2 KiB; any other
// exception fails the test, a crash ends it. QPS mutants that read and are small are also
// solved (15 iterations): a `solved` status must come with finite numbers. Runs in a few
// seconds (Release).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/learn/block_dataset.hpp>
#include <lcprelax/scenes/scene_json.hpp>
#include <lcprelax/scenes/trajectory_csv.hpp>
#include <lcprelax/sparse/matrix_market.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

namespace lcprelax {
namespace {

namespace fs = std::filesystem;
const std::string kData = LCPRELAX_TEST_DATA_DIR;
constexpr int kMutantsPerFile = 400;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// One random mutation of `text`.
std::string mutate(const std::string& text, std::mt19937& rng) {
  std::string t = text;
  auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  if (t.empty()) return t;
  // Line starts, for the line mutations.
  std::vector<std::size_t> starts{0};
  for (std::size_t i = 0; i + 1 < t.size(); ++i)
    if (t[i] == '\n') starts.push_back(i + 1);
  const std::size_t line = pick(starts.size());
  const std::size_t begin = starts[line];
  const std::size_t end = line + 1 < starts.size() ? starts[line + 1] : t.size();
  switch (pick(6)) {
    case 0: {  // flip a few bits
      for (int k = 0, n = 1 + static_cast<int>(pick(4)); k < n; ++k) t[pick(t.size())] ^= static_cast<char>(1u << pick(8));
      break;
    }
    case 1: {  // overwrite a byte with an interesting one
      static const char interesting[] = {'\0', '\n', ' ', '-', '9', 'e', '.', ',', '"', '[', '{', '\xEF', '\xFF'};
      t[pick(t.size())] = interesting[pick(sizeof interesting)];
      break;
    }
    case 2: t.resize(pick(t.size())); break;                                   // truncate
    case 3: t.insert(begin, t.substr(begin, end - begin)); break;              // duplicate a line
    case 4: t.erase(begin, end - begin); break;                                // delete a line
    default: {  // replace a number-like character run by an extreme value
      static const char* values[] = {"1e308", "-1e999", "nan", "2147483648", "-1", "0", "99999999999999999999"};
      const std::size_t at = pick(t.size());
      t.replace(at, std::min<std::size_t>(pick(8), t.size() - at), values[pick(7)]);
    }
  }
  return t;
}

using Reader = std::function<void(const std::string& text)>;

void solve_if_small(const QpProblem& p) {
  if (p.num_variables() > 60 || p.G.rows() > 60) return;
  QpSettings s;
  s.max_iter = 15;
  QpSolver solver(s);
  try {
    solver.setup(p);
  } catch (const InputError&) {
    return;
  }
  const QpResult& r = solver.solve();
  if (r.info.status == QpStatus::solved) {
    EXPECT_TRUE(r.x.allFinite() && r.y.allFinite() && r.z.allFinite()) << "solved with non-finite numbers";
  }
}

const Reader kQps = [](const std::string& t) {
  std::istringstream in(t);
  solve_if_small(io::parse_qps(in, "mutant.qps").problem);
};
const Reader kLcp = [](const std::string& t) {
  std::istringstream in(t);
  (void)io::parse_siconos_lcp(in, "mutant.dat", t.size());
};
const Reader kFc2d = [](const std::string& t) {
  std::istringstream in(t);
  (void)io::parse_siconos_fc2d(in, "mutant.dat", t.size());
};
const Reader kMtx = [](const std::string& t) {
  std::istringstream in(t);
  (void)sparse::parse_matrix_market(in, "mutant.mtx", t.size());
};
const Reader kScene = [](const std::string& t) { (void)parse_scene(t); };
const Reader kTrajectory = [](const std::string& t) {
  std::istringstream in(t);
  (void)read_trajectory(in, "mutant.csv");
};
const Reader kBlock = [](const std::string& t) {
  const fs::path path = fs::temp_directory_path() / "lcprelax_mutant_block.csv";
  std::ofstream(path, std::ios::binary) << t;
  (void)learn::read_block_csv(path.string(), 1.0, 1.0);
};

struct Case {
  std::string file;  // under tests/data
  Reader read;
};

const std::vector<Case> kCases = {
    {"qps/ranges.qps", kQps},
    {"qps/bounds.qps", kQps},
    {"qps/qmatrix.qps", kQps},
    {"maros_meszaros/HS21.qps", kQps},
    {"maros_meszaros/QAFIRO.qps", kQps},
    {"siconos/lcp/lcp_CPS_1.dat", kLcp},
    {"siconos/lcp/lcp_ortiz.dat", kLcp},
    {"siconos/handmade/lcp_sparse_block.dat", kLcp},
    {"siconos/handmade/lcp_csparse_csc.dat", kLcp},
    {"siconos/handmade/lcp_csparse_triplet.dat", kLcp},
    {"siconos/handmade/fc2d_sparse_block.dat", kFc2d},
    {"siconos/fc2d/FC2D_SliderCrankLagrangian00000.dat", kFc2d},
    {"fuzz/seeds/coordinate_symmetric.mtx", kMtx},
    {"fuzz/seeds/array_vector.mtx", kMtx},
    {"scenes/box_on_ground.json", kScene},
    {"scenes/box_stack.json", kScene},
    {"fuzz/seeds/trajectory_forces.csv", kTrajectory},
    {"block/good.csv", kBlock},
};

TEST(ReaderMutation, EveryMutantReadsOrThrowsInputError) {
  std::mt19937 rng(20240519);
  int mutants = 0, errors = 0;
  for (const Case& c : kCases) {
    const std::string original = slurp(kData + "/" + c.file);
    ASSERT_FALSE(original.empty()) << c.file;
    ASSERT_NO_THROW(c.read(original)) << c.file;  // the unmutated file reads
    for (int k = 0; k < kMutantsPerFile; ++k) {
      const std::string mutant = mutate(original, rng);
      ++mutants;
      try {
        c.read(mutant);
      } catch (const InputError& e) {
        ++errors;
        const std::string message = e.what();
        EXPECT_FALSE(message.empty()) << c.file << " mutant " << k;
        EXPECT_LT(message.size(), 2048u) << c.file << " mutant " << k;
      } catch (const std::exception& e) {
        ADD_FAILURE() << c.file << " mutant " << k << ": unexpected exception: " << e.what();
      }
    }
  }
  EXPECT_EQ(mutants, static_cast<int>(kCases.size()) * kMutantsPerFile);
  EXPECT_GT(errors, mutants / 4);  // the mutations do break files
}

}  // namespace
}  // namespace lcprelax
