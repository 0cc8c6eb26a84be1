#include "app/map_report_text.hpp"

#include <cstdio>

namespace pronk::app {

std::string disagreement_sentence(const nlohmann::json& d, const std::string& axis) {
  const nlohmann::json& first = d.at("first_disagreement");
  const nlohmann::json& upto = d.at("no_disagreement_up_to");
  if (first.is_null()) return "none anywhere on the grid (" + axis + " up to " + upto.dump() + ")";
  if (upto.is_null()) return "the first already at the grid's first " + axis + " = " + first.dump();
  return "none up to " + axis + " = " + upto.dump() + ", the first at " + first.dump();
}

std::string boundary_sentence(const optimize::map::BoundaryResult& b, const std::string& axis) {
  const std::string head = "boundary row " + std::to_string(b.row) + ": " + b.status;
  if (b.status == "none_good") return head + ": no " + axis + " on the grid stabilized every trial";
  char value[32];
  std::snprintf(value, sizeof value, "%.6g", b.boundary);
  return head + " " + axis + " = " + value;
}

}  // namespace pronk::app
