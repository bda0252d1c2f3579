// Plots of the README's benchmark results, from the CSVs in bench/results (CSV in, PNG
// out, scenes/line_plot.hpp):
//
//   run_report_plots [--results bench/results] [--out bench/results/plots]
//
//   work_precision_qp.png    interior point, total run time over the Maros–Meszaros set
//                            against the median and the largest relative objective error,
//                            one point per tolerance (work_precision.csv, experiment qp);
//                            Clp's barrier as one point (its default tolerance); an error
//                            of exactly 0 is drawn at 1e-17
//   work_precision_lcp.png   per Siconos LCP: Lemke's and the interior point's error against
//                            run time (experiment lcp; errors of 0 are not drawn on the log axis)
//   work_precision_pile.png  pile trajectory error against run time, one line per horizon
//   pile_scaling.png         CPU seconds per step against contacts (log-log), per model,
//                            1 thread (pile_scaling.csv, rows phase = window)
// A missing CSV skips its plots with a message; without Cairo nothing is drawn (exit 1).
#include <lcprelax/scenes/line_plot.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Row = std::map<std::string, std::string>;

// A small CSV reader: header line, comma-separated fields, "…" quoting without commas inside.
std::vector<Row> read_csv(const std::string& path) {
  std::vector<Row> rows;
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
    Row r;
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) r[header[i]] = f[i];
    rows.push_back(r);
  }
  return rows;
}

double num(const Row& r, const std::string& key) {
  const auto it = r.find(key);
  if (it == r.end() || it->second.empty()) return NAN;
  try {
    return std::stod(it->second);
  } catch (...) {
    return NAN;
  }
}

void qp_plot(const std::vector<Row>& rows, const std::string& out) {
  std::map<double, std::vector<double>> errors;
  std::map<double, double> seconds;
  double clp_time = 0.0;
  std::vector<double> clp_errors;
  for (const Row& r : rows) {
    if (r.at("experiment") != "qp") continue;
    if (r.at("solver") == "clp-barrier") {
      clp_time += num(r, "seconds");
      clp_errors.push_back(num(r, "error"));
      continue;
    }
    errors[num(r, "tolerance")].push_back(num(r, "error"));
    seconds[num(r, "tolerance")] += num(r, "seconds");
  }
  lcprelax::LineSeries median{"lcprelax, median error", {}, {}, true, true}, worst{"lcprelax, largest error", {}, {}, true, true, true};
  for (auto& [tol, e] : errors) {
    std::sort(e.begin(), e.end());
    median.x.push_back(seconds[tol]);
    median.y.push_back(std::max(e[e.size() / 2], 1e-17));  // 0 (exact) drawn at 1e-17
    worst.x.push_back(seconds[tol]);
    worst.y.push_back(std::max(e.back(), 1e-17));
  }
  std::vector<lcprelax::LineSeries> series = {median, worst};
  if (!clp_errors.empty()) {
    std::sort(clp_errors.begin(), clp_errors.end());
    series.push_back({"Clp barrier, median error", {clp_time}, {std::max(clp_errors[clp_errors.size() / 2], 1e-17)}, false, true});
  }
  lcprelax::LinePlotOptions o;
  o.title = "Maros-Meszaros: objective error vs total run time (eps 1e-1 ... 1e-9)";
  o.x_label = "total seconds over the problems";
  o.y_label = "relative objective error";
  o.log_x = o.log_y = true;
  lcprelax::write_line_plot(out, series, o);
}

void lcp_plot(const std::vector<Row>& rows, const std::string& out) {
  lcprelax::LineSeries lemke{"Lemke", {}, {}, false, true}, ipm{"interior point (eps 1e-4 ... 1e-10)", {}, {}, false, true};
  for (const Row& r : rows) {
    if (r.at("experiment") != "lcp") continue;
    lcprelax::LineSeries& s = r.at("solver") == "lemke" ? lemke : ipm;
    s.x.push_back(num(r, "seconds"));
    s.y.push_back(num(r, "error"));
  }
  lcprelax::LinePlotOptions o;
  o.title = "Siconos LCPs: error vs run time (error 0 not drawn)";
  o.x_label = "seconds";
  o.y_label = "Siconos LCP error";
  o.log_x = o.log_y = true;
  lcprelax::write_line_plot(out, {lemke, ipm}, o);
}

void pile_plot(const std::vector<Row>& rows, const std::string& out) {
  std::map<std::string, lcprelax::LineSeries> lines;
  for (const Row& r : rows) {
    if (r.at("experiment") != "pile" || r.at("solver") != "convex-ipm" || num(r, "error") <= 0) continue;
    lcprelax::LineSeries& s = lines[r.at("problem")];
    s.name = r.at("problem");
    s.markers = true;
    s.x.push_back(num(r, "seconds"));
    s.y.push_back(num(r, "error"));
  }
  std::vector<lcprelax::LineSeries> series;
  for (auto& [k, s] : lines) series.push_back(s);
  lcprelax::LinePlotOptions o;
  o.title = "Pile (convex model): trajectory error vs run time, eps 1e-4 ... 1e-10";
  o.x_label = "seconds";
  o.y_label = "largest position difference from eps 1e-11 (m)";
  o.log_x = o.log_y = true;
  lcprelax::write_line_plot(out, series, o);
}

void scaling_plot(const std::vector<Row>& rows, const std::string& out) {
  std::map<std::string, lcprelax::LineSeries> lines;
  for (const Row& r : rows) {
    if (r.at("phase") != "window" || r.at("threads") != "1") continue;
    lcprelax::LineSeries& s = lines[r.at("model")];
    s.name = r.at("model") + " model, 1 thread";
    s.markers = true;
    s.x.push_back(num(r, "contacts_mean"));
    s.y.push_back(num(r, "cpu_per_step"));
  }
  std::vector<lcprelax::LineSeries> series;
  for (auto& [k, s] : lines) series.push_back(s);
  lcprelax::LinePlotOptions o;
  o.title = "Pile: CPU time per step vs contacts";
  o.x_label = "contacts (mean over the timed steps)";
  o.y_label = "CPU seconds per step";
  o.log_x = o.log_y = true;
  lcprelax::write_line_plot(out, series, o);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"plots of the benchmark CSVs"};
  std::string results = "bench/results", out = "bench/results/plots";
  app.add_option("--results", results, "directory of the CSVs");
  app.add_option("--out", out, "directory of the PNGs");
  CLI11_PARSE(app, argc, argv);
  if (!lcprelax::line_plot_available()) {
    std::fprintf(stderr, "built without Cairo: no plots\n");
    return 1;
  }
  std::filesystem::create_directories(out);
  const std::vector<Row> wp = read_csv(results + "/work_precision.csv");
  if (wp.empty()) {
    std::fprintf(stderr, "no %s/work_precision.csv: work-precision plots skipped\n", results.c_str());
  } else {
    qp_plot(wp, out + "/work_precision_qp.png");
    lcp_plot(wp, out + "/work_precision_lcp.png");
    pile_plot(wp, out + "/work_precision_pile.png");
  }
  const std::vector<Row> scaling = read_csv(results + "/pile_scaling.csv");
  if (scaling.empty())
    std::fprintf(stderr, "no %s/pile_scaling.csv: scaling plot skipped\n", results.c_str());
  else
    scaling_plot(scaling, out + "/pile_scaling.png");
  std::printf("plots written to %s\n", out.c_str());
  return 0;
}
