#pragma once
// Reading the benchmark CSVs back (run_report_plots.cpp; header-only), opening one for
// writing only where asked (open_optional_csv), and the median their summaries use: a header line,
// comma-separated fields, "…" quoting without commas inside (as Google Benchmark's
// --benchmark_out_format=csv writes names and labels). Rows are maps column → text.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace lcprelax::bench {

using CsvRow = std::map<std::string, std::string>;

/// The non-empty comma-separated items of s (option lists, unquoted CSV lines).
inline std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

/// The median of v (the mean of the middle two for an even count); v must not be empty.
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Opens `path` for writing when it is not empty; false, with a message on stderr, when it
/// cannot be written. Only where asked: a run with other options must not overwrite a file of
/// bench/results (bench/regenerate.sh names every output).
inline bool open_optional_csv(const std::string& path, std::ofstream& out) {
  if (path.empty()) return true;
  out.open(path);
  if (out) return true;
  std::fprintf(stderr, "cannot write %s\n", path.c_str());
  return false;
}

/// The rows of `path` (empty when the file is missing or has no header). Lines before the
/// header that Google Benchmark may print are not expected: the header is the first line.
inline std::vector<CsvRow> read_csv(const std::string& path) {
  std::vector<CsvRow> rows;
  std::ifstream in(path);
  if (!in) return rows;
  auto split = [](const std::string& line) {
    std::vector<std::string> out;
    std::string field;
    bool quoted = false;
    for (char c : line) {
      if (c == '"') quoted = !quoted;
      else if (c == ',' && !quoted) out.push_back(field), field.clear();
      else field += c;
    }
    out.push_back(field);
    return out;
  };
  std::string line;
  if (!std::getline(in, line)) return rows;
  const std::vector<std::string> header = split(line);
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line);
    CsvRow r;
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) r[header[i]] = f[i];
    rows.push_back(r);
  }
  return rows;
}

/// The number in column `key` (NaN when missing, empty or not a number).
inline double csv_number(const CsvRow& r, const std::string& key) {
  const auto it = r.find(key);
  if (it == r.end() || it->second.empty()) return NAN;
  try {
    return std::stod(it->second);
  } catch (...) {
    return NAN;
  }
}

/// The text in column `key` ("" when missing).
inline std::string csv_text(const CsvRow& r, const std::string& key) {
  const auto it = r.find(key);
  return it == r.end() ? std::string() : it->second;
}

}  // namespace lcprelax::bench
