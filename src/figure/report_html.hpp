#pragma once
// report.html (docs/outputs.md, "What rootsim replaces"): the report of `rootsim figure all` for CI and
// browsers, one self-contained file: every panel inline as a PNG data: URI, the claims table with agree /
// disagree marked in colour and in words, the command that made the panels and the rootsim version. No
// external file, no network.
#include <filesystem>
#include <string>
#include <vector>

#include "figure_cases.hpp"

namespace rootsim::fig {

// standard base64 (RFC 4648, with padding)
std::string base64(const std::string& bytes);
// text with & < > " escaped for HTML
std::string htmlEscape(const std::string& text);

// the page: `command` as run, the claims, and each panel NAME read from dir/NAME.png (a panel whose file is
// missing or empty throws RunError: the page never shows a broken picture)
std::string reportHtml(const std::string& command, const std::vector<Claim>& claims,
                       const std::vector<std::string>& panels, const std::filesystem::path& dir);

}  // namespace rootsim::fig
