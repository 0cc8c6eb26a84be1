#include <algorithm>
#include <cmath>
#include <thread>

#include "io/load/json_reader.hpp"
#include "io/load/scene_loader.hpp"
#include "python/src/bindings.hpp"
#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/scene_loader.hpp"

namespace pronk::python {

py::object to_python(const nlohmann::json& j) {
  using V = nlohmann::json::value_t;
  switch (j.type()) {
    case V::null:
      return py::none();
    case V::boolean:
      return py::bool_(j.get<bool>());
    case V::number_integer:
      return py::int_(j.get<std::int64_t>());
    case V::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case V::number_float:
      return py::float_(j.get<double>());
    case V::string:
      return py::str(j.get_ref<const std::string&>());
    case V::array: {
      py::list out;
      for (const auto& v : j) out.append(to_python(v));
      return out;
    }
    case V::object: {
      py::dict out;
      for (auto it = j.begin(); it != j.end(); ++it) out[py::str(it.key())] = to_python(*it);
      return out;
    }
    default:
      return py::none();  // binary and discarded values never occur in pronk's documents
  }
}

namespace {

/// Python -> JSON with the limits the file readers keep: nesting at most kMaxJsonDepth
/// levels (deeper recursion would overflow the C++ stack) and no container that holds
/// itself (a cycle has no JSON form). `path` holds the JSON Pointer tokens down to the
/// value in hand, `open` the containers being converted (the cycle check).
class JsonFromPython {
 public:
  JsonFromPython(std::string file, std::string pointer)
      : file_(std::move(file)), base_(std::move(pointer)) {}

  nlohmann::json convert(const py::handle& obj) {
    if (obj.is_none()) return nullptr;
    if (py::isinstance<py::bool_>(obj)) return obj.cast<bool>();
    if (py::isinstance<py::int_>(obj)) return obj.cast<std::int64_t>();
    if (py::isinstance<py::float_>(obj)) return obj.cast<double>();
    if (py::isinstance<py::str>(obj)) return obj.cast<std::string>();
    const bool is_dict = py::isinstance<py::dict>(obj);
    if (is_dict || py::isinstance<py::list>(obj) || py::isinstance<py::tuple>(obj)) {
      enter(obj);
      nlohmann::json out = is_dict ? dict(obj) : list(obj);
      open_.pop_back();
      return out;
    }
    // NumPy: arrays and scalars through their Python equivalents.
    if (py::hasattr(obj, "tolist") && py::hasattr(obj, "dtype")) {
      return convert(obj.attr("tolist")());
    }
    throw py::type_error("cannot be written as JSON: " + py::repr(obj).cast<std::string>());
  }

 private:
  /// Opens a container one level down; InputError past the depth limit or on a cycle.
  void enter(const py::handle& obj) {
    if (std::find(open_.begin(), open_.end(), obj.ptr()) != open_.end()) {
      throw io::InputError(file_, pointer(), "a tree of dicts and lists (JSON has no cycles)",
                           "a container that contains itself");
    }
    if (open_.size() >= io::kMaxJsonDepth) {
      throw io::InputError(
          file_, pointer(),
          "a value nested at most " + std::to_string(io::kMaxJsonDepth) + " levels deep",
          "more than " + std::to_string(io::kMaxJsonDepth) + " levels");
    }
    open_.push_back(obj.ptr());
  }
  nlohmann::json dict(const py::handle& obj) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [k, v] : obj.cast<py::dict>()) {
      if (!py::isinstance<py::str>(k)) {
        throw py::type_error("JSON object keys must be str, found " +
                             py::repr(k).cast<std::string>());
      }
      std::string key = k.cast<std::string>();
      path_.push_back(key);
      out[key] = convert(v);
      path_.pop_back();
    }
    return out;
  }
  nlohmann::json list(const py::handle& obj) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& v : obj) {
      path_.push_back(std::to_string(out.size()));
      out.push_back(convert(v));
      path_.pop_back();
    }
    return out;
  }
  std::string pointer() const {
    std::string p = base_;
    for (const auto& t : path_) p += "/" + io::pointer_escape(t);
    return p;
  }

  std::string file_, base_;
  std::vector<std::string> path_;
  std::vector<PyObject*> open_;
};

}  // namespace

nlohmann::json from_python(const py::handle& obj, const std::string& file,
                           const std::string& pointer) {
  return JsonFromPython(file, pointer).convert(obj);
}

py::array_t<double> to_array(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict table_to_dict(const io::Table& t) {
  py::dict out;
  const size_t rows = t.rows(), cols = t.columns.size();
  for (size_t c = 0; c < cols; ++c) {
    py::array_t<double> a(static_cast<py::ssize_t>(rows));
    double* p = a.mutable_data();
    for (size_t r = 0; r < rows; ++r) p[r] = t.at(r, c);
    out[py::str(t.columns[c])] = std::move(a);
  }
  return out;
}

std::vector<double> vector_arg(const py::handle& x, size_t n, const char* what) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(x);
  if (!a || a.ndim() != 1 || static_cast<size_t>(a.shape(0)) != n) {
    throw py::value_error(std::string(what) + ": expected a sequence of " + std::to_string(n) +
                          " numbers, found " + py::repr(x).cast<std::string>());
  }
  std::vector<double> v(a.data(), a.data() + n);
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) {
      throw py::value_error(std::string(what) + ": expected finite numbers, found " +
                            std::to_string(v[i]) + " at index " + std::to_string(i));
    }
  }
  return v;
}

bool is_path_arg(const py::handle& path_or_dict) {
  return py::isinstance<py::str>(path_or_dict) || py::hasattr(path_or_dict, "__fspath__");
}

nlohmann::json document_arg(const py::handle& path_or_dict, std::string* file) {
  if (is_path_arg(path_or_dict)) {
    *file = py::module_::import("os").attr("fspath")(path_or_dict).cast<std::string>();
    return io::read_json_file(*file);
  }
  if (py::isinstance<py::dict>(path_or_dict)) {
    *file = "<dict>";
    return from_python(path_or_dict, *file);
  }
  throw py::type_error("expected a path (str or os.PathLike) or a dict, found " +
                       py::repr(path_or_dict).cast<std::string>());
}

std::vector<std::string> overrides_arg(const py::handle& overrides) {
  std::vector<std::string> out;
  if (overrides.is_none()) return out;
  if (py::isinstance<py::dict>(overrides)) {
    for (const auto& [k, v] : overrides.cast<py::dict>()) {
      const std::string ptr = k.cast<std::string>();
      out.push_back(ptr + "=" + from_python(v, "overrides", ptr).dump());
    }
    return out;
  }
  if (py::isinstance<py::str>(overrides)) return {overrides.cast<std::string>()};
  for (const auto& o : overrides) out.push_back(o.cast<std::string>());
  return out;
}

int threads_arg(const py::handle& threads) {
  if (!threads.is_none()) {
    // As the CLI's --threads (1 to 1024), with 0 for every core. Any integer (int, NumPy
    // integers: __index__) of any size is read; a bool is no count.
    long long n = -1;
    int overflow = 0;
    if (!py::isinstance<py::bool_>(threads)) {
      const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(threads.ptr()));
      if (index) {
        n = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
      } else {
        PyErr_Clear();
      }
    }
    if (overflow != 0 || n < 0 || n > kMaxThreads) {
      throw py::value_error("threads: expected 0 (all cores) or 1 to " +
                            std::to_string(kMaxThreads) + ", found " +
                            py::repr(threads).cast<std::string>());
    }
    if (n > 0) return static_cast<int>(n);
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? static_cast<int>(std::min<unsigned>(hw, kMaxThreads)) : 1;
}

}  // namespace pronk::python
