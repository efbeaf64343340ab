#include "wheel_surface_vtk.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <unistd.h>
#include <utility>

namespace wheelsim {

bool write_wheel_surface_vtk(const std::string &path, const geometry::TriangleMesh &mesh,
                             const WheelPose &state, const std::vector<double> &pressure_Pa,
                             const std::vector<double> &contact_count, long step, double time_s) {
  FILE *out = std::fopen(path.c_str(), "w");
  if (out == nullptr)
    return false;
  const Eigen::Matrix3d R = state.q_WB.toRotationMatrix();
  std::fprintf(out, "# vtk DataFile Version 3.0\n");
  std::fprintf(out, "wheelsim wheel surface, step %ld, time %.9g s\n", step, time_s);
  std::fprintf(out, "ASCII\nDATASET POLYDATA\nPOINTS %zu double\n", mesh.vertices_m.size());
  for (const Eigen::Vector3d &v : mesh.vertices_m) {
    const Eigen::Vector3d w = state.p_WB_W + R * v;
    std::fprintf(out, "%.9g %.9g %.9g\n", w.x(), w.y(), w.z());
  }
  const std::size_t nt = mesh.triangles.size();
  std::fprintf(out, "POLYGONS %zu %zu\n", nt, 4 * nt);
  for (const auto &t : mesh.triangles)
    std::fprintf(out, "3 %d %d %d\n", t[0], t[1], t[2]);
  std::fprintf(out, "CELL_DATA %zu\nSCALARS contact_pressure double 1\nLOOKUP_TABLE default\n", nt);
  for (std::size_t i = 0; i < nt; ++i)
    std::fprintf(out, "%.6g\n", i < pressure_Pa.size() ? pressure_Pa[i] : 0.0);
  std::fprintf(out, "SCALARS contact_count double 1\nLOOKUP_TABLE default\n");
  for (std::size_t i = 0; i < nt; ++i)
    std::fprintf(out, "%.6g\n", i < contact_count.size() ? contact_count[i] : 0.0);
  const bool ok = std::ferror(out) == 0;
  return std::fclose(out) == 0 && ok;
}

namespace {

std::string xml_escape(const std::string &text) {
  std::string out;
  for (char c : text) {
    switch (c) {
    case '&':
      out += "&amp;";
      break;
    case '<':
      out += "&lt;";
      break;
    case '>':
      out += "&gt;";
      break;
    case '"':
      out += "&quot;";
      break;
    default:
      out += c;
    }
  }
  return out;
}

std::string xml_unescape(const std::string &text) {
  static const char *const names[][2] = {
      {"&amp;", "&"}, {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}};
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    bool replaced = false;
    for (const auto &n : names) {
      const std::string entity = n[0];
      if (text.compare(i, entity.size(), entity) == 0) {
        out += n[1];
        i += entity.size();
        replaced = true;
        break;
      }
    }
    if (!replaced)
      out += text[i++];
  }
  return out;
}

/// The value of `name="..."` in `line` (false if absent).
bool xml_attribute(const std::string &line, const std::string &name, std::string &value) {
  const std::string key = " " + name + "=\"";
  const std::size_t begin = line.find(key);
  if (begin == std::string::npos)
    return false;
  const std::size_t first = begin + key.size();
  const std::size_t end = line.find('"', first);
  if (end == std::string::npos)
    return false;
  value = xml_unescape(line.substr(first, end - first));
  return true;
}

} // namespace

bool write_pvd(const std::string &path, const std::vector<PvdEntry> &entries) {
  const std::string tmp = path + ".tmp";
  FILE *out = std::fopen(tmp.c_str(), "w");
  if (out == nullptr)
    return false;
  std::fprintf(out, "<?xml version=\"1.0\"?>\n"
                    "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                    "  <Collection>\n");
  for (const PvdEntry &e : entries)
    std::fprintf(out, "    <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" file=\"%s\"/>\n",
                 e.time_s, xml_escape(e.file).c_str());
  std::fprintf(out, "  </Collection>\n</VTKFile>\n");
  bool ok = std::ferror(out) == 0 && std::fflush(out) == 0 && fsync(fileno(out)) == 0;
  ok = std::fclose(out) == 0 && ok;
  if (ok && std::rename(tmp.c_str(), path.c_str()) == 0)
    return true;
  std::remove(tmp.c_str());
  return false;
}

PvdSeries::PvdSeries(std::string prefix) : prefix_(std::move(prefix)), pvd_path_(prefix_ + ".pvd") {
  const std::size_t slash = prefix_.find_last_of('/');
  file_stem_ = (slash == std::string::npos ? prefix_ : prefix_.substr(slash + 1)) + "_";
}

std::string PvdSeries::vtk_path(long step) const {
  return prefix_ + "_" + std::to_string(step) + ".vtk";
}

void PvdSeries::keep_earlier_entries(long step) {
  std::ifstream in(pvd_path_);
  std::string line;
  while (std::getline(in, line)) {
    std::string time, file;
    if (line.find("<DataSet") == std::string::npos || !xml_attribute(line, "timestep", time) ||
        !xml_attribute(line, "file", file))
      continue;
    // only this series' own files: FILE_STEM<step>.vtk
    if (file.size() <= file_stem_.size() + 4 || file.compare(0, file_stem_.size(), file_stem_) ||
        file.compare(file.size() - 4, 4, ".vtk"))
      continue;
    const std::string digits = file.substr(file_stem_.size(), file.size() - file_stem_.size() - 4);
    char *end = nullptr;
    errno = 0;
    const long file_step = std::strtol(digits.c_str(), &end, 10);
    char *time_end = nullptr;
    const double time_s = std::strtod(time.c_str(), &time_end);
    if (errno != 0 || *end != '\0' || digits.empty() || *time_end != '\0' || time.empty())
      continue;
    if (file_step < step)
      entries_.push_back({file_step, time_s, file});
  }
}

bool PvdSeries::add(long step, double time_s) {
  if (!started_) {
    started_ = true;
    keep_earlier_entries(step);
  }
  const std::string file = file_stem_ + std::to_string(step) + ".vtk";
  const auto same = std::find_if(entries_.begin(), entries_.end(),
                                 [step](const PvdEntry &e) { return e.step == step; });
  if (same != entries_.end())
    *same = {step, time_s, file};
  else
    entries_.push_back({step, time_s, file});
  std::stable_sort(entries_.begin(), entries_.end(),
                   [](const PvdEntry &a, const PvdEntry &b) { return a.step < b.step; });
  return write_pvd(pvd_path_, entries_);
}

} // namespace wheelsim
