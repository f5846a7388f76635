// Peak particle velocity (PPV): the largest magnitude of the ground's velocity over a record,
// per component (the seed paper shows the vertical one) and as the three-component vector sum
// (sometimes called PVS or PCPV: it is never smaller than any component's peak). Velocities in
// m/s, times in s.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace rumble::post {

/// A peak and where it is: value = |v[index]| (or |v|(index) for a vector).
struct Peak {
  double value = 0.0;     // m/s; NaN when the signal holds a NaN
  std::size_t index = 0;  // sample of the (first) peak
};

/// max_k |v_k|. An empty signal gives 0.
Peak peak_abs(std::span<const double> v);

/// max_k sqrt(vx_k^2 + vy_k^2 + vz_k^2), the three-component PPV. The spans must have equal
/// lengths (std::invalid_argument otherwise).
Peak peak_vector(std::span<const double> vx, std::span<const double> vy,
                 std::span<const double> vz);

/// One receiver's peaks, for a PPV-versus-distance table.
struct ReceiverPpv {
  std::string name;
  double distance = 0.0;  // m, horizontal distance from the track axis
  double depth = 0.0;     // m below the surface
  double ppv_z = 0.0;     // m/s, vertical
  double ppv_3c = 0.0;    // m/s, vector sum; NaN when only the vertical component was recorded
};

/// The receivers ordered by distance from the track (then by depth, then by name), as plotted
/// in the paper's PPV-versus-distance figures.
std::vector<ReceiverPpv> ppv_versus_distance(std::vector<ReceiverPpv> receivers);

}  // namespace rumble::post
