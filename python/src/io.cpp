// Binds the readers of lcprelax_io (io/qps_reader.hpp, io/siconos_reader.hpp) as
// lcprelax.read_qps / parse_qps, read_siconos_lcp / parse_siconos_lcp and
// read_siconos_fc2d / parse_siconos_fc2d. Each returns a dict of copies (scipy CSC
// matrices, float64 NumPy arrays).
//
// Conventions (docs/formats.md):
// - QPS: {"name", "objective_name", "variable_names", "row_names", "problem"}, where
//   "problem" holds exactly the keyword arguments of QpSolver.setup (P as its UPPER
//   triangle, q, A (empty: every constraint row is a row of G, in file order), b, G, l, u,
//   xl, xu, r), so `solver.setup(**model["problem"])` solves the file's QP.
// - Siconos LCP: {"M", "q"} with w = Mz + q, 0 ≤ z ⊥ w ≥ 0.
// - Siconos fc2d: {"contacts", "W", "q", "mu"} with u = W r + q; contact i owns rows 2i
//   (normal) and 2i + 1 (tangent).
// Malformed files raise lcprelax.InputError "PATH:LINE: message". Paths may be str or
// os.PathLike; file reading releases the GIL.
#include "bindings.hpp"

#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/io/siconos_reader.hpp>

#include <pybind11/stl.h>

#include <sstream>

namespace lcprelax::python {
namespace {

std::string path_string(const py::object& path) {
  if (!PyUnicode_Check(path.ptr()) && !py::hasattr(path, "__fspath__"))
    throw py::type_error("path must be a str or os.PathLike, got " +
                         std::string(py::str(py::type::handle_of(path).attr("__qualname__"))));
  const py::object s = py::module_::import("os").attr("fspath")(path);
  if (!PyUnicode_Check(s.ptr())) throw py::type_error("path must be a text path (bytes paths are not supported)");
  return s.cast<std::string>();
}

std::string text_string(const py::object& text) {
  if (!PyUnicode_Check(text.ptr())) throw py::type_error("text must be a str");
  return text.cast<std::string>();
}

py::dict qps_dict(const io::QpsModel& model) {
  py::dict d;
  d["name"] = model.name;
  d["objective_name"] = model.objective_name;
  d["variable_names"] = model.variable_names;
  d["row_names"] = model.row_names;
  d["problem"] = problem_dict(model.problem);
  return d;
}

py::dict lcp_dict(const io::LcpData& data) {
  py::dict d;
  d["M"] = to_scipy(data.M);
  d["q"] = to_numpy(data.q);
  return d;
}

py::dict fc2d_dict(const io::Fc2dData& data) {
  py::dict d;
  d["contacts"] = data.contacts;
  d["W"] = to_scipy(data.W);
  d["q"] = to_numpy(data.q);
  d["mu"] = to_numpy(data.mu);
  return d;
}

/// Runs a reader with the GIL released and converts its value with the GIL held.
template <class Read, class Convert>
py::dict read_released(Read read, Convert convert) {
  decltype(read()) value;
  {
    py::gil_scoped_release nogil;
    value = read();
  }
  return convert(value);
}

}  // namespace

void bind_io(py::module_& m) {
  m.def(
      "read_qps",
      [](const py::object& path) {
        const std::string p = path_string(path);
        return read_released([&] { return io::read_qps(p); }, qps_dict);
      },
      py::arg("path"),
      "Reads a QPS file (Maros-Meszaros format). Returns {'name', 'objective_name', "
      "'variable_names', 'row_names', 'problem'}; solver.setup(**d['problem']) solves it.");
  m.def(
      "parse_qps",
      [](const py::object& text, const std::string& source_name) {
        std::istringstream in(text_string(text));
        return read_released([&] { return io::parse_qps(in, source_name); }, qps_dict);
      },
      py::arg("text"), py::arg("source_name") = "<string>", "As read_qps, from the text of a QPS file.");
  m.def(
      "read_siconos_lcp",
      [](const py::object& path) {
        const std::string p = path_string(path);
        return read_released([&] { return io::read_siconos_lcp(p); }, lcp_dict);
      },
      py::arg("path"), "Reads a Siconos LCP .dat file. Returns {'M': csc, 'q': array}.");
  m.def(
      "parse_siconos_lcp",
      [](const py::object& text, const std::string& source_name) {
        std::istringstream in(text_string(text));
        return read_released([&] { return io::parse_siconos_lcp(in, source_name); }, lcp_dict);
      },
      py::arg("text"), py::arg("source_name") = "<string>", "As read_siconos_lcp, from the file's text.");
  m.def(
      "read_siconos_fc2d",
      [](const py::object& path) {
        const std::string p = path_string(path);
        return read_released([&] { return io::read_siconos_fc2d(p); }, fc2d_dict);
      },
      py::arg("path"),
      "Reads a Siconos 2-D frictional contact .dat file. Returns {'contacts', 'W', 'q', 'mu'} "
      "(u = W r + q; rows 2i normal, 2i+1 tangent).");
  m.def(
      "parse_siconos_fc2d",
      [](const py::object& text, const std::string& source_name) {
        std::istringstream in(text_string(text));
        return read_released([&] { return io::parse_siconos_fc2d(in, source_name); }, fc2d_dict);
      },
      py::arg("text"), py::arg("source_name") = "<string>", "As read_siconos_fc2d, from the file's text.");
}

}  // namespace lcprelax::python
