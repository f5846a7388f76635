// A user's mesh against the track: its footprint rectangles matched to the track's footprints.
// A mismatch blames the track, not the file, so its messages differ from the import's checks and
// live on their own.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "mesh/gmsh_model.hpp"
#include "mesh/gmsh_reading.hpp"

namespace rumble::fem {

namespace {

/// x to 1 nm, for messages (a centre at -1e-17 m reads 0).
double nm(double x) {
  const double r = std::round(x * 1e9) / 1e9;
  return r == 0.0 ? 0.0 : r;
}

}  // namespace

double mesh_footprint_tolerance(const Footprint& f) {
  return std::max(1e-3, 0.02 * std::min(f.length, f.width));
}

void check_mesh_footprints(const MeshFile& file, const std::vector<Footprint>& footprints) {
  const std::string where = where_file(file.path);
  // A mesh made for another track: the track's footprints are blamed (the engine reports a
  // layout refusal that names no "fem: params/<key>:" at /track/sleepers), the file named.
  const std::string mismatch =
      "fem: the track's footprints do not fit the mesh of params/mesh/file '" + file.path + "'";
  std::ostringstream track;
  track.precision(6);
  track << "the track has " << footprints.size() << " footprint(s)";
  if (!footprints.empty()) {
    const Footprint& a = footprints.front();
    const Footprint& b = footprints.back();
    track << ", " << a.length << " m x " << a.width
          << " m (across x along), centred at x = " << a.x;
    if (footprints.size() > 1)
      track << " .. " << b.x << " m every "
            << (b.x - a.x) / static_cast<double>(footprints.size() - 1);
    track << " m, y = " << a.y << " m";
  }
  if (!file.has_footprints)
    throw std::invalid_argument(
        where + " has no physical surface \"footprints\" (it has: " + quoted_list(file.surfaces) +
        "); " + track.str() +
        ": embed each footprint's rectangle in the ground and put them in a physical surface "
        "\"footprints\"");
  if (file.footprints.size() != footprints.size()) {
    std::ostringstream m;
    m.precision(6);
    m << mismatch << " has " << file.footprints.size()
      << " footprint rectangle(s) in its physical surface \"footprints\"";
    if (!file.footprints.empty())
      m << " (centred at x = " << nm(file.footprints.front().centre_x()) << " .. "
        << nm(file.footprints.back().centre_x()) << " m)";
    m << "; " << track.str()
      << ": mesh one rectangle per footprint (rectangles must not touch), or change "
         "/track/sleepers to the mesh's";
    throw std::invalid_argument(m.str());
  }
  for (std::size_t j = 0; j < footprints.size(); ++j) {
    const Footprint& f = footprints[j];
    const MeshFootprint* nearest = nullptr;
    double best = std::numeric_limits<double>::max();
    for (const MeshFootprint& p : file.footprints) {
      const double d = std::hypot(p.centre_x() - f.x, p.centre_y() - f.y);
      if (d < best) {
        best = d;
        nearest = &p;
      }
    }
    const double tol = mesh_footprint_tolerance(f);
    const MeshFootprint& p = *nearest;
    if (std::abs(p.centre_x() - f.x) <= tol && std::abs(p.centre_y() - f.y) <= tol &&
        std::abs((p.x1 - p.x0) - f.width) <= tol && std::abs((p.y1 - p.y0) - f.length) <= tol)
      continue;
    std::ostringstream m;
    m.precision(6);
    m << mismatch << ": footprint " << j << " of the track (centre x " << f.x << " m, y " << f.y
      << " m, " << f.length << " m x " << f.width << " m) has no rectangle of the physical "
      << "surface \"footprints\" within " << tol << " m; the nearest is centred at x "
      << nm(p.centre_x()) << " m, y " << nm(p.centre_y()) << " m, " << nm(p.y1 - p.y0) << " m x "
      << nm(p.x1 - p.x0) << " m; " << track.str()
      << ": place the mesh's footprints at the track's, or change /track/sleepers";
    throw std::invalid_argument(m.str());
  }
}

}  // namespace rumble::fem
