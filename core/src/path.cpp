#include "coverbench/path.hpp"

namespace coverbench {

void Path::moveTo(Point p, bool tool) {
  if (!waypoints.empty() && waypoints.back() == p) return;
  if (!waypoints.empty()) tool_on.push_back(tool);
  waypoints.push_back(p);
}

std::string toString(VehicleModel::Kind kind) {
  switch (kind) {
    case VehicleModel::Kind::Holonomic: return "holonomic";
    case VehicleModel::Kind::Gantry: return "gantry";
  }
  return "holonomic";
}

bool parseVehicleKind(const std::string& name, VehicleModel::Kind& kind) {
  for (VehicleModel::Kind k : {VehicleModel::Kind::Holonomic, VehicleModel::Kind::Gantry})
    if (name == toString(k)) {
      kind = k;
      return true;
    }
  return false;
}

}  // namespace coverbench
