// Private to wheelsim_rig: typed, range-checked reading of one table of a rig config (TOML), with
// messages that name the key, the expected range with its unit and the value found
// (docs/rig-config.md). Used by the per-table parsers (rig_tables.cpp, slip_modes.cpp, terrains/).
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "wheelsim/config_messages.h"
#include "wheelsim/rig/rig_config.h"

namespace wheelsim::rig::detail {

using config::closest;
using config::fmt;
using config::type_name;

class Parser {
public:
  Parser(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const toml::node *where, const std::string &message) const {
    throw RigConfigError(config::located(source_, where, message));
  }

  const std::string &source() const { return source_; }

private:
  std::string source_;
};

/// One table of the document, with typed, range-checked getters.
class Table {
public:
  Table(const Parser &p, const toml::table *t, std::string name)
      : p_(p), t_(t), name_(std::move(name)) {}

  bool present() const { return t_ != nullptr; }
  const Parser &parser() const { return p_; }
  /// Fails at the table itself (a missing key): "<source>:<line>: <message>".
  [[noreturn]] void fail_table(const std::string &message) const { p_.fail(t_, message); }
  bool has(const std::string &key) const { return t_ && t_->get(key); }
  const toml::node *node(const std::string &key) const { return t_ ? t_->get(key) : nullptr; }
  std::string full(const std::string &key) const { return name_ + "." + key; }

  [[noreturn]] void fail(const std::string &key, const std::string &message) const {
    p_.fail(node(key) ? node(key) : static_cast<const toml::node *>(t_), message);
  }

  std::optional<double> number(const std::string &key, const std::string &unit) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    if (auto i = n->as_integer())
      return static_cast<double>(i->get());
    if (auto f = n->as_floating_point()) {
      if (!std::isfinite(f->get()))
        fail(key, full(key) + " must be a finite number in " + unit + ", got " + fmt(f->get()));
      return f->get();
    }
    fail(key, full(key) + " must be a number in " + unit + ", got " + type_name(*n));
  }

  std::optional<long long> integer(const std::string &key, const std::string &unit) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    if (auto i = n->as_integer())
      return i->get();
    fail(key, full(key) + " must be an integer (" + unit + "), got " + type_name(*n));
  }

  std::optional<std::string> string(const std::string &key) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    if (auto s = n->as_string())
      return s->get();
    fail(key, full(key) + " must be a string, got " + type_name(*n));
  }

  std::optional<bool> boolean(const std::string &key) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    if (auto b = n->as_boolean())
      return b->get();
    fail(key, full(key) + " must be true or false, got " + type_name(*n));
  }

  /// An array of numbers (integers allowed), each finite.
  std::optional<std::vector<double>> numbers(const std::string &key,
                                             const std::string &unit) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    const toml::array *a = n->as_array();
    if (!a)
      fail(key, full(key) + " must be an array of numbers in " + unit + ", got " + type_name(*n));
    std::vector<double> out;
    for (const toml::node &e : *a) {
      if (auto i = e.as_integer())
        out.push_back(static_cast<double>(i->get()));
      else if (auto f = e.as_floating_point(); f && std::isfinite(f->get()))
        out.push_back(f->get());
      else
        fail(key, full(key) + " must be an array of finite numbers in " + unit +
                      ", got an "
                      "element that is " +
                      type_name(e));
    }
    return out;
  }

  std::optional<std::vector<std::string>> strings(const std::string &key) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    const toml::array *a = n->as_array();
    if (!a)
      fail(key, full(key) + " must be an array of strings, got " + type_name(*n));
    std::vector<std::string> out;
    for (const toml::node &e : *a) {
      if (auto str = e.as_string())
        out.push_back(str->get());
      else
        fail(key,
             full(key) + " must be an array of strings, got an element that is " + type_name(e));
    }
    return out;
  }

  std::string choice(const std::string &key, const std::vector<std::string> &allowed,
                     const std::optional<std::string> &fallback) const {
    const auto v = string(key);
    std::string list;
    for (const auto &a : allowed)
      list += (list.empty() ? "\"" : ", \"") + a + "\"";
    if (!v) {
      if (fallback)
        return *fallback;
      p_.fail(t_, "missing key '" + full(key) + "': write " + full(key) + " = one of " + list);
    }
    if (std::find(allowed.begin(), allowed.end(), *v) == allowed.end()) {
      std::string msg = full(key) + " must be one of " + list + ", got \"" + *v + "\"";
      const std::string c = closest(*v, allowed);
      if (!c.empty())
        msg += "; did you mean \"" + c + "\"?";
      fail(key, msg);
    }
    return *v;
  }

  /// A number that must satisfy `ok`; `range` reads like "> 0" and the message is
  /// "<table.key> must be <range> <unit>, got <value>".
  template <class Ok>
  std::optional<double> checked(const std::string &key, const std::string &unit, const char *range,
                                Ok ok) const {
    const auto v = number(key, unit);
    if (v && !ok(*v))
      fail(key,
           full(key) + " must be " + range + (unit.empty() ? "" : " ") + unit + ", got " + fmt(*v));
    return v;
  }
  std::optional<double> positive(const std::string &key, const std::string &unit) const {
    return checked(key, unit, "> 0", [](double v) { return v > 0; });
  }
  std::optional<double> non_negative(const std::string &key, const std::string &unit) const {
    return checked(key, unit, ">= 0", [](double v) { return v >= 0; });
  }
  double required(const std::optional<double> &v, const std::string &key,
                  const std::string &what) const {
    if (!v)
      p_.fail(t_, "missing key '" + full(key) + "': write " + full(key) + " = <" + what + ">");
    return *v;
  }
  /// Rejects keys of this table that the chosen mode does not use.
  void only_with(const std::vector<std::string> &keys, const std::string &mode_key,
                 const std::string &mode) const {
    for (const auto &k : keys)
      if (has(k))
        fail(k, full(k) + " is not used with " + full(mode_key) + " = \"" + mode +
                    "\"; remove it (or choose the " + mode_key + " that uses it)");
  }

private:
  const Parser &p_;
  const toml::table *t_;
  std::string name_;
};

/// `path` resolved against `base_dir` (unchanged if absolute or base_dir is empty).
inline std::string resolve(const std::string &path, const std::string &base_dir) {
  if (path.empty() || base_dir.empty() || std::filesystem::path(path).is_absolute())
    return path;
  return (std::filesystem::path(base_dir) / path).lexically_normal().string();
}

} // namespace wheelsim::rig::detail
