#pragma once
// internal: screening of TOML text before toml++ parses it.
//
// Debian's toml++ 3.3.0 reaches __builtin_unreachable() (undefined behaviour: in an optimised build
// anything may follow) for some non-ASCII code points where it tests for whitespace, e.g. U+00A1..U+0499
// (which holds the degree sign, the micro sign and Greek) outside strings and comments, or after a
// line-ending backslash in a multi-line string (upstream issues marzer/tomlplusplus#190 and #295, fixed
// by PR #305 after 3.3.0). Found by fuzz/fuzz_scene. rootsim's files need no non-ASCII text except in
// comments, so everything else is refused with a SceneError before toml++ sees it.
#include <string>

namespace rootsim::detail {

// "" when text holds non-ASCII bytes only inside # comments; else "<line>: <why>"
std::string nonAsciiOutsideComments(const std::string& text);

}  // namespace rootsim::detail
