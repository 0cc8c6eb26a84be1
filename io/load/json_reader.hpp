// A strict reader over one JSON object: every key read is recorded, and
// finish() rejects the keys nobody asked for (typos must not be silently
// ignored). Every error is an InputError naming file, JSON Pointer, what was
// expected and what was found.
#pragma once

#include <array>
#include <initializer_list>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "io/load/input_error.hpp"
#include "io/load/json_text.hpp"

namespace pronk::io {

using json = nlohmann::json;

/// Largest magnitude of a number read without an explicit bound: every derived
/// quantity (energies, forces, their products) stays far inside the double range.
inline constexpr double kMaxInputMagnitude = 1e12;
/// Physical bounds of the loaders: masses [kg], gravity components [m/s^2].
inline constexpr double kMinMass = 1e-6, kMaxMass = 1e6, kMaxGravity = 1e3;
/// Short description of a JSON value for error messages ("string \"abc\"").
std::string describe(const json& value);

/// Whether doc is an object whose key holds exactly want (of want's type): a tag such as
/// "type" read without nlohmann's value(), which throws when the key holds another type.
inline bool holds(const json& doc, const char* key, const json& want) {
  return doc.is_object() && doc.contains(key) && doc.at(key) == want;
}
/// Escapes a key for use in a JSON Pointer (RFC 6901).
std::string pointer_escape(const std::string& key);
/// The value at JSON Pointer `pointer` (RFC 6901) in `doc` (`doc` itself for ""), or nullptr
/// when there is none: a pointer that does not start with '/', an escape other than ~0 and
/// ~1, a missing key, a token below a number or string, an array index that is not a plain
/// decimal (no sign, no leading zero, not "-") below the array's size. Never throws: a
/// pointer from the user must not reach nlohmann's own exceptions.
const json* find_pointer(const json& doc, const std::string& pointer);
json* find_pointer(json& doc, const std::string& pointer);

/// Longest name pronk uses as a file or directory name (NAME_MAX of Linux file systems).
inline constexpr std::size_t kMaxPathNameBytes = 255;
/// Why `name` cannot be one component of an output path ("" when it can): it must be
/// non-empty, at most kMaxPathNameBytes bytes, not "." or "..", and hold no '/' and no
/// control character (bytes below 0x20, and 0x7f).
std::string path_name_problem(const std::string& name);

class JsonReader {
 public:
  /// Reads the object `node` found at `pointer` of `file`. Throws if it is not an object.
  JsonReader(const json& node, std::string file, std::string pointer);

  bool has(const std::string& key) const;
  /// Declares an optional key as known (read elsewhere or absent).
  void optional(const std::string& key) { read_.insert(key); }
  /// A sub-object (required).
  JsonReader object(const std::string& key);
  /// Array of sub-objects.
  std::vector<JsonReader> object_array(const std::string& key);

  /// A finite number in [lo, hi]; required. An infinite bound stands for
  /// kMaxInputMagnitude (so does every unbounded number below).
  double number(const std::string& key, double lo = -std::numeric_limits<double>::infinity(),
                double hi = std::numeric_limits<double>::infinity());
  /// A finite number in [lo, hi] or `fallback` when absent.
  double number_or(const std::string& key, double fallback,
                   double lo = -std::numeric_limits<double>::infinity(),
                   double hi = std::numeric_limits<double>::infinity());
  /// A number in (0, kMaxInputMagnitude] (or fallback when absent).
  double positive_or(const std::string& key, double fallback);
  long integer_or(const std::string& key, long fallback, long lo, long hi);
  bool boolean_or(const std::string& key, bool fallback);
  std::string string_or(const std::string& key, const std::string& fallback);
  /// A string used as a file or directory name (a scene's or study's "name": the default
  /// output directory): see path_name_problem.
  std::string path_name_or(const std::string& key, const std::string& fallback);
  /// A string that must be one of `choices`.
  std::string choice_or(const std::string& key, const std::string& fallback,
                        std::initializer_list<const char*> choices);
  std::string choice_or(const std::string& key, const std::string& fallback,
                        const std::vector<std::string>& choices);
  /// Array of exactly n finite numbers, each in [lo, hi].
  Eigen::VectorXd vector(const std::string& key, int n,
                         double lo = -std::numeric_limits<double>::infinity(),
                         double hi = std::numeric_limits<double>::infinity());
  Eigen::Vector3d vec3_or(const std::string& key, const Eigen::Vector3d& fallback);
  /// rows x cols matrix given as an array of rows.
  Eigen::MatrixXd matrix(const std::string& key, int rows, int cols);
  /// Array of [x, y, z] points, between min_n and max_n of them.
  std::vector<Eigen::Vector3d> vec3_list(const std::string& key, size_t min_n, size_t max_n);
  /// Array of non-empty arrays of distinct integers in [0, max_index].
  std::vector<std::vector<int>> index_groups(const std::string& key, long max_index);
  /// Array of integers in [lo, hi].
  std::vector<long> integer_array_or(const std::string& key, long lo, long hi);

  /// Throws for the first key that was never read.
  void finish() const;

  /// Builds an error at this object's key (or at the object itself if key empty).
  InputError error(const std::string& key, const std::string& expected,
                   const std::string& found) const;
  const std::string& pointer() const { return pointer_; }
  const std::string& file() const { return file_; }
  std::string pointer_of(const std::string& key) const;

 private:
  const json& get(const std::string& key);
  const json* node_;
  std::string file_;
  std::string pointer_;
  std::set<std::string> read_;
};

}  // namespace pronk::io
