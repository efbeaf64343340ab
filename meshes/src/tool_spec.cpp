#include "tool_spec.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace wheelsim::meshes {
namespace {

void check_positive(const std::string &name, double value, const char *what) {
  if (!(value > 0.0) || !std::isfinite(value))
    fail_value<ToolSpecError>(name, value, "m", std::string(what) + " must be > 0 m");
}

double round_up_to_4(double n) { return 4.0 * std::ceil(n / 4.0); }

/// segment_count before validation, as a double (max_edge_m may ask for absurdly many).
double raw_segment_count(const ToolSpec &s) {
  if (!s.round())
    return 0.0;
  if (s.segments > 0)
    return s.segments;
  double n = segments_for_chord_error(s.chord_error);
  if (s.max_edge_m > 0.0) {
    // A chord of n segments is 2 R sin(pi / n) <= max_edge.
    const double half = std::min(1.0, 0.5 * s.max_edge_m / s.radius_m);
    n = std::max(n, round_up_to_4(std::ceil(M_PI / std::asin(half) - 1e-9)));
  }
  return n;
}

} // namespace

const std::vector<ToolSyntax> &tool_syntaxes() {
  static const std::vector<ToolSyntax> syntaxes{
      {ToolKind::plate_rect, "plate-rect", "LX LY T",
       "rectangular plate (box) LX x LY, thickness T: a bevameter plate, a shear-box lid"},
      {ToolKind::plate_disc, "plate-disc", "R T [SEGMENTS]",
       "circular plate of radius R, thickness T: a round bevameter plate"},
      {ToolKind::frame, "frame", "LX LY WALL H",
       "rectangular open frame: hole LX x LY, wall WALL, height H: a half of a direct shear box"},
      {ToolKind::ring, "ring", "RI RO H [SEGMENTS]",
       "annulus (hollow cylinder) RI..RO, height H: a shear ring, an angle-of-repose cylinder"},
  };
  return syntaxes;
}

const char *to_string(ToolKind kind) {
  for (const auto &s : tool_syntaxes())
    if (s.kind == kind)
      return s.name;
  return "?";
}

double ToolSpec::half_x_m() const {
  switch (kind) {
  case ToolKind::plate_rect:
    return 0.5 * lx_m;
  case ToolKind::frame:
    return 0.5 * lx_m + wall_m;
  default:
    return radius_m;
  }
}

double ToolSpec::half_y_m() const {
  switch (kind) {
  case ToolKind::plate_rect:
    return 0.5 * ly_m;
  case ToolKind::frame:
    return 0.5 * ly_m + wall_m;
  default:
    return radius_m;
  }
}

double edge_parts(double length_m, double max_edge_m) {
  return max_edge_m > 0.0 ? std::max(1.0, std::ceil(length_m / max_edge_m - 1e-9)) : 1.0;
}

int segments_for_chord_error(double fraction) {
  const double n = std::ceil(M_PI / std::acos(1.0 - fraction) - 1e-9);
  return std::max(kMinSegments, static_cast<int>(round_up_to_4(n)));
}

int segment_count(const ToolSpec &spec) { return static_cast<int>(raw_segment_count(spec)); }

double estimated_triangle_count(const ToolSpec &s) {
  const double e = s.max_edge_m, nz = edge_parts(s.height_m, e);
  switch (s.kind) {
  case ToolKind::plate_rect: {
    const double nx = edge_parts(s.lx_m, e), ny = edge_parts(s.ly_m, e);
    return 4.0 * nx * ny + 4.0 * (nx + ny) * nz;
  }
  case ToolKind::frame: {
    const double hx = edge_parts(s.lx_m, e), hy = edge_parts(s.ly_m, e),
                 w = edge_parts(s.wall_m, e);
    const double nx = hx + 2.0 * w, ny = hy + 2.0 * w;
    return 4.0 * nx * ny + 4.0 * (nx + ny + hx + hy) * nz;
  }
  case ToolKind::plate_disc: {
    const double n = raw_segment_count(s);
    return 4.0 * n * edge_parts(s.radius_m, e) + 2.0 * n * nz;
  }
  case ToolKind::ring: {
    const double n = raw_segment_count(s);
    return 4.0 * n * edge_parts(s.radius_m - s.inner_radius_m, e) + 4.0 * n * nz;
  }
  }
  return 0.0;
}

void validate(const ToolSpec &s) {
  switch (s.kind) {
  case ToolKind::plate_rect:
    check_positive("LX", s.lx_m, "the plate length");
    check_positive("LY", s.ly_m, "the plate width");
    check_positive("T", s.height_m, "the plate thickness");
    check_plausible<ToolSpecError>("LX", s.lx_m, kPlausibleToolLength_m, "a plate length");
    check_plausible<ToolSpecError>("LY", s.ly_m, kPlausibleToolLength_m, "a plate width");
    check_plausible<ToolSpecError>("T", s.height_m, kPlausibleToolThickness_m, "a plate thickness");
    break;
  case ToolKind::plate_disc:
    check_positive("R", s.radius_m, "the plate radius");
    check_positive("T", s.height_m, "the plate thickness");
    check_plausible<ToolSpecError>("R", s.radius_m, kPlausibleToolLength_m, "a plate radius");
    check_plausible<ToolSpecError>("T", s.height_m, kPlausibleToolThickness_m, "a plate thickness");
    break;
  case ToolKind::frame:
    check_positive("LX", s.lx_m, "the hole length");
    check_positive("LY", s.ly_m, "the hole width");
    if (!(s.wall_m > 0.0) || !std::isfinite(s.wall_m)) {
      fail_value<ToolSpecError>(
          "WALL", s.wall_m, "m",
          "the wall thickness must be > 0 m (the frame is the hole LX x LY with a wall WALL on "
          "every side; without a wall the hole would be as large as the body)");
    }
    check_positive("H", s.height_m, "the frame height");
    check_plausible<ToolSpecError>("LX", s.lx_m, kPlausibleToolLength_m,
                                   "the hole length of a frame");
    check_plausible<ToolSpecError>("LY", s.ly_m, kPlausibleToolLength_m,
                                   "the hole width of a frame");
    check_plausible<ToolSpecError>("WALL", s.wall_m, kPlausibleToolThickness_m, "a frame wall");
    check_plausible<ToolSpecError>("H", s.height_m, kPlausibleToolHeight_m, "a frame height");
    break;
  case ToolKind::ring: {
    check_positive("RI", s.inner_radius_m, "the inner radius");
    check_positive("RO", s.radius_m, "the outer radius");
    if (!(s.inner_radius_m < s.radius_m)) {
      std::ostringstream os;
      os << "RI " << s.inner_radius_m << " m >= RO " << s.radius_m
         << " m: the hole (inner radius RI) must be smaller than the body (outer radius RO)";
      throw ToolSpecError(os.str());
    }
    check_positive("H", s.height_m, "the ring height");
    check_plausible<ToolSpecError>("RO", s.radius_m, kPlausibleToolLength_m,
                                   "the outer radius of a ring");
    check_plausible<ToolSpecError>("RI", s.inner_radius_m, kPlausibleToolInnerRadius_m,
                                   "the inner radius of a ring");
    const double wall = s.radius_m - s.inner_radius_m;
    if (wall < kPlausibleToolThickness_m.min_m) {
      std::ostringstream os;
      os << "RO - RI = " << wall << " m (RI " << s.inner_radius_m << " m, RO " << s.radius_m
         << " m): the ring wall must be at least " << kPlausibleToolThickness_m.min_m << " m thick";
      throw ToolSpecError(os.str());
    }
    check_plausible<ToolSpecError>("H", s.height_m, kPlausibleToolHeight_m, "a ring height");
    break;
  }
  }
  if (s.round()) {
    if (s.segments != 0 && (s.segments < kMinSegments || s.segments > kMaxSegments)) {
      std::ostringstream os;
      os << "SEGMENTS " << s.segments << ": expected " << kMinSegments << "–" << kMaxSegments
         << " segments around the circle (or leave it out to pick them from --chord-error)";
      throw ToolSpecError(os.str());
    }
    if (!(s.chord_error >= kMinChordError && s.chord_error <= kMaxChordError)) {
      std::ostringstream os;
      os << "--chord-error " << s.chord_error << ": expected a fraction of the radius in ["
         << kMinChordError << ", " << kMaxChordError << "]";
      throw ToolSpecError(os.str());
    }
  }
  if (!(s.max_edge_m >= 0.0) || !std::isfinite(s.max_edge_m)) {
    fail_value<ToolSpecError>("--max-edge", s.max_edge_m, "m",
                              "must be > 0 m (or 0 for no subdivision)");
  }
  const double n = estimated_triangle_count(s);
  if (n > kMaxEstimatedTriangles) {
    std::ostringstream os;
    os << "the mesh of this tool (" << to_string(s.kind) << ") would have about " << n
       << " triangles (at most " << kMaxEstimatedTriangles << "); use a larger --max-edge";
    if (s.round())
      os << ", fewer SEGMENTS or a larger --chord-error";
    throw ToolSpecError(os.str());
  }
}

double ideal_volume_m3(const ToolSpec &s) {
  switch (s.kind) {
  case ToolKind::plate_rect:
    return s.lx_m * s.ly_m * s.height_m;
  case ToolKind::plate_disc:
    return M_PI * s.radius_m * s.radius_m * s.height_m;
  case ToolKind::frame:
    return (4.0 * s.half_x_m() * s.half_y_m() - s.lx_m * s.ly_m) * s.height_m;
  case ToolKind::ring:
    return M_PI * (s.radius_m * s.radius_m - s.inner_radius_m * s.inner_radius_m) * s.height_m;
  }
  return 0.0;
}

std::string describe(const ToolSpec &s) {
  std::ostringstream os;
  os << to_string(s.kind) << " ";
  switch (s.kind) {
  case ToolKind::plate_rect:
    os << "LX " << s.lx_m << " m x LY " << s.ly_m << " m, T " << s.height_m << " m";
    break;
  case ToolKind::plate_disc:
    os << "R " << s.radius_m << " m, T " << s.height_m << " m";
    break;
  case ToolKind::frame:
    os << "hole LX " << s.lx_m << " m x LY " << s.ly_m << " m, WALL " << s.wall_m << " m (outer "
       << 2.0 * s.half_x_m() << " m x " << 2.0 * s.half_y_m() << " m), H " << s.height_m << " m";
    break;
  case ToolKind::ring:
    os << "RI " << s.inner_radius_m << " m, RO " << s.radius_m << " m, H " << s.height_m << " m";
    break;
  }
  if (s.round())
    os << ", " << segment_count(s) << " segments";
  if (s.max_edge_m > 0.0)
    os << ", max edge " << s.max_edge_m << " m";
  return os.str();
}

} // namespace wheelsim::meshes
