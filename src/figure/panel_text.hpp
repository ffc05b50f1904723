#pragma once
// The text of the report: numbers to three digits, yes / no, a panel's markdown section.
#include <string>

namespace rootsim::fig {

// three significant digits ("n/a" when not finite)
std::string fmt3(double v);
// "yes", or a bold "no"
std::string yesNo(bool b);
// a panel's section: heading, the picture NAME.png, the caption, then the body
std::string md(const std::string& name, const std::string& caption, const std::string& body = "");

}  // namespace rootsim::fig
