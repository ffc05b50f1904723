#pragma once
// internal: screening of TOML text before toml++ parses it.
//
// Debian's toml++ 3.3.0 reaches __builtin_unreachable() (undefined behaviour: in an optimised build
// anything may follow) for some non-ASCII code points where it tests for whitespace, e.g. U+00A1..U+0499
// (which holds the degree sign, the micro sign and Greek) outside strings and comments, or after a
// line-ending backslash in a multi-line string (upstream issues marzer/tomlplusplus#190 and #295, fixed
// by PR #305 after 3.3.0). Found by fuzz/fuzz_scene. rootsim's files need no non-ASCII text except in
// comments, so everything else is refused with a SceneError before toml++ sees it.
//
// toml++ also parses nested tables and values recursively (and frees them recursively): a dotted key of
// 35 000 parts (80 kB of text, well under the 1 MiB file limit) overflowed the stack (SIGSEGV). Keys
// and values are therefore bounded on the text too, far beyond anything a scene or sweep needs (two or
// three levels): nesting at most kMaxTomlDepth levels, counting the parts of the [table] header, of
// the dotted keys and the inline arrays and tables around a value; a key of at most kMaxTomlKeyBytes.
#include <cstddef>
#include <string>

namespace rootsim::detail {

// "" when text holds non-ASCII bytes only inside # comments; else "<line>: <why>"
std::string nonAsciiOutsideComments(const std::string& text);

inline constexpr int kMaxTomlDepth = 64;
inline constexpr std::size_t kMaxTomlKeyBytes = 1024;

// "" when no key or value is nested deeper than kMaxTomlDepth and no key is longer than
// kMaxTomlKeyBytes; else "<line>: <why>" (the limit named)
std::string nestingBeyondLimits(const std::string& text);

// both screens, as every TOML reader applies them before toml++ parses text: "" or "<line>: <why>"
std::string screenToml(const std::string& text);

}  // namespace rootsim::detail
