// The text of the report: numbers to three digits, yes / no, a panel's markdown section.
#include "panel_text.hpp"

#include <cmath>
#include <cstdio>

#include "rootsim/number_text.hpp"

namespace rootsim::fig {

std::string fmt3(double v) {
  return std::isfinite(v) ? significantText(v, 3) : "n/a";
}

std::string yesNo(bool b) { return b ? "yes" : "**no**"; }

std::string md(const std::string& name, const std::string& caption, const std::string& body) {
  return "## " + name + "\n\n![" + name + "](" + name + ".png)\n\n" + caption + "\n\n" + body + "\n";
}

}  // namespace rootsim::fig
