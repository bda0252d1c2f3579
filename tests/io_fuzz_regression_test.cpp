// Regression inputs of the fuzz findings (tests/fuzz/README.md): every file directly under
// tests/data/fuzz/ is read by the reader its name selects and must give a clean
// lcprelax::InputError naming the file and a line (not a crash, not another exception, not
// a large allocation). The prefix picks the reader: qps_*.qps (QPS), qpsolve_*.qps (QPS, then
// QpSolver: an InputError or any status, but `solved` only with finite numbers), lcp_*.dat
// and fc2d_*.dat (Siconos), mtx_*.mtx (Matrix Market, as a matrix and as a vector),
// scene_*.json (scene JSON), trajectory_*.csv (trajectory CSV). Seeds of the fuzz corpora
// (tests/data/fuzz/seeds/) are read and must succeed.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/scenes/scene_json.hpp>
#include <lcprelax/scenes/trajectory_csv.hpp>
#include <lcprelax/sparse/matrix_market.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>

namespace lcprelax {
namespace {

namespace fs = std::filesystem;
const std::string kFuzzData = std::string(LCPRELAX_TEST_DATA_DIR) + "/fuzz";

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

/// The reader for a file name, or nullptr when the name matches no prefix.
std::function<void(const std::string&)> reader_for(const std::string& name) {
  if (starts_with(name, "qps_")) return [](const std::string& p) { (void)io::read_qps(p); };
  if (starts_with(name, "qpsolve_"))
    return [](const std::string& p) {
      QpSettings s;
      s.max_iter = 15;
      QpSolver solver(s);
      solver.setup(io::read_qps(p).problem);
      const QpResult& r = solver.solve();
      if (r.info.status == QpStatus::solved && !(r.x.allFinite() && r.y.allFinite() && r.z.allFinite()))
        ADD_FAILURE() << p << ": solved with non-finite numbers";
    };
  if (starts_with(name, "lcp_")) return [](const std::string& p) { (void)io::read_siconos_lcp(p); };
  if (starts_with(name, "fc2d_")) return [](const std::string& p) { (void)io::read_siconos_fc2d(p); };
  if (starts_with(name, "mtx_"))
    return [](const std::string& p) {
      try {
        (void)sparse::read_matrix_market(p);
      } catch (const InputError&) {
      }
      (void)sparse::read_matrix_market_vector(p);
    };
  if (starts_with(name, "scene_")) return [](const std::string& p) { (void)load_scene(p); };
  if (starts_with(name, "trajectory_")) return [](const std::string& p) { (void)load_trajectory(p); };
  return nullptr;
}

std::vector<fs::path> files_in(const std::string& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != "README.md") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(FuzzRegression, EveryRegressionInputGivesACleanInputError) {
  int checked = 0;
  for (const fs::path& path : files_in(kFuzzData)) {
    const std::string name = path.filename().string();
    SCOPED_TRACE(name);
    const auto read = reader_for(name);
    ASSERT_TRUE(read) << "no reader for " << name << " (see the prefixes in this test)";
    try {
      read(path.string());
      // QpSolver inputs may be valid problems: only a crash or a lie is a failure there.
      if (!starts_with(name, "qpsolve_")) ADD_FAILURE() << name << " read without an error";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.string() + ":"), std::string::npos) << message;
      EXPECT_LT(message.size(), 2048u);
    } catch (const std::exception& e) {
      ADD_FAILURE() << name << ": unexpected exception " << e.what();
    }
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

TEST(FuzzRegression, SeedFilesRead) {
  for (const fs::path& path : files_in(kFuzzData + "/seeds")) {
    SCOPED_TRACE(path.string());
    if (path.extension() == ".mtx") {
      EXPECT_NO_THROW((void)sparse::read_matrix_market(path.string()));
    }
    if (path.extension() == ".csv") {
      EXPECT_FALSE(load_trajectory(path.string()).empty());
    }
  }
}

}  // namespace
}  // namespace lcprelax
