#include "reamsim/core/InteractionNode.h"

namespace reamsim {

void InteractionNode::setPlaceRequest(std::optional<ScapulaLandmark> which) {
  placeRequest_ = which;
  markModified();
}

}  // namespace reamsim
