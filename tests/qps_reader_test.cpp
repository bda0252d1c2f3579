// QPS reader: every shared Maros–Meszaros file parses into a consistent problem of the
// right size; small hand-written files check RANGES, BOUNDS, QUADOBJ vs QMATRIX and the
// objective constant; malformed files give InputError "FILE:LINE: ..." at the right line.
#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

namespace lcprelax::io {
namespace {

namespace fs = std::filesystem;
constexpr double kInf = std::numeric_limits<double>::infinity();
const std::string kData = LCPRELAX_TEST_DATA_DIR;

Vector vec2(double a, double b) { return Vector(Eigen::Vector2d(a, b)); }

/// ½xᵀPx + qᵀx + r by hand from the upper triangle: xᵀPx = Σ_diag p x_i² + 2 Σ_offdiag p x_i x_j.
double objective_by_hand(const QpProblem& p, const Vector& x) {
  double quad = 0.0;
  for (int k = 0; k < p.P.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(p.P, k); it; ++it)
      quad += (it.row() == it.col() ? 1.0 : 2.0) * it.value() * x[it.row()] * x[it.col()];
  return 0.5 * quad + p.q.dot(x) + p.r;
}

/// Non-N rows in the ROWS section, counted independently of the reader.
long count_constraint_rows(const std::string& path) {
  std::ifstream in(path);
  std::string line, section;
  long m = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '*') continue;
    if (line[0] != ' ' && line[0] != '\t') { section = line.substr(0, line.find(' ')); continue; }
    std::istringstream s(line);
    std::string type;
    s >> type;
    if (section == "ROWS" && type != "N") ++m;
  }
  return m;
}

TEST(QpsReader, EveryMarosMeszarosFileParses) {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(kData + "/maros_meszaros")) {
    if (entry.path().extension() != ".qps") continue;
    ++files;
    const std::string path = entry.path().string();
    SCOPED_TRACE(path);
    const QpsModel m = read_qps(path);
    const QpProblem& p = m.problem;
    const Index n = p.num_variables();
    EXPECT_EQ(m.name, entry.path().stem().string());
    EXPECT_GT(n, 0);
    EXPECT_EQ(static_cast<Index>(m.variable_names.size()), n);
    EXPECT_EQ(std::set<std::string>(m.variable_names.begin(), m.variable_names.end()).size(), m.variable_names.size());
    EXPECT_EQ(p.num_inequalities(), count_constraint_rows(path));
    EXPECT_EQ(static_cast<Index>(m.row_names.size()), p.num_inequalities());
    EXPECT_EQ(p.num_equalities(), 0);
    EXPECT_EQ(p.G.cols(), n);
    EXPECT_GT(p.P.nonZeros(), 0) << "every Maros–Meszaros problem has a quadratic term";
    EXPECT_EQ(p.validation_error(), "");  // sizes, NaN, l ≤ u, P upper triangular
  }
  EXPECT_EQ(files, 34);
}

TEST(QpsReader, KnownSizes) {
  struct Size { const char* name; Index n, m; };
  for (const Size& s : {Size{"HS21", 2, 1}, Size{"HS118", 15, 17}, Size{"QAFIRO", 32, 27}, Size{"CVXQP1_S", 100, 50},
                        Size{"DUALC1", 9, 215}, Size{"QRECIPE", 180, 91}, Size{"GENHS28", 10, 8}, Size{"AUG2D", 20200, 10000}}) {
    const QpsModel m = read_qps(kData + "/maros_meszaros/" + s.name + ".qps");
    EXPECT_EQ(m.problem.num_variables(), s.n) << s.name;
    EXPECT_EQ(m.problem.num_inequalities(), s.m) << s.name;
  }
}

TEST(QpsReader, Hs21Data) {
  // min 0.01 x0² + x1² − 100  s.t. 10 x0 − x1 ≥ 10, 2 ≤ x0 ≤ 50, −50 ≤ x1 ≤ 50; optimum (2, 0).
  const QpsModel m = read_qps(kData + "/maros_meszaros/HS21.qps");
  const QpProblem& p = m.problem;
  EXPECT_EQ(m.objective_name, "obj");
  EXPECT_EQ(m.variable_names, (std::vector<std::string>{"x0", "x1"}));
  EXPECT_EQ(m.row_names, (std::vector<std::string>{"r0"}));
  EXPECT_EQ(p.P.nonZeros(), 2);
  EXPECT_DOUBLE_EQ(p.P.coeff(0, 0), 0.02);
  EXPECT_DOUBLE_EQ(p.P.coeff(1, 1), 2.0);
  EXPECT_EQ(p.q, Vector::Zero(2));
  EXPECT_DOUBLE_EQ(p.r, -100.0);
  EXPECT_DOUBLE_EQ(p.G.coeff(0, 0), 10.0);
  EXPECT_DOUBLE_EQ(p.G.coeff(0, 1), -1.0);
  EXPECT_DOUBLE_EQ(p.l[0], 10.0);
  EXPECT_EQ(p.u[0], kInf);
  EXPECT_EQ(p.xl, vec2(2.0, -50.0));
  EXPECT_EQ(p.xu, vec2(50.0, 50.0));
  const Vector x = vec2(2.0, 0.0);
  EXPECT_NEAR(objective_by_hand(p, x), -99.96, 1e-12);
  EXPECT_NEAR(p.objective(x), -99.96, 1e-12);
}

TEST(QpsReader, RangesOnEveryRowType) {
  const QpsModel m = read_qps(kData + "/qps/ranges.qps");
  const QpProblem& p = m.problem;
  EXPECT_EQ(m.row_names, (std::vector<std::string>{"e_pos", "e_neg", "e_zero", "l_row", "g_row", "g_plain"}));
  EXPECT_EQ(m.objective_name, "cost");
  const std::vector<double> l = {1.0, -1.0, 3.0, 2.5, 5.0, 6.0};
  const std::vector<double> u = {3.0, 2.0, 3.0, 4.0, 7.5, kInf};
  ASSERT_EQ(p.l.size(), 6);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(p.l[i], l[i]) << m.row_names[i];
    EXPECT_EQ(p.u[i], u[i]) << m.row_names[i];
  }
  EXPECT_DOUBLE_EQ(p.r, 3.5);            // objective RHS −3.5 is −r
  EXPECT_EQ(p.q, vec2(1.0, 2.0));  // the dropped N row "extra" does not enter q
  EXPECT_EQ(p.G.nonZeros(), 7);
  EXPECT_EQ(p.P.nonZeros(), 0);
  EXPECT_EQ(p.xl, Vector::Zero(2));      // default bounds [0, +∞)
  EXPECT_EQ(p.xu, Vector::Constant(2, kInf));
}

TEST(QpsReader, EveryBoundType) {
  const QpsModel m = read_qps(kData + "/qps/bounds.qps");
  const std::vector<double> lo = {-1.5, 0, 2.5, -kInf, -kInf, -kInf, -kInf, 0, -kInf, -5, -4, 0, 0, 0};
  const std::vector<double> up = {kInf, 4, 2.5, kInf, kInf, kInf, 3, kInf, -2, -2, -2, 0, kInf, kInf};
  ASSERT_EQ(m.problem.num_variables(), 14);
  for (int j = 0; j < 14; ++j) {
    EXPECT_EQ(m.problem.xl[j], lo[j]) << m.variable_names[j];
    EXPECT_EQ(m.problem.xu[j], up[j]) << m.variable_names[j];
  }
}

TEST(QpsReader, QuadobjAndQmatrixAgree) {
  const QpsModel a = read_qps(kData + "/qps/quadobj.qps");
  const QpsModel b = read_qps(kData + "/qps/qmatrix.qps");
  DenseMatrix expected(3, 3);
  expected << 4, 1, -0.5, 0, 3, 0, 0, 0, 2;  // upper triangle
  EXPECT_EQ(DenseMatrix(a.problem.P), expected);
  EXPECT_EQ(DenseMatrix(b.problem.P), expected);
  EXPECT_EQ(a.problem.P.nonZeros(), 5);
  EXPECT_EQ(b.problem.P.nonZeros(), 5);
  const Vector x = Eigen::Vector3d(1.0, 2.0, -1.0);
  EXPECT_DOUBLE_EQ(objective_by_hand(a.problem, x), 6.0);  // computed in quadobj.qps
  EXPECT_DOUBLE_EQ(objective_by_hand(b.problem, x), 6.0);
  EXPECT_DOUBLE_EQ(a.problem.objective(x), 6.0);
  EXPECT_DOUBLE_EQ(a.problem.r, -2.0);
  EXPECT_EQ(a.problem.l, Vector::Ones(1));
  EXPECT_EQ(a.problem.u, Vector::Ones(1));
}

/// Reads `path` and returns the InputError message (empty if nothing was thrown).
std::string error_of(const std::string& path) {
  try {
    read_qps(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

struct MalformedCase {
  const char* file;
  int line;
  const char* message;
};

void PrintTo(const MalformedCase& c, std::ostream* os) { *os << c.file << ":" << c.line; }

class QpsMalformed : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(QpsMalformed, ThrowsWithLineNumber) {
  const MalformedCase& c = GetParam();
  const std::string path = kData + "/qps/malformed/" + c.file;
  const std::string what = error_of(path);
  EXPECT_NE(what.find(path + ":" + std::to_string(c.line) + ": "), std::string::npos) << what;
  EXPECT_NE(what.find(c.message), std::string::npos) << what;
}

INSTANTIATE_TEST_SUITE_P(
    Files, QpsMalformed,
    ::testing::Values(MalformedCase{"unknown_section.qps", 11, "unknown section"},
                      MalformedCase{"unknown_row.qps", 8, "unknown row 'c2'"},
                      MalformedCase{"unknown_column.qps", 12, "unknown column 'z'"},
                      MalformedCase{"field_count.qps", 8, "fields"},
                      MalformedCase{"bad_number.qps", 10, "not a number"},
                      MalformedCase{"nan_value.qps", 14, "NaN"},
                      MalformedCase{"duplicate_row.qps", 6, "duplicate row"},
                      MalformedCase{"duplicate_entry.qps", 9, "duplicate entry"},
                      MalformedCase{"truncated.qps", 7, "ENDATA missing"},
                      MalformedCase{"integer_marker.qps", 9, "integer variable 'y'"},
                      MalformedCase{"integer_bound.qps", 12, "BV"},
                      MalformedCase{"qmatrix_asymmetric.qps", 16, "differs"}),
    [](const ::testing::TestParamInfo<MalformedCase>& info) {
      std::string name = info.param.file;
      return name.substr(0, name.find('.'));
    });

/// A small valid file with `section_text` placed after COLUMNS (lines 1–7 fixed).
std::string tiny(const std::string& after_columns) {
  return "NAME T\nROWS\n N obj\n L c1\nCOLUMNS\n x obj 1.0 c1 1.0\n y c1 1.0\n" + after_columns + "ENDATA\n";
}

std::string inline_error(const std::string& text) {
  std::istringstream in(text);
  try {
    parse_qps(in, "inline");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(QpsReader, InlineMalformed) {
  EXPECT_NE(inline_error(tiny("BOUNDS\n LO b x 3.0\n UP b x 1.0\n")).find("inline:10: bounds of column 'x' cross"), std::string::npos);
  EXPECT_NE(inline_error(tiny("QUADOBJ\n x y 1.0\n y x 1.0\n")).find("inline:10: duplicate quadratic entry"), std::string::npos);
  EXPECT_NE(inline_error(tiny("QMATRIX\n x y 1.0\n y y 1.0\n")).find("inline:9: QMATRIX entry (x, y) has no symmetric partner"), std::string::npos);
  EXPECT_NE(inline_error(tiny("RANGES\n r obj 1.0\n")).find("inline:9: RANGES entry on objective"), std::string::npos);
  EXPECT_NE(inline_error(tiny("RHS\n r c1 1e999\n")).find("inline:9: infinite value"), std::string::npos);
  EXPECT_NE(inline_error(tiny("RHS\n r c1 1.0\n s c1 2.0\n")).find("inline:10: second RHS set"), std::string::npos);
  EXPECT_NE(inline_error(tiny("RHS\n r c1 1.0\nRHS\n")).find("inline:10: section RHS appears twice"), std::string::npos);
  EXPECT_NE(inline_error(tiny("BOUNDS\n XX b x 1.0\n")).find("inline:9: unknown bound type"), std::string::npos);
  EXPECT_NE(inline_error(tiny("BOUNDS\n UP b x\n")).find("inline:9: BOUNDS UP line (type, set, column, value) has 3 fields, expected 4"), std::string::npos);
  EXPECT_NE(inline_error(tiny("OBJSENSE\n MAX\n")).find("inline:9: maximization"), std::string::npos);
  EXPECT_NE(inline_error(tiny("QSECTION c1\n")).find("inline:8: QSECTION for row 'c1'"), std::string::npos);
  EXPECT_NE(inline_error("NAME T\nCOLUMNS\n x obj 1.0\nENDATA\n").find("inline:2: COLUMNS section before ROWS"), std::string::npos);
  EXPECT_NE(inline_error("NAME T\nROWS\n N obj\n X c1\nENDATA\n").find("inline:4: unknown row type"), std::string::npos);
  EXPECT_NE(inline_error("NAME T\n x y\n").find("inline:2: data line outside"), std::string::npos);
  EXPECT_NE(inline_error("").find("inline:1: unexpected end of file"), std::string::npos);
  EXPECT_NE(error_of(kData + "/qps/does_not_exist.qps").find("cannot open"), std::string::npos);
}

TEST(QpsReader, InlineValidVariants) {
  // QSECTION on the objective row is QMATRIX; RHS entries may come in pairs; '*' comments,
  // blank lines and CRLF line ends are accepted; the value after ENDATA is never read.
  std::istringstream in(tiny("* comment\r\n\r\nRHS\n r c1 4.0 obj -1.5\r\nQSECTION obj\n x x 2.0\n x y 0.5\n y x 0.5\n") +
                        "garbage after ENDATA\n");
  const QpsModel m = parse_qps(in, "inline");
  EXPECT_EQ(m.problem.u, Vector::Constant(1, 4.0));
  EXPECT_EQ(m.problem.l, Vector::Constant(1, -kInf));
  EXPECT_DOUBLE_EQ(m.problem.r, 1.5);
  EXPECT_EQ(m.problem.P.nonZeros(), 2);
  EXPECT_DOUBLE_EQ(m.problem.P.coeff(0, 1), 0.5);
  EXPECT_EQ(m.problem.q, vec2(1.0, 0.0));
}

}  // namespace
}  // namespace lcprelax::io
