#include "wheelsim/config_messages.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace wheelsim::config {

std::size_t edit_distance(const std::string &a, const std::string &b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string closest(const std::string &word, const std::vector<std::string> &candidates) {
  std::string best;
  std::size_t best_score = static_cast<std::size_t>(-1);
  for (const auto &c : candidates) {
    std::size_t score;
    if (word.size() >= 3 &&
        (c.find(word) != std::string::npos || word.find(c) != std::string::npos))
      score = 0;
    else {
      const std::size_t d = edit_distance(word, c);
      if (d > std::max<std::size_t>(2, word.size() / 3))
        continue;
      score = d;
    }
    if (score < best_score) {
      best_score = score;
      best = c;
    }
  }
  return best;
}

const char *type_name(const toml::node &n) {
  switch (n.type()) {
  case toml::node_type::string:
    return "a string";
  case toml::node_type::integer:
    return "an integer";
  case toml::node_type::floating_point:
    return "a number";
  case toml::node_type::boolean:
    return "a boolean";
  case toml::node_type::table:
    return "a table";
  case toml::node_type::array:
    return "an array";
  default:
    return "a date/time";
  }
}

std::string located(const std::string &source_name, const toml::node *where,
                    const std::string &message) {
  std::ostringstream os;
  os << source_name;
  if (where && where->source().begin.line > 0)
    os << ':' << where->source().begin.line;
  os << ": " << message;
  return os.str();
}

std::string syntax_error(const toml::parse_error &error, const std::string &source_name) {
  std::ostringstream os;
  os << source_name << ':' << error.source().begin.line
     << ": TOML syntax error: " << error.description();
  return os.str();
}

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

std::string json_string(const std::string &s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\t':
      out += "\\t";
      break;
    case '\r':
      out += "\\r";
      break;
    default:
      if (static_cast<unsigned char>(c) < 0x20) {
        char buffer[8];
        std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
        out += buffer;
      } else {
        out += c;
      }
    }
  }
  return out + "\"";
}

} // namespace wheelsim::config
