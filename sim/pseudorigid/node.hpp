// A reference to a point a force can act on: a mass, a ghost point of a body,
// or a grounded anchor.
#pragma once

namespace pronk::pseudorigid {

struct NodeRef {
  enum class Kind { kMass, kGhost, kAnchor };
  Kind kind = Kind::kMass;
  int index = 0;  ///< into Mechanism::masses, ghost_points or anchors
  bool operator==(const NodeRef&) const = default;
};

}  // namespace pronk::pseudorigid
