// What the two files of the design reader share (design_reader.cpp: the design itself;
// staged_design_reader.cpp: a staged study's stages, fidelity gap and cross evaluation).
#pragma once

#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "optimize/objective.hpp"
#include "io/load/json_reader.hpp"

namespace pronk::optimize::design_detail {

/// Throws unless `r` has `key` ("a recorded value", "nothing").
void require(const io::JsonReader& r, const std::string& key);
std::string required_string(io::JsonReader& r, const std::string& key);
bool required_bool(io::JsonReader& r, const std::string& key);

/// The object `key` of `node` (read by `parent`): finite numbers whose names `allowed`
/// accepts (`what` says which in the error).
MetricMap read_numbers(io::JsonReader& parent, const nlohmann::json& node, const std::string& key,
                       const std::function<bool(const std::string&)>& allowed,
                       const std::string& what);

/// A staged study's design (`r` reads `design`): its stages, the last one the design itself,
/// the fidelity gap and the optional cross evaluation.
void check_staged_records(io::JsonReader& r, const nlohmann::json& design);

}  // namespace pronk::optimize::design_detail
