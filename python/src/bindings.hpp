// Shared pieces of the Python module `pronk` (pybind11): conversions between
// JSON and Python objects, tables as dicts of NumPy arrays, and the argument
// conventions (a path or a dict, overrides as a dict or "/ptr=value" strings).
#pragma once

#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <nlohmann/json.hpp>

#include "io/write/table.hpp"

namespace pronk::python {

namespace py = pybind11;

/// JSON -> Python (dict, list, str, int, float, bool, None); doubles keep every bit.
py::object to_python(const nlohmann::json& j);
/// Python -> JSON: dict (str keys), list, tuple, str, int, float, bool, None,
/// NumPy scalars and arrays. TypeError for anything else; io::InputError naming `file`
/// and the JSON Pointer (below `pointer`, where obj goes) for nesting deeper than
/// io::kMaxJsonDepth or a container that contains itself (the file readers' limits).
nlohmann::json from_python(const py::handle& obj, const std::string& file,
                           const std::string& pointer = "");

/// A table as {column name: 1-D float64 array} (columns in order).
py::dict table_to_dict(const io::Table& t);
/// A vector of doubles as a 1-D float64 array.
py::array_t<double> to_array(const std::vector<double>& v);
/// A 1-D sequence of finite numbers of length n (ValueError otherwise), `what` names it.
std::vector<double> vector_arg(const py::handle& x, size_t n, const char* what);

/// A document given as a path (str or os.PathLike: read with the strict reader)
/// or as a dict (taken as it is). Sets *file to the path or "<dict>" (names it in errors).
nlohmann::json document_arg(const py::handle& path_or_dict, std::string* file);
/// True when the argument is a path rather than a document.
bool is_path_arg(const py::handle& path_or_dict);
/// Overrides as "/ptr=value" assignments: from a dict {pointer: value} (the value
/// as JSON) or a list of "/ptr=value" strings (the CLI's --set); None: none.
std::vector<std::string> overrides_arg(const py::handle& overrides);
/// Most worker threads an argument may ask for (the CLI's --threads range is 1 to 1024).
inline constexpr int kMaxThreads = 1024;
/// Worker threads: 1 to kMaxThreads as given, 0 (or None): every hardware thread.
/// ValueError for anything else (a negative or larger count, a non-integer).
int threads_arg(const py::handle& threads);

void bind_errors(py::module_& m);
void bind_simulate(py::module_& m);
void bind_study(py::module_& m);
void bind_engines(py::module_& m);

}  // namespace pronk::python
