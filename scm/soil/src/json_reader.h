// A small JSON reader for the Chrono soil files (chrono_soil.cpp): objects, arrays, strings,
// numbers, true/false/null, and the // and /* */ comments that Chrono's own reader accepts (its
// sample files start with one). Every value keeps the line it starts on, for error messages.
// Not a general-purpose library: no streaming, whole documents only.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace wheelsim::scm::json {

/// A syntax error; what() is "<line>: <description>" (the caller adds the file name).
class SyntaxError : public std::runtime_error {
public:
  SyntaxError(int line, const std::string &what) : std::runtime_error(what), line_(line) {}
  int line() const { return line_; }

private:
  int line_;
};

struct Value {
  enum class Type { null, boolean, number, string, array, object };
  Type type = Type::null;
  int line = 0; ///< 1-based line where the value starts
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Value> array;
  /// Members in file order (duplicate names are a syntax error).
  std::vector<std::pair<std::string, Value>> object;

  /// The member `name` of an object, or nullptr.
  const Value *find(const std::string &name) const;
};

/// "an object", "a number", ... for messages.
const char *type_name(Value::Type type);

/// Parses a whole document. Throws SyntaxError.
Value parse(const std::string &text);

} // namespace wheelsim::scm::json
