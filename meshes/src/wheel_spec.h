// Parameters of a rigid lugged wheel (TERRAMECHANICS.md §7) and their validation.
#pragma once

#include <stdexcept>
#include <string>

#include "plausible.h"

namespace wheelsim::meshes {

/// Thrown for invalid wheel parameters; the message names the option (as on the wheel-mesh
/// command line, e.g. "--lug-height") and the offending value with its unit.
class WheelSpecError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

enum class LugType { straight, combined, nondirectional };

/// "straight", "combined" or "nondirectional".
const char *to_string(LugType type);
/// Parses a lug type name; throws WheelSpecError naming --type otherwise.
LugType parse_lug_type(const std::string &name);

/// Resolution of the generated surface.
struct Resolution {
  /// Maximum arc length of one circumferential segment on the outer radius [m].
  double max_arc_m = 0.008;
  /// Maximum angle of one circumferential segment [deg] (governs small wheels).
  double max_angle_deg = 3.0;
  /// Maximum edge length across the width (y) and radially on the side discs [m].
  double max_width_edge_m = 0.02;
};

/// A wheel in the wheel frame: centre at the origin, axle along +y (y in [-w/2, w/2]), x forward,
/// z up. Forward travel along +x is rolling with angular velocity +omega about +y.
struct WheelSpec {
  /// Outer diameter over the lugs D0 [m] (the cylinder diameter when smooth).
  double diameter_m = 0.0;
  /// Width w [m].
  double width_m = 0.0;
  /// Smooth cylinder of diameter D0: no lugs, the lug parameters are unused.
  bool smooth = false;
  /// Lug count nl (>= 1 unless smooth).
  int lug_count = 0;
  /// Lug height lh [m]; the rim radius is D0/2 - lh.
  double lug_height_m = 0.0;
  /// Lug width (thickness) [m], measured on the lug top perpendicular to the lug centreline.
  double lug_width_m = 0.040;
  /// Lug angle delta [deg] between the lug (arm) and the axle direction, in [0, 70].
  double lug_angle_deg = 0.0;
  /// Lug centre length h [m]: the axle-parallel centre segment (combined) or the overlap of the
  /// two half-lugs across the mid-plane (nondirectional). Unused for straight lugs.
  double centre_length_m = 0.0;
  LugType type = LugType::straight;
  Resolution resolution;

  double outer_radius_m() const { return 0.5 * diameter_m; }
  double rim_radius_m() const {
    return smooth ? 0.5 * diameter_m : 0.5 * diameter_m - lug_height_m;
  }
};

/// Smallest allowed clearance between neighbouring lugs on the lug top [m]: lugs closer than
/// this would touch (or leave sliver triangles) and are rejected.
inline constexpr double kMinLugClearance_m = 0.001;

/// Plausible wheel sizes [m]: a value outside is almost surely millimetres given for metres (or
/// a typo), and the generator would spend minutes on a wheel hundreds of metres across at a
/// millimetre resolution. From planetary-rover wheels (D0 ~ 0.1-0.3 m, lugs of a few mm) to large
/// tyres (D0 up to ~4 m). docs/wheel-mesh.md lists them.
inline constexpr PlausibleRange kPlausibleDiameter_m{0.05, 5.0};
inline constexpr PlausibleRange kPlausibleWidth_m{0.01, 3.0};
inline constexpr PlausibleRange kPlausibleLugHeight_m{0.0005, 0.5};
inline constexpr PlausibleRange kPlausibleLugWidth_m{0.0005, 0.5};

/// Upper estimate of the triangle count from the size and the resolution (tread: circumferential
/// segments x width bands x 2, times 2 for the lugs' walls; side discs: rings x segments x 2
/// each), cheap enough to run before the mesh is built.
double estimated_triangle_count(const WheelSpec &spec);

/// Checks the parameters one by one; throws WheelSpecError naming the option. Sizes outside the
/// plausible ranges above and resolutions giving more than kMaxEstimatedTriangles are rejected
/// at once. Lug overlap is checked by build_wheel_mesh, which knows the footprint.
void validate(const WheelSpec &spec);

/// One-line human summary, e.g. "D0 1.234 m, w 0.479 m, 15 combined lugs, lh 0.06 m, ...".
std::string describe(const WheelSpec &spec);

} // namespace wheelsim::meshes
