// Pieces of the error messages of wheelsim's TOML configurations (rig configs, SCM soil files):
// "did you mean" suggestions, the TOML type of a value in words, syntax errors with their line,
// numbers as the user wrote them.
#pragma once

#include <string>
#include <vector>

#include <toml++/toml.h>

namespace wheelsim::config {

/// The closest of `candidates` to `word`, or "" if none is plausibly meant: a candidate that
/// contains the word (or is contained in it, words of 3+ characters) wins, else the smallest edit
/// distance up to a third of the word's length (at least 2).
std::string closest(const std::string &word, const std::vector<std::string> &candidates);

/// `s` as a JSON string literal: in double quotes, with '"', '\\' and control characters
/// escaped (\n, \t, \r by name, the others as \u00XX). Used by every JSON writer of wheelsim.
std::string json_string(const std::string &s);

/// Levenshtein distance between a and b.
std::size_t edit_distance(const std::string &a, const std::string &b);

/// "a string", "an integer", "a number", "a boolean", "a table", "an array" or "a date/time".
const char *type_name(const toml::node &node);

/// "<source>:<line>: <message>", the line of `where` (just "<source>: <message>" if `where` is
/// null or has no line).
std::string located(const std::string &source_name, const toml::node *where,
                    const std::string &message);

/// "<source>:<line>: TOML syntax error: <description>" for a file toml++ could not parse.
std::string syntax_error(const toml::parse_error &error, const std::string &source_name);

/// A number in the shortest default stream form (3, 0.5, 1e+07).
std::string fmt(double value);

} // namespace wheelsim::config
