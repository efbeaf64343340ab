#include "wheelsim/rig/checkpoint.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace wheelsim::rig {
namespace {

const char *kMagic = "wheelsim-rig-checkpoint";

std::string escape(const std::string &text) {
  std::string out;
  for (char c : text) {
    if (c == '\\')
      out += "\\\\";
    else if (c == '\n')
      out += "\\n";
    else
      out += c;
  }
  return out;
}

std::string unescape(const std::string &text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\\' && i + 1 < text.size()) {
      out += text[i + 1] == 'n' ? '\n' : text[i + 1];
      ++i;
    } else {
      out += text[i];
    }
  }
  return out;
}

void check_key(const std::string &key) {
  if (key.empty() || key.find_first_of(" \t\n") != std::string::npos)
    throw CheckpointError("checkpoint key '" + key + "' must be one word");
}

} // namespace

void CheckpointData::missing(const std::string &key, const char *kind) const {
  throw CheckpointError(source_ + ": no " + kind + " '" + key +
                        "' (a checkpoint of another program version, or a damaged file)");
}

double CheckpointData::number(const std::string &key) const {
  const std::vector<double> &v = numbers(key);
  if (v.size() != 1)
    throw CheckpointError(source_ + ": '" + key + "' holds " + std::to_string(v.size()) +
                          " numbers, expected 1");
  return v[0];
}

const std::vector<double> &CheckpointData::numbers(const std::string &key) const {
  const auto it = numbers_.find(key);
  if (it == numbers_.end())
    missing(key, "number");
  return it->second;
}

std::int64_t CheckpointData::integer(const std::string &key) const {
  const auto it = integers_.find(key);
  if (it == integers_.end())
    missing(key, "integer");
  return it->second;
}

const std::string &CheckpointData::text(const std::string &key) const {
  const auto it = texts_.find(key);
  if (it == texts_.end())
    missing(key, "text");
  return it->second;
}

bool CheckpointData::has(const std::string &key) const {
  return numbers_.count(key) || integers_.count(key) || texts_.count(key);
}

void CheckpointData::write(const std::string &path) const {
  const std::string writing = path + ".writing";
  {
    std::ofstream out(writing, std::ios::trunc);
    if (!out)
      throw CheckpointError("cannot write the rig checkpoint '" + writing +
                            "': " + std::strerror(errno) + " (does its directory exist?)");
    out << kMagic << ' ' << kCheckpointVersion << '\n';
    char buf[40];
    for (const auto &[key, values] : numbers_) {
      check_key(key);
      out << "n " << key << ' ' << values.size();
      for (double v : values) {
        std::snprintf(buf, sizeof buf, " %.17g", v);
        out << buf;
      }
      out << '\n';
    }
    for (const auto &[key, value] : integers_) {
      check_key(key);
      out << "i " << key << ' ' << value << '\n';
    }
    for (const auto &[key, text] : texts_) {
      check_key(key);
      out << "t " << key << ' ' << escape(text) << '\n';
    }
    out << "end\n";
    out.flush();
    if (!out)
      throw CheckpointError("writing the rig checkpoint '" + writing + "' failed");
  }
  if (std::rename(writing.c_str(), path.c_str()) != 0)
    throw CheckpointError("renaming '" + writing + "' onto '" + path +
                          "': " + std::strerror(errno));
}

CheckpointData CheckpointData::read(const std::string &path) {
  std::ifstream in(path);
  if (!in)
    throw CheckpointError("cannot read the rig checkpoint '" + path + "': " + std::strerror(errno));
  CheckpointData data;
  data.source_ = "rig checkpoint '" + path + "'";
  std::string line;
  std::getline(in, line);
  {
    std::istringstream first(line);
    std::string magic;
    int version = 0;
    first >> magic >> version;
    if (magic != kMagic)
      throw CheckpointError(data.source_ + ": not a rig checkpoint (first line '" +
                            line.substr(0, 60) + "')");
    if (version != kCheckpointVersion)
      throw CheckpointError(data.source_ + ": format version " + std::to_string(version) +
                            ", this wheel-rig reads version " + std::to_string(kCheckpointVersion));
  }
  bool complete = false;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line == "end") {
      complete = true;
      break;
    }
    auto bad = [&] {
      return CheckpointError(data.source_ + ": line " + std::to_string(number) +
                             " is malformed: '" + line.substr(0, 80) + "'");
    };
    if (line.size() < 3 || line[1] != ' ')
      throw bad();
    const std::size_t key_end = line.find(' ', 2);
    const std::string key =
        line.substr(2, key_end == std::string::npos ? std::string::npos : key_end - 2);
    const std::string rest = key_end == std::string::npos ? "" : line.substr(key_end + 1);
    if (line[0] == 't') {
      data.texts_[key] = unescape(rest);
    } else if (line[0] == 'i') {
      char *end = nullptr;
      const long long v = std::strtoll(rest.c_str(), &end, 10);
      if (end == rest.c_str())
        throw bad();
      data.integers_[key] = v;
    } else if (line[0] == 'n') {
      const char *p = rest.c_str();
      char *end = nullptr;
      const long long count = std::strtoll(p, &end, 10);
      if (end == p || count < 0)
        throw bad();
      std::vector<double> values;
      values.reserve(static_cast<std::size_t>(count));
      p = end;
      for (long long k = 0; k < count; ++k) {
        const double v = std::strtod(p, &end);
        if (end == p)
          throw bad();
        values.push_back(v);
        p = end;
      }
      data.numbers_[key] = std::move(values);
    } else {
      throw bad();
    }
  }
  if (!complete)
    throw CheckpointError(data.source_ + ": incomplete (no 'end' line)");
  return data;
}

} // namespace wheelsim::rig
