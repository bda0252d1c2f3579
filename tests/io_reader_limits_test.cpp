// Reader limits (core/text_input.hpp, docs/formats.md "Limits of the readers"): every text
// reader stops at /dev/zero (NUL bytes) and at a line over 1 MiB with an InputError that
// names the file and line, echoes long tokens cut to 64 characters, skips a leading UTF-8
// BOM, rejects QPS files with NUL bytes or without variables, and rejects a header whose
// sizes the file cannot hold before allocating for them. Each test failed before issue 19.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/core/text_input.hpp>
#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/learn/block_dataset.hpp>
#include <lcprelax/scenes/scene_json.hpp>
#include <lcprelax/scenes/trajectory_csv.hpp>
#include <lcprelax/sparse/matrix_market.hpp>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

namespace lcprelax {
namespace {

namespace fs = std::filesystem;

/// The InputError message of `read` ("" if it did not throw one).
std::string error_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string write_temp(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / ("lcprelax_limits_" + name);
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

const char* kBom = "\xEF\xBB\xBF";

const std::string kQps =
    "NAME T\nROWS\n N obj\n L c1\nCOLUMNS\n    x obj 1.0 c1 1.0\n    y obj 2.0 c1 1.0\n"
    "RHS\n    rhs c1 4.0\nENDATA\n";
const std::string kLcp = "2\n0\n2\t2\n2\t2\n1 0\n0 1\n-1 -1\n";
const std::string kMtx = "%%MatrixMarket matrix coordinate real general\n2 2 1\n1 2 3.5\n";
const std::string kCsv = "step,time,body,x,y,theta,vx,vy,omega\n0,0,0,0,0.5,0,0,0,0\n";

// One call per reader of a file on disk.
const std::vector<std::pair<std::string, std::function<void(const std::string&)>>> kReaders = {
    {"qps", [](const std::string& p) { (void)io::read_qps(p); }},
    {"siconos lcp", [](const std::string& p) { (void)io::read_siconos_lcp(p); }},
    {"siconos fc2d", [](const std::string& p) { (void)io::read_siconos_fc2d(p); }},
    {"matrix market", [](const std::string& p) { (void)sparse::read_matrix_market(p); }},
    {"trajectory csv", [](const std::string& p) { (void)load_trajectory(p); }},
    {"block csv", [](const std::string& p) { (void)learn::read_block_csv(p, 1.0, 1.0); }},
    {"scene json", [](const std::string& p) { (void)load_scene(p); }},
};

TEST(ReaderLimits, DevZeroFailsFastInEveryReader) {
  if (!fs::exists("/dev/zero")) GTEST_SKIP() << "no /dev/zero";
  for (const auto& reader : kReaders) {
    const auto& read = reader.second;  // a named reference: a lambda may capture it (not a binding)
    SCOPED_TRACE(reader.first);
    const auto start = std::chrono::steady_clock::now();
    const std::string message = error_of([&] { read("/dev/zero"); });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_NE(message.find("/dev/zero"), std::string::npos) << message;
    EXPECT_LT(seconds, 5.0);
    EXPECT_LT(message.size(), 400u) << message;
  }
}

TEST(ReaderLimits, LineLongerThanOneMebibyteIsAnError) {
  const std::string line(text::kMaxLineBytes + 10, 'a');
  for (const auto& reader : kReaders) {
    const auto& read = reader.second;
    if (reader.first == "scene json") continue;  // not line based: its limit is the file size
    SCOPED_TRACE(reader.first);
    const std::string path = write_temp("long_line", line + "\n");
    const std::string message = error_of([&] { read(path); });
    EXPECT_NE(message.find(path + ":1: line longer than 1048576 bytes"), std::string::npos) << message;
  }
}

TEST(ReaderLimits, LongTokensAreCutInMessages) {
  const std::string token(500000, 'Z');
  const std::vector<std::pair<std::string, std::string>> inputs = {
      {"qps", token + "\n"},
      {"siconos lcp", token + "\n"},
      {"siconos fc2d", "2 " + token + "\n"},
      {"matrix market", "%%MatrixMarket matrix " + token + " real general\n"},
      {"trajectory csv", "step,time,body," + token + "\n"},
      {"block csv", "v,u," + token + "\n"},
      {"scene json", "{\"" + token + "\": 1}"},
  };
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    SCOPED_TRACE(inputs[i].first);
    ASSERT_EQ(inputs[i].first, kReaders[i].first);
    const std::string path = write_temp("long_token", inputs[i].second);
    const std::string message = error_of([&] { kReaders[i].second(path); });
    EXPECT_NE(message.find(std::string(64, 'Z') + "..."), std::string::npos) << message.substr(0, 300);
    EXPECT_LT(message.size(), 400u);
  }
  const std::string model = error_of([&] { (void)parse_scene("{\"model\": \"" + token + "\"}"); });
  EXPECT_NE(model.find("model: unknown contact model 'ZZZZ"), std::string::npos) << model.substr(0, 300);
  EXPECT_LT(model.size(), 400u);
}

TEST(ReaderLimits, QpsWithNulBytesIsRejectedNamingLineAndColumn) {
  std::string text = kQps;
  text.insert(text.find("x obj") + 2, std::string(1, '\0'));
  std::istringstream in(text);
  const std::string message = error_of([&] { (void)io::parse_qps(in, "nul.qps"); });
  EXPECT_NE(message.find("nul.qps:6: NUL byte in column 7"), std::string::npos) << message;
}

TEST(ReaderLimits, QpsWithoutVariablesIsRejected) {
  for (const std::string& text : {std::string("NAME EMPTY\nROWS\n N obj\nCOLUMNS\nENDATA\n"),
                                  std::string("NAME EMPTY\nENDATA\n")}) {
    std::istringstream in(text);
    const std::string message = error_of([&] { (void)io::parse_qps(in, "empty.qps"); });
    EXPECT_NE(message.find("empty.qps:"), std::string::npos) << message;
    EXPECT_NE(message.find("no variables"), std::string::npos) << message;
  }
}

TEST(ReaderLimits, LeadingUtf8BomIsSkippedByEveryReader) {
  EXPECT_EQ(io::read_qps(write_temp("bom.qps", kBom + kQps)).problem.num_variables(), 2);
  EXPECT_EQ(io::read_siconos_lcp(write_temp("bom.dat", kBom + kLcp)).q.size(), 2);
  EXPECT_EQ(sparse::read_matrix_market(write_temp("bom.mtx", kBom + kMtx)).nonZeros(), 1);
  EXPECT_EQ(load_trajectory(write_temp("bom.csv", kBom + kCsv)).size(), 1u);
  const std::string block = write_temp("bom_block.csv", kBom + std::string("v,v_next,u\n0.5,0.1,0\n"));
  EXPECT_EQ(learn::read_block_csv(block, 1.0, 1.0).samples.size(), 1u);
  EXPECT_EQ(load_scene(write_temp("bom.json", kBom + std::string("{\"steps\": 3}"))).steps, 3);
}

TEST(ReaderLimits, SiconosHeaderLargerThanTheFileIsRejectedAtTheHeader) {
  const std::string huge = error_of([] { (void)io::read_siconos_lcp(write_temp("n12.dat", "1000000000000\n0\n")); });
  EXPECT_NE(huge.find(":1: LCP size n 1000000000000 out of range"), std::string::npos) << huge;
  const std::string path = write_temp("n9.dat", "1000000000\n1\n1000000000 1000000000\n0\n1 2 3\n");
  const std::string big = error_of([&] { (void)io::read_siconos_lcp(path); });
  EXPECT_NE(big.find(path + ":1: LCP size n = 1000000000: q needs 1000000000 values, more than the"),
            std::string::npos) << big;
  // n values of q fit in the file (padding), n² dense entries do not.
  const std::string dense_text = "30000\n0\n30000 30000\n30000 30000\n1 2\n" + std::string(70000, ' ');
  const std::string dense = error_of([&] { (void)io::read_siconos_lcp(write_temp("dense.dat", dense_text)); });
  EXPECT_NE(dense.find(":4: the dense 30000x30000 matrix needs 900000000 values"), std::string::npos) << dense;
  const std::string fc2d = error_of([] { (void)io::read_siconos_fc2d(write_temp("fc.dat", "2\n300000000\n0\n")); });
  EXPECT_NE(fc2d.find("number of contacts 300000000: q and mu needs 900000000 values"), std::string::npos) << fc2d;
}

TEST(ReaderLimits, MatrixMarketSizesAreCheckedBeforeAllocation) {
  const std::string wide = error_of([] {
    (void)sparse::read_matrix_market(write_temp("wide.mtx", "%%MatrixMarket matrix coordinate real general\n2147483647 2147483647 0\n"));
  });
  EXPECT_NE(wide.find(":2: matrix size 2147483647x2147483647 exceeds the limit 1048576"), std::string::npos) << wide;
  const std::string count = error_of([] {
    (void)sparse::read_matrix_market(write_temp("count.mtx", "%%MatrixMarket matrix coordinate real general\n1000 1000 900000\n1 1 1\n"));
  });
  EXPECT_NE(count.find(":2: entry count 900000 is more than the"), std::string::npos) << count;
  // A stream of unknown size: the dimension is checked against the bytes read.
  std::istringstream pipe("%%MatrixMarket matrix array real general\n2000000 0\n");
  const std::string streamed = error_of([&] { (void)sparse::parse_matrix_market_vector(pipe, "pipe"); });
  EXPECT_NE(streamed.find("pipe:2: matrix size 2000000x0 exceeds the limit 1048576"), std::string::npos) << streamed;
  // An empty matrix within the limit still reads.
  std::istringstream small("%%MatrixMarket matrix coordinate real general\n1000 1000 0\n");
  EXPECT_EQ(sparse::parse_matrix_market(small, "small").rows(), 1000);
}

TEST(ReaderLimits, CheckedArithmeticDetectsOverflow) {
  std::uint64_t r = 7;
  EXPECT_FALSE(text::checked_mul(std::uint64_t{1} << 33, std::uint64_t{1} << 31, r));
  EXPECT_EQ(r, 7u);
  EXPECT_TRUE(text::checked_mul(2147483647, 2147483647, r));
  EXPECT_EQ(r, 4611686014132420609u);
  EXPECT_FALSE(text::checked_add(~std::uint64_t{0}, 1, r));
  EXPECT_FALSE(text::values_fit(~std::uint64_t{0}, 100));
  EXPECT_TRUE(text::values_fit(50, 99));
  EXPECT_FALSE(text::values_fit(50, 98));
  EXPECT_EQ(text::quote(std::string("a\0b", 3)), "'a\\x00b'");
}

}  // namespace
}  // namespace lcprelax
