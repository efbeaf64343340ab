// Parameters of the rigid tools of the virtual soil lab (bevameter plates, the halves and lid of a
// direct shear box, shear rings, the lifted cylinder of an angle-of-repose test) and their
// validation. Reference: docs/tool-mesh.md.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "plausible.h"

namespace wheelsim::meshes {

/// Thrown for invalid tool parameters; the message names the parameter as on the wheel-mesh tool
/// command line ("LX", "RI", "SEGMENTS", "--max-edge") and the offending value with its unit.
class ToolSpecError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

enum class ToolKind { plate_rect, plate_disc, frame, ring };

/// One tool of the command line: its name, its positional parameters (in order, the optional
/// ones in brackets) and a one-line summary.
struct ToolSyntax {
  ToolKind kind;
  const char *name;       ///< "plate-rect", ...
  const char *parameters; ///< "LX LY T", "R T [SEGMENTS]", ...
  const char *summary;
};

/// The four tools, in the order of the documentation.
const std::vector<ToolSyntax> &tool_syntaxes();
/// "plate-rect", "plate-disc", "frame" or "ring".
const char *to_string(ToolKind kind);

/// A tool in its body frame: centred at the origin (the centre of its bounding box, which is also
/// its centroid), z up, every size in metres. Every tool is a prism along z: a plane region
/// (rectangle, disc, rectangle with a rectangular hole, annulus) extruded from z = -height/2 to
/// +height/2.
struct ToolSpec {
  ToolKind kind = ToolKind::plate_rect;
  /// plate-rect: the plate size along x and y, LX and LY [m]; frame: the size of the hole
  /// (inner size) along x and y [m].
  double lx_m = 0.0;
  double ly_m = 0.0;
  /// plate-disc: the radius R [m]; ring: the outer radius RO [m].
  double radius_m = 0.0;
  /// ring: the inner radius RI [m].
  double inner_radius_m = 0.0;
  /// frame: the wall thickness WALL [m]; the outer size is (LX + 2 WALL) x (LY + 2 WALL).
  double wall_m = 0.0;
  /// Extent along z [m]: the thickness T of the plates, the height H of the frame and the ring.
  double height_m = 0.0;
  /// Round tools: segments around the circle (SEGMENTS); 0 picks them from chord_error and
  /// max_edge_m (segment_count).
  int segments = 0;
  /// Round tools: the largest chord error (sagitta, R (1 - cos(pi / n))) as a fraction of the
  /// (outer) radius, when the segments are not given.
  double chord_error = 1.0e-3;
  /// Largest edge on the flat faces and walls [m] (and along the circle when the segments are
  /// not given); 0: no subdivision, the fewest triangles.
  double max_edge_m = 0.0;

  bool round() const { return kind == ToolKind::plate_disc || kind == ToolKind::ring; }
  /// Half the bounding box along x and y [m] (R for the round tools).
  double half_x_m() const;
  double half_y_m() const;
};

/// Plausible tool sizes [m]; a value outside is rejected at once (docs/tool-mesh.md lists them).
/// Lateral sizes: from the angle-of-repose cylinders and shear rings of a few cm (down to 5 mm
/// for tests) to plates and blades of a few metres.
inline constexpr PlausibleRange kPlausibleToolLength_m{0.005, 5.0};
/// Inner radius RI of a ring (a thin rod's bore up to a large cylinder).
inline constexpr PlausibleRange kPlausibleToolInnerRadius_m{0.001, 5.0};
/// Plate thickness T, frame wall WALL and the ring wall RO - RI (lower bound only).
inline constexpr PlausibleRange kPlausibleToolThickness_m{0.0005, 1.0};
/// Height H of a frame or a ring.
inline constexpr PlausibleRange kPlausibleToolHeight_m{0.001, 5.0};

/// Default chord error of the round tools, as a fraction of the radius: 72 segments, volume
/// 0.13 % below the round tool's.
inline constexpr double kDefaultChordError = 1.0e-3;
/// Allowed range of --chord-error (fraction of the radius).
inline constexpr double kMinChordError = 1.0e-6;
inline constexpr double kMaxChordError = 0.05;
/// Allowed SEGMENTS.
inline constexpr int kMinSegments = 8;
inline constexpr int kMaxSegments = 100000;

/// Segments of a circle whose chord error (sagitta) is at most `fraction` of the radius:
/// the smallest n with 1 - cos(pi / n) <= fraction, rounded up to a multiple of 4 (so vertices
/// lie on the +-x and +-y axes and the bounding box is exactly +-R), at least kMinSegments.
int segments_for_chord_error(double fraction);

/// The segments of a round tool: SEGMENTS when given, else segments_for_chord_error, raised (to
/// a multiple of 4) so that no edge along the outer circle is longer than max_edge_m when it is
/// set. 0 for the rectangular tools.
int segment_count(const ToolSpec &spec);

/// Parts of an interval of `length_m` with edges no longer than `max_edge_m` (1 when it is 0):
/// the subdivision count the estimate and the builder share. A double, because before
/// validate() the count can be too large for an int.
double edge_parts(double length_m, double max_edge_m);

/// Upper estimate of the triangle count, cheap enough to run before the mesh is built.
double estimated_triangle_count(const ToolSpec &spec);

/// Checks the parameters one by one; throws ToolSpecError naming the parameter, the value, the
/// unit and what was expected. Sizes outside the plausible ranges, a hole as large as the body
/// (RI >= RO; WALL <= 0) and meshes of more than kMaxEstimatedTriangles are rejected.
void validate(const ToolSpec &spec);

/// Volume of the ideal tool [m^3] (round tools with true circles).
double ideal_volume_m3(const ToolSpec &spec);

/// One-line human summary, e.g. "ring RI 0.05 m, RO 0.055 m, H 0.1 m, 72 segments".
std::string describe(const ToolSpec &spec);

} // namespace wheelsim::meshes
