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
//                            1 thread (pile_scaling.csv, rows phase = window), fitted slopes
//   qp_scaling.png           forward and backward CPU time against n, slopes (qp_scaling.csv)
//   lemke_scaling.png        dense vs sparse Lemke, CPU time per solve against n on the
//                            piles and random P-matrix LCPs, slopes over n ≥ 100
//                            (lemke.json: bench_lemke --benchmark_out_format=json)
//   learn_throughput_{block,polygon}.png  samples/s against OpenMP threads (1 rank) and
//                            MPI ranks (1 thread) per method (learn_throughput.csv)
//   kkt_backends.png         QP wall time per KKT backend and rank count against problem
//                            size (kkt_backends.csv)
//   learn_convergence_{block,polygon}.png  learned-parameter error against training wall
//                            time per method (learn_convergence.csv; errors below 1e-12
//                            drawn at 1e-12)
//   learning_curves_scene_pile30_all{,_mode}.png  the 30-body pile's learning curves over
//                            every size run (learning_curves_scene.csv, Adam's relaxed-loss
//                            rows): median next-state error and mean mode error per
//                            parameterization
// Slopes: least squares of log y against log x (pile_timing.hpp loglog_slope).
// A missing CSV skips its plots with a message; without Cairo nothing is drawn (exit 1).
#include "csv_table.hpp"
#include "pile_timing.hpp"

#include <lcprelax/kkt/qp_result.hpp>
#include <lcprelax/scenes/line_plot.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <string>
#include <vector>

namespace {

using Row = lcprelax::bench::CsvRow;
using lcprelax::bench::read_csv;

double num(const Row& r, const std::string& key) { return lcprelax::bench::csv_number(r, key); }
std::string text(const Row& r, const std::string& key) { return lcprelax::bench::csv_text(r, key); }

// Whether a QP status written as to_string(QpStatus) in a CSV carries a solution.
bool has_solution_text(const std::string& status) {
  using lcprelax::QpStatus;
  for (QpStatus s : {QpStatus::unsolved, QpStatus::solved, QpStatus::solved_inaccurate, QpStatus::primal_infeasible,
                     QpStatus::dual_infeasible, QpStatus::max_iterations, QpStatus::time_limit,
                     QpStatus::numerical_error})
    if (status == lcprelax::to_string(s)) return lcprelax::has_solution(s);
  return false;
}

// Appends ", slope S" (least-squares slope of log y against log x over the series' points
// with x ≥ from) to the legend entry.
lcprelax::LineSeries with_slope(lcprelax::LineSeries s, double from = 0.0) {
  std::vector<double> x, y;
  for (std::size_t i = 0; i < s.x.size(); ++i)
    if (s.x[i] >= from) x.push_back(s.x[i]), y.push_back(s.y[i]);
  char buf[64];
  std::snprintf(buf, sizeof buf, ", slope %.2f", lcprelax::bench::loglog_slope(x, y));
  s.name += buf;
  return s;
}

lcprelax::LinePlotOptions log_log(const std::string& title, const std::string& x, const std::string& y) {
  lcprelax::LinePlotOptions o;
  o.title = title;
  o.x_label = x;
  o.y_label = y;
  o.log_x = o.log_y = true;
  return o;
}

void qp_plot(const std::vector<Row>& rows, const std::string& out) {
  std::map<double, std::vector<double>> errors;
  std::map<double, double> seconds;
  double clp_time = 0.0;
  std::vector<double> clp_errors;
  for (const Row& r : rows) {
    if (text(r, "experiment") != "qp") continue;
    if (text(r, "solver") == "clp-barrier") {
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
    if (text(r, "experiment") != "lcp") continue;
    lcprelax::LineSeries& s = text(r, "solver") == "lemke" ? lemke : ipm;
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
    if (text(r, "experiment") != "pile" || text(r, "solver") != "convex-ipm" || num(r, "error") <= 0) continue;
    lcprelax::LineSeries& s = lines[text(r, "problem")];
    s.name = text(r, "problem");
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
    if (text(r, "phase") != "window" || text(r, "threads") != "1") continue;
    lcprelax::LineSeries& s = lines[text(r, "model")];
    s.name = text(r, "model") + " model, 1 thread";
    s.markers = true;
    s.x.push_back(num(r, "contacts_mean"));
    s.y.push_back(num(r, "cpu_per_step"));
  }
  std::vector<lcprelax::LineSeries> series;
  for (auto& [k, s] : lines) series.push_back(with_slope(s));
  lcprelax::LinePlotOptions o;
  o.title = "Pile: CPU time per step vs contacts (least-squares log-log slopes)";
  o.x_label = "contacts (mean over the timed steps)";
  o.y_label = "CPU seconds per step";
  o.log_x = o.log_y = true;
  lcprelax::write_line_plot(out, series, o);
}

void qp_scaling_plot(const std::vector<Row>& rows, const std::string& out) {
  lcprelax::LineSeries fwd{"forward (setup + solve)", {}, {}, true, true};
  lcprelax::LineSeries bwd{"backward (adjoint)", {}, {}, true, true, true};
  for (const Row& r : rows) {
    if (!has_solution_text(text(r, "status"))) continue;
    fwd.x.push_back(num(r, "n")), fwd.y.push_back(num(r, "forward_cpu_s"));
    bwd.x.push_back(num(r, "n")), bwd.y.push_back(num(r, "backward_cpu_s"));
  }
  lcprelax::write_line_plot(out, {with_slope(fwd), with_slope(bwd)},
                            log_log("Random sparse QPs: CPU time vs variables (least-squares log-log slopes)",
                                    "variables n", "CPU seconds (fastest run)"));
}

// Google Benchmark JSON of bench_lemke: CPU time of one solve against the LCP size n.
void lemke_plot(const std::string& path, const std::string& out) {
  std::ifstream in(path);
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s: Lemke plot skipped\n", path.c_str(), e.what());
    return;
  }
  std::map<std::string, lcprelax::LineSeries> lines;
  for (const nlohmann::json& b : j.value("benchmarks", nlohmann::json::array())) {
    const std::string name = b.value("name", "");
    const bool pile = name.rfind("BM_Fc2dPile/", 0) == 0, random = name.rfind("BM_RandomP/", 0) == 0;
    if ((!pile && !random) || b.value("run_type", "") != "iteration" || b.value("solved", 0.0) == 0.0) continue;
    const std::string method = name.find("/dense/") != std::string::npos ? "dense" : "sparse";
    const std::string key = std::string(pile ? "fc2d pile" : "random P-matrix") + ", " + method;
    lcprelax::LineSeries& s = lines[key];
    s.name = key, s.markers = true, s.dashed = random;
    const std::string unit = b.value("time_unit", "ns");
    const double scale = unit == "ms" ? 1e-3 : unit == "us" ? 1e-6 : unit == "ns" ? 1e-9 : 1.0;
    s.x.push_back(b.value("n", NAN)), s.y.push_back(scale * b.value("cpu_time", NAN));
  }
  std::vector<lcprelax::LineSeries> series;
  for (auto& [k, s] : lines) series.push_back(with_slope(s, 100));
  lcprelax::write_line_plot(out, series,
                            log_log("Lemke, dense vs sparse basis: CPU time per solve (slopes fitted over n >= 100)",
                                    "LCP size n", "CPU seconds per setup + solve"));
}

void throughput_plot(const std::vector<Row>& rows, const std::string& problem, const std::string& out) {
  std::map<std::string, lcprelax::LineSeries> lines;
  for (const Row& r : rows) {
    if (text(r, "problem") != problem) continue;
    const int ranks = static_cast<int>(num(r, "ranks")), threads = static_cast<int>(num(r, "threads"));
    const std::string m = text(r, "method");
    if (ranks == 1) {  // threads series (ranks = 1)
      lcprelax::LineSeries& s = lines[m + ", threads"];
      s.name = m + ": 1 rank x T threads", s.markers = true;
      s.x.push_back(threads), s.y.push_back(num(r, "samples_per_s"));
    }
    if (threads == 1) {  // ranks series (threads = 1)
      lcprelax::LineSeries& s = lines[m + ", ranks"];
      s.name = m + ": R ranks x 1 thread", s.markers = true, s.dashed = true;
      s.x.push_back(ranks), s.y.push_back(num(r, "samples_per_s"));
    }
  }
  std::vector<lcprelax::LineSeries> series;
  for (auto& [k, s] : lines) {
    std::vector<std::size_t> order(s.x.size());  // sort by workers
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return s.x[a] < s.x[b]; });
    lcprelax::LineSeries sorted = s;
    for (std::size_t i = 0; i < order.size(); ++i) sorted.x[i] = s.x[order[i]], sorted.y[i] = s.y[order[i]];
    series.push_back(sorted);
  }
  lcprelax::LinePlotOptions o = log_log("Learning throughput, " + problem + ": loss + gradient over the dataset",
                                        "workers (OpenMP threads or MPI ranks)", "samples per second");
  o.log_x = false;
  o.x_min = 0.8, o.x_max = 2.2;
  lcprelax::write_line_plot(out, series, o);
}

void kkt_plot(const std::vector<Row>& rows, const std::string& out) {
  std::map<std::string, std::map<double, double>> points;  // series → size → seconds
  for (const Row& r : rows) {
    if (!has_solution_text(text(r, "status"))) continue;
    const std::string key = text(r, "backend") + ", " + text(r, "ranks") + (text(r, "ranks") == "1" ? " rank" : " ranks");
    points[key][num(r, "n") + num(r, "rows")] = num(r, "total_s");
  }
  std::vector<lcprelax::LineSeries> series;
  for (auto& [k, p] : points) {
    lcprelax::LineSeries s{k, {}, {}, true, true, k.rfind("cholmod", 0) != 0};
    for (auto& [x, y] : p) s.x.push_back(x), s.y.push_back(y);
    series.push_back(s);
  }
  lcprelax::write_line_plot(out, series,
                            log_log("QP solve by KKT backend (Maros-Meszaros + random QP; solved runs only)",
                                    "variables + constraint rows", "wall seconds, setup + solve"));
}

void convergence_plot(const std::vector<Row>& rows, const std::string& problem, const std::string& out) {
  std::map<std::string, lcprelax::LineSeries> lines;
  for (const Row& r : rows) {
    if (text(r, "problem") != problem) continue;
    const std::string key = text(r, "method") + (problem == "block" ? ", mu0 = " + text(r, "init") + " truth" : "");
    lcprelax::LineSeries& s = lines[key];
    s.name = key, s.dashed = text(r, "init") == "0.3x";
    s.x.push_back(num(r, "seconds")), s.y.push_back(std::max(num(r, "error"), 1e-12));
  }
  std::vector<lcprelax::LineSeries> series;
  for (auto& [k, s] : lines) series.push_back(s);
  lcprelax::LinePlotOptions o = log_log(
      problem == "block" ? "Learning the block's mu: relative error vs training time (truth 0.1)"
                         : "Learning the polygon: largest relative parameter error vs training time",
      "wall seconds of training", problem == "block" ? "|mu - mu*| / mu*" : "largest relative error");
  o.log_x = false;
  lcprelax::write_line_plot(out, series, o);
}

// A scene's learning curves over every training size in the merged CSV
// (learning_curves_scene.csv): per parameterization, the median held-out next-state error
// over the seeds (log-log) and the mean stick/slip mode error, rows of `method` only.
void scene_curve_plot(const std::vector<Row>& rows, const std::string& scene, const std::string& method,
                      const std::string& out, const std::string& out_mode) {
  struct Cell {
    std::vector<double> err, mode;
  };
  std::map<std::string, std::map<double, Cell>> cells;  // param → N → the seeds' errors
  for (const Row& r : rows) {
    if (text(r, "scene") != scene || text(r, "method") != method) continue;
    Cell& c = cells[text(r, "param")][num(r, "samples")];
    c.err.push_back(num(r, "test_error"));
    c.mode.push_back(num(r, "mode_error"));
  }
  std::vector<lcprelax::LineSeries> e_series, m_series;
  for (const auto& [param, by_n] : cells) {
    lcprelax::LineSeries e{param, {}, {}}, m{param, {}, {}};
    e.markers = m.markers = true;
    for (const auto& [n, c] : by_n) {
      e.x.push_back(n), e.y.push_back(lcprelax::bench::median(c.err));
      m.x.push_back(n), m.y.push_back(std::accumulate(c.mode.begin(), c.mode.end(), 0.0) / c.mode.size());
    }
    e_series.push_back(e), m_series.push_back(m);
  }
  lcprelax::LinePlotOptions o = log_log(scene + " (" + method + " loss): held-out next-state error, median of seeds",
                                        "training transitions", "relative RMS error of v+");
  lcprelax::write_line_plot(out, e_series, o);
  o.title = scene + " (" + method + " loss): held-out stick/slip mode error, mean of seeds";
  o.y_label = "fraction of wrong modes";
  o.log_y = false;
  lcprelax::write_line_plot(out_mode, m_series, o);
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
  // CSV → plot(s); a missing CSV skips its plots with a message.
  auto each = [&](const std::string& csv, const std::function<void(const std::vector<Row>&)>& draw) {
    const std::vector<Row> rows = read_csv(results + "/" + csv);
    if (rows.empty())
      std::fprintf(stderr, "no %s/%s: its plots skipped\n", results.c_str(), csv.c_str());
    else
      draw(rows);
  };
  each("qp_scaling.csv", [&](const std::vector<Row>& r) { qp_scaling_plot(r, out + "/qp_scaling.png"); });
  if (std::filesystem::exists(results + "/lemke.json"))
    lemke_plot(results + "/lemke.json", out + "/lemke_scaling.png");
  else
    std::fprintf(stderr, "no %s/lemke.json: Lemke plot skipped\n", results.c_str());
  each("learn_throughput.csv", [&](const std::vector<Row>& r) {
    throughput_plot(r, "block", out + "/learn_throughput_block.png");
    throughput_plot(r, "polygon", out + "/learn_throughput_polygon.png");
  });
  each("kkt_backends.csv", [&](const std::vector<Row>& r) { kkt_plot(r, out + "/kkt_backends.png"); });
  each("learn_convergence.csv", [&](const std::vector<Row>& r) {
    convergence_plot(r, "block", out + "/learn_convergence_block.png");
    convergence_plot(r, "polygon", out + "/learn_convergence_polygon.png");
  });
  each("learning_curves_scene.csv", [&](const std::vector<Row>& r) {
    scene_curve_plot(r, "pile30", "relaxed", out + "/learning_curves_scene_pile30_all.png",
                     out + "/learning_curves_scene_pile30_all_mode.png");
  });
  std::printf("plots written to %s\n", out.c_str());
  return 0;
}
