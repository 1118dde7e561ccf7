// obstacles: boxes, cylinders and spheres.
#include "io/scenario/Obstacles.hpp"

#include "io/schema/ObstacleKeys.hpp"
#include "io/settings/Radians.hpp"

namespace fw::io::reader {

namespace {

fluid::SolidBox read_box(const Loader& loader, const Field& field) {
  const Section<schema::kObstacleKeys, "obstacles[].box"> map(loader, field);
  fluid::SolidBox box;
  box.name = loader.text(map.require<"name">());
  box.center = loader.vector<3>(map.require<"center">());
  box.size = loader.vector<3>(map.require<"size">());
  if (const auto yaw = map.get<"yaw">()) box.yaw_rad = radians(loader.number(*yaw));
  return box;
}

fluid::SolidCylinder read_cylinder(const Loader& loader, const Field& field) {
  const Section<schema::kObstacleKeys, "obstacles[].cylinder"> map(loader, field);
  fluid::SolidCylinder cylinder;
  cylinder.name = loader.text(map.require<"name">());
  cylinder.base = loader.vector<3>(map.require<"base">());
  cylinder.radius = loader.number(map.require<"radius">());
  cylinder.height = loader.number(map.require<"height">());
  return cylinder;
}

fluid::SolidSphere read_sphere(const Loader& loader, const Field& field) {
  const Section<schema::kObstacleKeys, "obstacles[].sphere"> map(loader, field);
  fluid::SolidSphere sphere;
  sphere.name = loader.text(map.require<"name">());
  sphere.center = loader.vector<3>(map.require<"center">());
  sphere.radius = loader.number(map.require<"radius">());
  return sphere;
}

}  // namespace

std::vector<Obstacle> read_obstacles(const Loader& loader, const Field& field) {
  std::vector<Obstacle> obstacles;
  for (const Field& item : loader.items(field)) {
    const Section<schema::kObstacleKeys, "obstacles[]"> kind(loader, item);
    kind.exactly_one();
    if (const auto box = kind.get<"box">()) obstacles.emplace_back(read_box(loader, *box));
    if (const auto cylinder = kind.get<"cylinder">())
      obstacles.emplace_back(read_cylinder(loader, *cylinder));
    if (const auto sphere = kind.get<"sphere">()) obstacles.emplace_back(read_sphere(loader, *sphere));
  }
  return obstacles;
}

}  // namespace fw::io::reader
