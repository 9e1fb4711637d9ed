#pragma once
// What the next click on the bone in a view does, when it is not turning the view (MRML's interaction
// node, small): a panel asks for a landmark to be placed (setPlaceRequest), the view places it on the cut
// bone at the next click that meets the bone and clears the request. The request lives in the document, so
// the panel needs no handle on the view.
#include <optional>

#include "reamsim/core/Node.h"
#include "reamsim/core/ScapulaLandmarks.h"

namespace reamsim {

class InteractionNode : public Node {
 public:
  static constexpr NodeKind kKind = NodeKind::Interaction;
  explicit InteractionNode(std::string name = {}) : Node(std::move(name)) {}
  NodeKind kind() const override { return kKind; }

  // Which landmark of the cut bone the next click on it places; nullopt when none is asked for.
  const std::optional<ScapulaLandmark>& placeRequest() const { return placeRequest_; }
  void setPlaceRequest(std::optional<ScapulaLandmark> which);

 private:
  std::optional<ScapulaLandmark> placeRequest_;
};

}  // namespace reamsim
