#include "toml_guard.hpp"

#include <vector>

namespace rootsim::detail {

std::string nonAsciiOutsideComments(const std::string& text) {
  // a small TOML lexer that knows only what decides whether a '#' starts a comment: strings (basic,
  // literal, multi-line) and escapes. Where it is unsure it errs towards "not a comment" (refusal).
  enum class S { Normal, Comment, Basic, Literal, MlBasic, MlLiteral } s = S::Normal;
  int line = 1;
  const size_t n = text.size();
  auto at = [&](size_t i, const char* lit) { return text.compare(i, 3, lit) == 0; };
  for (size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      ++line;
      if (s == S::Comment || s == S::Basic || s == S::Literal) s = S::Normal;  // single-line ends here
      continue;
    }
    if (c >= 0x80 && s != S::Comment)
      return std::to_string(line) + ": non-ASCII character outside a comment (scene and sweep files are ASCII "
                                    "TOML; other text may only appear in # comments)";
    switch (s) {
      case S::Normal:
        if (c == '#') s = S::Comment;
        else if (at(i, "\"\"\"")) { s = S::MlBasic; i += 2; }
        else if (at(i, "'''")) { s = S::MlLiteral; i += 2; }
        else if (c == '"') s = S::Basic;
        else if (c == '\'') s = S::Literal;
        break;
      case S::Comment:
        break;
      case S::Basic:
      case S::MlBasic:
        if (c == '\\') {
          // the escaped character is skipped (a line-ending backslash in a multi-line string: the newline)
          if (i + 1 < n && text[i + 1] == '\n') ++line;
          if (i + 1 < n && static_cast<unsigned char>(text[i + 1]) >= 0x80)
            return std::to_string(line) + ": non-ASCII character outside a comment (scene and sweep files are "
                                          "ASCII TOML; other text may only appear in # comments)";
          ++i;
        } else if (s == S::Basic && c == '"') {
          s = S::Normal;
        } else if (s == S::MlBasic && at(i, "\"\"\"")) {
          s = S::Normal;
          i += 2;
        }
        break;
      case S::Literal:
        if (c == '\'') s = S::Normal;
        break;
      case S::MlLiteral:
        if (at(i, "'''")) {
          s = S::Normal;
          i += 2;
        }
        break;
    }
  }
  return "";
}

std::string nestingBeyondLimits(const std::string& text) {
  // A second small lexer: it follows keys (at a line's start, in a [table] header, after '{' or ',' in
  // an inline table) and values (after '='), skips strings and comments, and counts levels. A key part
  // in a table L deep is L + 1 deep; an array's elements are one deeper than the array. Input that
  // toml++ refuses anyway may be miscounted: only its refusal matters then.
  const std::string depth = std::to_string(kMaxTomlDepth);
  const std::string keyDeep = ": a key nested more than " + depth +
                              " levels deep (its dotted parts, with those of its [table] header and of the "
                              "inline tables around it; at most " + depth + ")";
  const std::string valueDeep = ": arrays or inline tables nested more than " + depth +
                                " levels deep (with the dotted parts of the keys around them; at most " + depth + ")";
  const std::string keyLong = ": a key longer than " + std::to_string(kMaxTomlKeyBytes) + " bytes (at most " +
                              std::to_string(kMaxTomlKeyBytes) + ")";
  struct Open {
    char kind;  // '[' array, '{' inline table
    int level;  // the level of the container itself
  };
  std::vector<Open> open;
  int line = 1;
  int tableLevel = 0;     // the parts of the current [table] header
  bool key = true;        // reading a key
  bool lineStart = true;  // nothing but blanks yet on this line (outside any container)
  bool header = false;    // the key is a [table] or [[array]] header
  int keyLevel = 0;       // the level of the table the key is in
  int parts = 0;          // the key's parts so far
  bool inPart = false;    // inside a part (a '.' ends it)
  std::size_t keyStart = std::string::npos;
  int valueLevel = 0;     // the level of the value being read
  const std::size_t n = text.size();
  auto at = [&](std::size_t i, const char* lit) { return text.compare(i, 3, lit) == 0; };
  auto newKey = [&](int level) {
    key = true;
    keyLevel = level;
    parts = 0;
    inPart = false;
    keyStart = std::string::npos;
  };
  // the end of a single-line string that starts at i: its closing quote (or the last byte of its line)
  auto endOfString = [&](std::size_t i) {
    const char q = text[i];
    std::size_t j = i + 1;
    while (j < n && text[j] != q && text[j] != '\n')
      j += (q == '"' && text[j] == '\\' && j + 1 < n && text[j + 1] != '\n') ? 2 : 1;
    return j < n && text[j] == q ? j : j - 1;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      if (open.empty()) {
        newKey(tableLevel);
        header = false;
        lineStart = true;
      }
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') continue;
    if (c == '#') {
      while (i + 1 < n && text[i + 1] != '\n') ++i;
      continue;
    }
    if (key) {
      const bool first = lineStart;
      lineStart = false;
      if (first && open.empty() && c == '[') {
        header = true;
        newKey(0);
        if (i + 1 < n && text[i + 1] == '[') ++i;
        continue;
      }
      const bool bare = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
      if (bare || c == '"' || c == '\'') {
        if (keyStart == std::string::npos) keyStart = i;
        if (!inPart) {
          inPart = true;
          if (keyLevel + ++parts > kMaxTomlDepth) return std::to_string(line) + keyDeep;
        }
        if (!bare) i = endOfString(i);
        if (i - keyStart + 1 > kMaxTomlKeyBytes) return std::to_string(line) + keyLong;
        continue;
      }
      if (c == '.') {
        inPart = false;
        continue;
      }
      key = false;
      valueLevel = keyLevel + parts;
      if (header) {
        tableLevel = parts;  // at ']' (or at a syntax error toml++ reports)
        header = false;
        while (i + 1 < n && text[i + 1] == ']') ++i;
        continue;
      }
      if (c == '=') continue;
      // not a key: toml++ reports it; read on as a value
    }
    if (c == '"' || c == '\'') {
      const char* triple = c == '"' ? "\"\"\"" : "'''";
      if (!at(i, triple)) {
        i = endOfString(i);
        continue;
      }
      // a multi-line string: to its closing triple quote, counting lines
      for (i += 3; i < n && !at(i, triple); ++i) {
        if (text[i] == '\n') {
          ++line;
        } else if (c == '"' && text[i] == '\\' && i + 1 < n) {
          if (text[i + 1] == '\n') ++line;
          ++i;
        }
      }
      i += 2;
      continue;
    }
    if (c == '[' || c == '{') {
      open.push_back({c, valueLevel});
      if (valueLevel + 1 > kMaxTomlDepth) return std::to_string(line) + valueDeep;
      if (c == '{') newKey(valueLevel);
      else valueLevel += 1;
      continue;
    }
    if (c == ',' && !open.empty()) {
      if (open.back().kind == '{') newKey(open.back().level);
      else valueLevel = open.back().level + 1;
      continue;
    }
    if ((c == ']' || c == '}') && !open.empty()) {
      open.pop_back();
      key = false;
      if (!open.empty() && open.back().kind == '[') valueLevel = open.back().level + 1;
      continue;
    }
  }
  return "";
}

std::string screenToml(const std::string& text) {
  if (std::string bad = nonAsciiOutsideComments(text); !bad.empty()) return bad;
  return nestingBeyondLimits(text);
}

}  // namespace rootsim::detail
