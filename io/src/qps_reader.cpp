// QPS reader (free-format MPS with QUADOBJ / QMATRIX / QSECTION), conventions in
// <lcprelax/io/qps_reader.hpp>. One pass over the lines collects names,
// triplets and bound data with duplicate checks; row bounds (RHS + RANGES), variable-bound
// crossings and the symmetry of a full QMATRIX are resolved after ENDATA, with the line
// number of the offending entry kept for the message. Integer data (MARKER blocks, BV/LI/
// UI/SC bounds) are rejected, never silently relaxed.
#include <lcprelax/io/qps_reader.hpp>

#include "qps_lexer.hpp"

#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace lcprelax::io {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Columns, rows and matrix entries are counted in Index (int): at most 2^31 − 1 of each.
constexpr std::size_t kMaxCount = static_cast<std::size_t>(std::numeric_limits<Index>::max());

enum class RowKind { objective, dropped, constraint };
struct RowRef {
  RowKind kind;
  Index index;  ///< constraint index (file order of E/L/G rows), −1 otherwise
};

struct QuadEntry {
  Index i, j;
  double value;
  long line;
};

std::string Q(const std::string& token) { return QpsLexer::quote(token); }

std::uint64_t key(Index i, Index j) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) | static_cast<std::uint32_t>(j);
}

/// All state of one parse; parse() drives the section machine, finish() builds the model.
class QpsParser {
 public:
  QpsParser(std::istream& in, const std::string& source) : lex_(in, source) {}

  QpsModel parse() {
    std::vector<std::string> f;
    bool endata = false;
    while (!endata && lex_.next(f)) {
      if (lex_.is_header()) {
        endata = enter_section(f);
      } else {
        data_line(f);
      }
    }
    if (!endata) lex_.fail("unexpected end of file: ENDATA missing (truncated file?)");
    return finish();
  }

 private:
  QpsLexer lex_;
  QpsSection section_ = QpsSection::none;
  std::unordered_set<int> seen_sections_;
  QpsModel model_;
  bool has_objective_ = false;
  // rows
  std::unordered_map<std::string, RowRef> rows_;
  std::vector<char> row_type_;  ///< 'E', 'L' or 'G' per constraint row
  // columns
  std::unordered_map<std::string, Index> cols_;
  std::vector<double> q_;
  std::vector<char> q_set_;
  std::vector<Triplet> g_;
  std::unordered_set<std::uint64_t> g_keys_;
  bool in_integer_block_ = false;
  // RHS / RANGES
  std::vector<double> rhs_, range_;
  std::vector<char> rhs_set_, range_set_;
  bool objective_rhs_set_ = false;
  double r_ = 0.0;
  std::string rhs_name_, ranges_name_, bounds_name_;
  // BOUNDS
  std::vector<double> xl_, xu_;
  std::vector<char> lower_set_;
  std::vector<long> bound_line_;
  // quadratic part
  std::vector<QuadEntry> quad_;
  std::unordered_map<std::uint64_t, std::size_t> quad_keys_;
  bool full_quadratic_ = false;  ///< QMATRIX/QSECTION (both triangles) vs QUADOBJ

  /// Switches section; returns true at ENDATA.
  bool enter_section(const std::vector<std::string>& f) {
    const QpsSection s = section_from_name(f[0]);
    if (s == QpsSection::none) lex_.fail("unknown section " + Q(f[0]));
    const bool quadratic = s == QpsSection::quadobj || s == QpsSection::qmatrix;
    const int id = quadratic ? static_cast<int>(QpsSection::quadobj) : static_cast<int>(s);
    if (!seen_sections_.insert(id).second) lex_.fail("section " + f[0] + " appears twice");
    const bool needs_rows = s == QpsSection::columns;
    const bool needs_columns = s == QpsSection::rhs || s == QpsSection::ranges ||
                               s == QpsSection::bounds || quadratic;
    if (needs_rows && !seen(QpsSection::rows)) lex_.fail(f[0] + " section before ROWS");
    if (needs_columns && !seen(QpsSection::columns)) lex_.fail(f[0] + " section before COLUMNS");
    if (s == QpsSection::rows && seen(QpsSection::columns)) lex_.fail("ROWS section after COLUMNS");
    if (s == QpsSection::name) {
      if (f.size() > 2) lex_.fail("NAME line has " + std::to_string(f.size()) + " fields, expected 1 or 2");
      model_.name = f.size() == 2 ? f[1] : std::string();
    } else if (s == QpsSection::objsense) {
      if (f.size() > 2) lex_.fail("OBJSENSE line has too many fields");
      if (f.size() == 2) check_sense(f[1]);
    } else if (f[0] == "QSECTION") {
      if (f.size() > 2) lex_.fail("QSECTION line has too many fields");
      if (f.size() == 2 && (!has_objective_ || f[1] != model_.objective_name))
        lex_.fail("QSECTION for row " + Q(f[1]) + ": quadratic constraints are not supported");
    } else if (f.size() != 1) {
      lex_.fail("unexpected fields after section header " + f[0]);
    }
    full_quadratic_ = full_quadratic_ || s == QpsSection::qmatrix;
    section_ = s;
    return s == QpsSection::endata;
  }

  bool seen(QpsSection s) const { return seen_sections_.count(static_cast<int>(s)) != 0; }

  void check_sense(const std::string& sense) {
    if (sense == "MIN" || sense == "MINIMIZE") return;
    if (sense == "MAX" || sense == "MAXIMIZE") lex_.fail("maximization (OBJSENSE " + Q(sense) + ") is not supported");
    lex_.fail("unknown OBJSENSE " + Q(sense));
  }

  void data_line(const std::vector<std::string>& f) {
    switch (section_) {
      case QpsSection::rows: row_line(f); break;
      case QpsSection::columns: column_line(f); break;
      case QpsSection::rhs: rhs_line(f, false); break;
      case QpsSection::ranges: rhs_line(f, true); break;
      case QpsSection::bounds: bound_line(f); break;
      case QpsSection::quadobj:
      case QpsSection::qmatrix: quad_line(f); break;
      case QpsSection::objsense:
        if (f.size() != 1) lex_.fail("OBJSENSE data line needs 1 field");
        check_sense(f[0]);
        break;
      default: lex_.fail("data line outside of a section (section headers start in column 1)");
    }
  }

  void row_line(const std::vector<std::string>& f) {
    lex_.expect_fields(f, 2, 2, "ROWS line (type, name)");
    const std::string& t = f[0];
    if (t != "N" && t != "E" && t != "L" && t != "G") lex_.fail("unknown row type " + Q(t) + " (expected N, E, L or G)");
    if (rows_.count(f[1])) lex_.fail("duplicate row name " + Q(f[1]));
    RowRef ref{RowKind::constraint, -1};
    if (t == "N") {
      ref.kind = has_objective_ ? RowKind::dropped : RowKind::objective;
      if (!has_objective_) model_.objective_name = f[1];
      has_objective_ = true;
    } else {
      if (row_type_.size() >= kMaxCount) lex_.fail("more than " + std::to_string(kMaxCount) + " constraint rows");
      ref.index = static_cast<Index>(row_type_.size());
      row_type_.push_back(t[0]);
      model_.row_names.push_back(f[1]);
    }
    rows_.emplace(f[1], ref);
  }

  const RowRef& row(const std::string& name) {
    auto it = rows_.find(name);
    if (it == rows_.end()) lex_.fail("unknown row " + Q(name));
    return it->second;
  }

  Index column(const std::string& name) {
    auto it = cols_.find(name);
    if (it == cols_.end()) lex_.fail("unknown column " + Q(name));
    return it->second;
  }

  void column_line(const std::vector<std::string>& f) {
    if (f.size() >= 2 && f[1] == "'MARKER'") {
      lex_.expect_fields(f, 3, 3, "MARKER line (name, 'MARKER', 'INTORG'|'INTEND')");
      if (f[2] == "'INTORG'") in_integer_block_ = true;
      else if (f[2] == "'INTEND'") in_integer_block_ = false;
      else lex_.fail("unknown MARKER type " + Q(f[2]));
      return;
    }
    if (f.size() != 3 && f.size() != 5)
      lex_.fail("COLUMNS line has " + std::to_string(f.size()) + " fields, expected 3 or 5 (column, row, value[, row, value])");
    if (in_integer_block_)
      lex_.fail("integer variable " + Q(f[0]) + " (inside an INTORG/INTEND MARKER block) is not supported");
    if (q_.size() >= kMaxCount && !cols_.count(f[0])) lex_.fail("more than " + std::to_string(kMaxCount) + " columns");
    auto [it, inserted] = cols_.emplace(f[0], static_cast<Index>(q_.size()));
    const Index j = it->second;
    if (inserted) {
      model_.variable_names.push_back(f[0]);
      q_.push_back(0.0);
      q_set_.push_back(0);
    }
    for (std::size_t k = 1; k + 1 < f.size(); k += 2) {
      const RowRef& ref = row(f[k]);
      const double v = lex_.finite_number(f[k + 1]);
      if (ref.kind == RowKind::objective) {
        if (q_set_[j]) lex_.fail("duplicate objective entry for column " + Q(f[0]));
        q_set_[j] = 1;
        q_[j] = v;
      } else if (ref.kind == RowKind::constraint) {
        if (!g_keys_.insert(key(ref.index, j)).second)
          lex_.fail("duplicate entry for column " + Q(f[0]) + " in row " + Q(f[k]));
        if (g_.size() >= kMaxCount) lex_.fail("more than " + std::to_string(kMaxCount) + " constraint entries");
        if (v != 0.0) g_.emplace_back(ref.index, j, v);
      }
    }
  }

  void check_set_name(std::string& stored, const std::string& name, const char* what) {
    if (stored.empty()) stored = name;
    else if (stored != name) lex_.fail(std::string("second ") + what + " set " + Q(name) + " (only one set is supported, first was " + Q(stored) + ")");
  }

  /// RHS (ranges = false) or RANGES line: set, row, value[, row, value].
  void rhs_line(const std::vector<std::string>& f, bool ranges) {
    const char* what = ranges ? "RANGES" : "RHS";
    if (f.size() != 3 && f.size() != 5)
      lex_.fail(std::string(what) + " line has " + std::to_string(f.size()) + " fields, expected 3 or 5 (set, row, value[, row, value])");
    check_set_name(ranges ? ranges_name_ : rhs_name_, f[0], what);
    rhs_.resize(row_type_.size(), 0.0);
    rhs_set_.resize(row_type_.size(), 0);
    range_.resize(row_type_.size(), 0.0);
    range_set_.resize(row_type_.size(), 0);
    for (std::size_t k = 1; k + 1 < f.size(); k += 2) {
      const RowRef& ref = row(f[k]);
      const double v = lex_.finite_number(f[k + 1]);
      if (ref.kind != RowKind::constraint) {
        if (ranges) lex_.fail("RANGES entry on objective (N) row " + Q(f[k]));
        if (ref.kind == RowKind::objective) {
          if (objective_rhs_set_) lex_.fail("duplicate RHS entry for objective row " + Q(f[k]));
          objective_rhs_set_ = true;
          r_ = -v;  // the objective row's RHS is −r
        }
        continue;
      }
      std::vector<char>& set = ranges ? range_set_ : rhs_set_;
      if (set[ref.index]) lex_.fail(std::string("duplicate ") + what + " entry for row " + Q(f[k]));
      set[ref.index] = 1;
      (ranges ? range_ : rhs_)[ref.index] = v;
    }
  }

  void bound_line(const std::vector<std::string>& f) {
    if (f.empty()) return;
    const std::string& t = f[0];
    const bool valueless = t == "FR" || t == "MI" || t == "PL";
    if (t == "BV" || t == "LI" || t == "UI" || t == "SC")
      lex_.fail("integer or semi-continuous bound type " + Q(t) + " is not supported");
    if (!valueless && t != "LO" && t != "UP" && t != "FX")
      lex_.fail("unknown bound type " + Q(t) + " (expected LO, UP, FX, FR, MI or PL)");
    if (valueless) lex_.expect_fields(f, 3, 4, "BOUNDS " + t + " line (type, set, column[, value])");
    else lex_.expect_fields(f, 4, 4, "BOUNDS " + t + " line (type, set, column, value)");
    check_set_name(bounds_name_, f[1], "BOUNDS");
    const Index j = column(f[2]);
    if (xl_.empty()) {
      xl_.assign(q_.size(), 0.0);
      xu_.assign(q_.size(), kInf);
      lower_set_.assign(q_.size(), 0);
      bound_line_.assign(q_.size(), 0);
    }
    bound_line_[j] = lex_.line();
    if (valueless) {
      if (f.size() == 4) lex_.number(f[3]);  // value field present: checked, then ignored
      if (t == "FR") { xl_[j] = -kInf; xu_[j] = kInf; lower_set_[j] = 1; }
      if (t == "MI") { xl_[j] = -kInf; lower_set_[j] = 1; }
      if (t == "PL") xu_[j] = kInf;
      return;
    }
    const double v = lex_.number(f[3]);
    if (t == "LO") {
      if (v == kInf) lex_.fail("LO bound +inf on column " + Q(f[2]));
      xl_[j] = v;
      lower_set_[j] = 1;
    } else if (t == "UP") {
      if (v == -kInf) lex_.fail("UP bound -inf on column " + Q(f[2]));
      xu_[j] = v;
      if (v < 0.0 && !lower_set_[j]) xl_[j] = -kInf;  // classic MPS rule for a negative UP
    } else {  // FX
      if (!std::isfinite(v)) lex_.fail("infinite FX bound on column " + Q(f[2]));
      xl_[j] = xu_[j] = v;
      lower_set_[j] = 1;
    }
  }

  void quad_line(const std::vector<std::string>& f) {
    lex_.expect_fields(f, 3, 3, "quadratic line (column, column, value)");
    const Index i = column(f[0]);
    const Index j = column(f[1]);
    const double v = lex_.finite_number(f[2]);
    // QUADOBJ holds one entry per pair, in either orientation: key on (min, max).
    const std::uint64_t k = full_quadratic_ ? key(i, j) : key(std::min(i, j), std::max(i, j));
    if (!quad_keys_.emplace(k, quad_.size()).second)
      lex_.fail("duplicate quadratic entry (" + Q(f[0]) + ", " + Q(f[1]) + ")" +
                (full_quadratic_ ? "" : "; QUADOBJ lists each off-diagonal pair once"));
    if (quad_.size() >= kMaxCount) lex_.fail("more than " + std::to_string(kMaxCount) + " quadratic entries");
    quad_.push_back({i, j, v, lex_.line()});
  }

  /// Upper-triangular P triplets; for QMATRIX every off-diagonal entry needs an equal mirror.
  std::vector<Triplet> upper_triplets() {
    std::vector<Triplet> t;
    t.reserve(quad_.size());
    for (const QuadEntry& e : quad_) {
      if (full_quadratic_ && e.i != e.j) {
        auto it = quad_keys_.find(key(e.j, e.i));
        const std::string pair = "(" + text::truncate(model_.variable_names[e.i]) + ", " +
                                 text::truncate(model_.variable_names[e.j]) + ")";
        if (it == quad_keys_.end())
          lex_.fail_at(e.line, "QMATRIX entry " + pair + " has no symmetric partner");
        const QuadEntry& m = quad_[it->second];
        const double tol = 1e-12 * std::max(std::abs(e.value), std::abs(m.value));
        if (std::abs(e.value - m.value) > tol)
          lex_.fail_at(std::max(e.line, m.line), "QMATRIX entry " + pair + " = " + lex_.format(e.value) +
                                                     " differs from its symmetric partner " + lex_.format(m.value));
        if (e.i > e.j) continue;  // the mirror was checked; keep the upper copy only
      }
      if (e.value != 0.0) t.emplace_back(std::min(e.i, e.j), std::max(e.i, e.j), e.value);
    }
    return t;
  }

  /// Row bounds from RHS and RANGES (MPS rules), in lcprelax's [l, u] form.
  void row_bounds(Vector& l, Vector& u) {
    const Index m = static_cast<Index>(row_type_.size());
    rhs_.resize(m, 0.0);
    range_.resize(m, 0.0);
    range_set_.resize(m, 0);
    l.resize(m);
    u.resize(m);
    for (Index i = 0; i < m; ++i) {
      const double b = rhs_[i];
      const double r = std::abs(range_[i]);
      switch (row_type_[i]) {
        case 'E':
          l[i] = b;
          u[i] = b;
          if (range_set_[i] && range_[i] > 0.0) u[i] = b + r;
          if (range_set_[i] && range_[i] < 0.0) l[i] = b - r;
          break;
        case 'L':
          l[i] = range_set_[i] ? b - r : -kInf;
          u[i] = b;
          break;
        default:  // 'G'
          l[i] = b;
          u[i] = range_set_[i] ? b + r : kInf;
      }
    }
  }

  QpsModel finish() {
    const Index n = static_cast<Index>(q_.size());
    const Index m = static_cast<Index>(row_type_.size());
    // A problem without variables is no problem: reject it here rather than "solve" it.
    if (n == 0) lex_.fail("no variables: the COLUMNS section lists no column");
    if (xl_.empty()) {
      xl_.assign(n, 0.0);
      xu_.assign(n, kInf);
      bound_line_.assign(n, 0);
    }
    for (Index j = 0; j < n; ++j) {
      if (xl_[j] > xu_[j])
        lex_.fail_at(bound_line_[j], "bounds of column " + Q(model_.variable_names[j]) + " cross: lower " +
                                         lex_.format(xl_[j]) + " > upper " + lex_.format(xu_[j]));
    }
    QpProblem& p = model_.problem;
    const std::vector<Triplet> pt = upper_triplets();
    p.P.resize(n, n);
    p.P.setFromTriplets(pt.begin(), pt.end());
    p.q = Eigen::Map<const Vector>(q_.data(), n);
    p.r = r_;
    p.A.resize(0, n);
    p.A.makeCompressed();
    p.b.resize(0);
    p.G.resize(m, n);
    p.G.setFromTriplets(g_.begin(), g_.end());
    row_bounds(p.l, p.u);
    p.xl = Eigen::Map<const Vector>(xl_.data(), n);
    p.xu = Eigen::Map<const Vector>(xu_.data(), n);
    return std::move(model_);
  }
};

}  // namespace

QpsModel parse_qps(std::istream& in, const std::string& source_name) {
  return QpsParser(in, source_name).parse();
}

QpsModel read_qps(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file");
  return parse_qps(in, path);
}

}  // namespace lcprelax::io
