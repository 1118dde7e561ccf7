// obstacles: boxes, cylinders and spheres.
#include "io/scenario/Sections.hpp"

namespace fw::io::reader {

void read_obstacles(const Loader& loader, const Field& field, Scenario& scenario) {
  for (const Field& item : loader.items(field)) {
    const MapFields kind(loader, item);
    const std::string shape = the_one_key(loader, kind);
    const MapFields map(loader, *kind.get(shape));
    if (shape == "box") {
      fluid::SolidBox box;
      box.name = loader.text(map.require("name"));
      box.center = loader.vector<3>(map.require("center"));
      box.size = loader.vector<3>(map.require("size"));
      if (const auto yaw = map.get("yaw")) box.yaw_rad = radians(loader.number(*yaw));
      scenario.obstacles.emplace_back(box);
    } else if (shape == "cylinder") {
      fluid::SolidCylinder cylinder;
      cylinder.name = loader.text(map.require("name"));
      cylinder.base = loader.vector<3>(map.require("base"));
      cylinder.radius = loader.number(map.require("radius"));
      cylinder.height = loader.number(map.require("height"));
      scenario.obstacles.emplace_back(cylinder);
    } else {
      fluid::SolidSphere sphere;
      sphere.name = loader.text(map.require("name"));
      sphere.center = loader.vector<3>(map.require("center"));
      sphere.radius = loader.number(map.require("radius"));
      scenario.obstacles.emplace_back(sphere);
    }
  }
}

}  // namespace fw::io::reader
