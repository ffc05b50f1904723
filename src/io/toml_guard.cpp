#include "toml_guard.hpp"

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

}  // namespace rootsim::detail
