// The small JSON reader (json_reader.h): recursive descent over RFC 8259, plus comments.
#include "json_reader.h"

#include <cerrno>
#include <cstdlib>

namespace wheelsim::scm::json {
namespace {

class Reader {
public:
  explicit Reader(const std::string &text) : s_(text) {}

  Value document() {
    skip_space();
    Value v = value(0);
    skip_space();
    if (pos_ != s_.size())
      fail("unexpected text after the end of the document");
    return v;
  }

private:
  static constexpr int kMaxDepth = 64;

  [[noreturn]] void fail(const std::string &what) const { throw SyntaxError(line_, what); }

  bool at_end() const { return pos_ >= s_.size(); }
  char peek() const { return at_end() ? '\0' : s_[pos_]; }
  char next() {
    const char c = s_[pos_++];
    if (c == '\n')
      ++line_;
    return c;
  }

  void skip_space() {
    while (!at_end()) {
      const char c = peek();
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
        next();
      } else if (c == '/' && pos_ + 1 < s_.size() && s_[pos_ + 1] == '/') {
        while (!at_end() && peek() != '\n')
          next();
      } else if (c == '/' && pos_ + 1 < s_.size() && s_[pos_ + 1] == '*') {
        const int start = line_;
        next();
        next();
        while (!(peek() == '*' && pos_ + 1 < s_.size() && s_[pos_ + 1] == '/')) {
          if (at_end())
            throw SyntaxError(start, "unterminated /* comment");
          next();
        }
        next();
        next();
      } else {
        return;
      }
    }
  }

  void expect_word(const char *word) {
    for (const char *w = word; *w; ++w)
      if (at_end() || next() != *w)
        fail(std::string("invalid literal (expected '") + word + "')");
  }

  Value value(int depth) {
    if (depth > kMaxDepth)
      fail("nesting deeper than 64 levels");
    Value v;
    v.line = line_;
    const char c = peek();
    if (c == '{') {
      v.type = Value::Type::object;
      object(v, depth);
    } else if (c == '[') {
      v.type = Value::Type::array;
      array(v, depth);
    } else if (c == '"') {
      v.type = Value::Type::string;
      v.string = string();
    } else if (c == 't') {
      expect_word("true");
      v.type = Value::Type::boolean;
      v.boolean = true;
    } else if (c == 'f') {
      expect_word("false");
      v.type = Value::Type::boolean;
    } else if (c == 'n') {
      expect_word("null");
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      v.type = Value::Type::number;
      v.number = number();
    } else if (at_end()) {
      fail("unexpected end of the document (a value was expected)");
    } else {
      fail(std::string("unexpected character '") + c + "' (a value was expected)");
    }
    return v;
  }

  void object(Value &v, int depth) {
    next(); // {
    skip_space();
    if (peek() == '}') {
      next();
      return;
    }
    for (;;) {
      skip_space();
      if (peek() != '"')
        fail("expected a member name in double quotes");
      const int name_line = line_;
      std::string name = string();
      for (const auto &m : v.object)
        if (m.first == name)
          throw SyntaxError(name_line, "duplicate key \"" + name + "\"");
      skip_space();
      if (peek() != ':')
        fail("expected ':' after \"" + name + "\"");
      next();
      skip_space();
      v.object.emplace_back(std::move(name), value(depth + 1));
      skip_space();
      const char c = at_end() ? '\0' : next();
      if (c == '}')
        return;
      if (c != ',')
        fail("expected ',' or '}' in an object");
    }
  }

  void array(Value &v, int depth) {
    next(); // [
    skip_space();
    if (peek() == ']') {
      next();
      return;
    }
    for (;;) {
      skip_space();
      v.array.push_back(value(depth + 1));
      skip_space();
      const char c = at_end() ? '\0' : next();
      if (c == ']')
        return;
      if (c != ',')
        fail("expected ',' or ']' in an array");
    }
  }

  static void append_utf8(std::string &out, unsigned long cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }

  unsigned long hex4() {
    unsigned long cp = 0;
    for (int i = 0; i < 4; ++i) {
      const char h = at_end() ? '\0' : next();
      cp <<= 4;
      if (h >= '0' && h <= '9')
        cp |= static_cast<unsigned long>(h - '0');
      else if (h >= 'a' && h <= 'f')
        cp |= static_cast<unsigned long>(h - 'a' + 10);
      else if (h >= 'A' && h <= 'F')
        cp |= static_cast<unsigned long>(h - 'A' + 10);
      else
        fail("invalid \\u escape (four hexadecimal digits expected)");
    }
    return cp;
  }

  std::string string() {
    next(); // "
    std::string out;
    for (;;) {
      if (at_end())
        fail("unterminated string");
      const char c = next();
      if (c == '"')
        return out;
      if (c == '\n')
        fail("line break inside a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      const char e = at_end() ? '\0' : next();
      switch (e) {
      case '"':
      case '\\':
      case '/':
        out += e;
        break;
      case 'b':
        out += '\b';
        break;
      case 'f':
        out += '\f';
        break;
      case 'n':
        out += '\n';
        break;
      case 'r':
        out += '\r';
        break;
      case 't':
        out += '\t';
        break;
      case 'u': {
        unsigned long cp = hex4();
        if (cp >= 0xD800 && cp < 0xDC00 && peek() == '\\') { // surrogate pair
          next();
          if (next() != 'u')
            fail("invalid surrogate pair in a \\u escape");
          const unsigned long lo = hex4();
          cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
        }
        append_utf8(out, cp);
        break;
      }
      default:
        fail(std::string("invalid escape '\\") + e + "' in a string");
      }
    }
  }

  double number() {
    const std::size_t start = pos_;
    auto digits = [&] {
      const std::size_t d = pos_;
      while (peek() >= '0' && peek() <= '9')
        next();
      return pos_ > d;
    };
    if (peek() == '-')
      next();
    if (!digits())
      fail("invalid number (a digit was expected)");
    if (peek() == '.') {
      next();
      if (!digits())
        fail("invalid number (a digit was expected after '.')");
    }
    if (peek() == 'e' || peek() == 'E') {
      next();
      if (peek() == '+' || peek() == '-')
        next();
      if (!digits())
        fail("invalid number (a digit was expected in the exponent)");
    }
    const std::string text = s_.substr(start, pos_ - start);
    errno = 0;
    const double v = std::strtod(text.c_str(), nullptr);
    if (errno == ERANGE && (v > 1.0 || v < -1.0))
      fail("number out of range: " + text);
    return v;
  }

  const std::string &s_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

} // namespace

const Value *Value::find(const std::string &name) const {
  for (const auto &m : object)
    if (m.first == name)
      return &m.second;
  return nullptr;
}

const char *type_name(Value::Type type) {
  switch (type) {
  case Value::Type::null:
    return "null";
  case Value::Type::boolean:
    return "a boolean";
  case Value::Type::number:
    return "a number";
  case Value::Type::string:
    return "a string";
  case Value::Type::array:
    return "an array";
  case Value::Type::object:
    return "an object";
  }
  return "a value";
}

Value parse(const std::string &text) { return Reader(text).document(); }

} // namespace wheelsim::scm::json
