// Storm damage seen from above (`forestwind render DIR --field damage`): FrameRender's top view of the
// frame's wind (a horizontal slice at `height`, by default render's 10 m; without the deformed trees and
// leaves) and over it every tree of damage.csv as a disc at its root, 0.15 x its height in radius (about a
// crown's, at least kSmallestDisc px), filled with the colour of its max_utilisation on the "utilisation"
// map from 0 to kUtilisationTop (greys up to 1, reds from 1: viz/ColourMap.hpp). A tree broken by the
// frame's time carries a black X, an overturned one a black square, each on a white halo so that it reads
// over any fill. A tree whose failure time is after the frame's is drawn standing, so the frames of a movie
// show the failures appearing; its colour stays its max_utilisation from the file, the largest up to the
// last frame written (damage.csv holds no history), not up to this frame.
// Right of the map, under the wind's colour bar: the utilisation bar with a line at 1, and a legend of the
// three marks with how many trees stand, are broken and are overturned at the frame's time.
//
//   const fw::viz::DamageTable damage = fw::viz::read_damage_table(run.folder() / "damage.csv");
//   const fw::viz::DamageMap map(run.load(frame), damage, run.scenario_name(), {});
//   map.canvas().write_png("out/storm/damage.png");
#pragma once

#include <array>
#include <string>

#include "viz/DamageTable.hpp"
#include "viz/FrameRender.hpp"

namespace fw::viz {

/// The smallest disc radius, px: a short tree far away stays a visible dot with a visible mark.
constexpr double kSmallestDisc = 4.0;

/// The settings DamageMap draws the wind with: `settings` without the trees (RenderSettings::trees false).
/// Throws std::invalid_argument("render: --field damage: draws the top view only ...") for another view, so
/// that a command can refuse it before reading any frame.
RenderSettings damage_map_settings(RenderSettings settings);

class DamageMap {
 public:
  /// Draws `damage` over `frame`. Throws std::invalid_argument("render: --field damage: ...") for a view
  /// other than top, and what FrameRender throws.
  DamageMap(const FrameData& frame, const DamageTable& damage, const std::string& scenario,
            const RenderSettings& settings);

  const Canvas& canvas() const { return picture_.canvas(); }
  /// Where the world lands in the picture.
  const Camera& camera() const { return picture_.camera(); }
  /// The wind picture underneath (its slice, range and map).
  const FrameRender& wind() const { return picture_; }
  /// A tree's disc radius, px.
  double disc_radius(const DamagedTree& tree) const;
  /// How many trees stand, are broken and are overturned at the frame's time.
  const std::array<int, 3>& counts() const { return counts_; }

 private:
  FrameRender picture_;
  std::array<int, 3> counts_{0, 0, 0};
};

}  // namespace fw::viz
