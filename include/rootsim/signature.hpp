#pragma once
// The signature rootsim writes into every file it may later be asked to replace at a user's path
// (PNG: a tEXt "Software" chunk; MP4: the "comment" tag). The write rule (write_rule.hpp) replaces a
// lone file only when it carries it. Header only: the renderer writes it without linking rootsim_io.
#include <string>

#include "rootsim/version.hpp"

namespace rootsim {

inline constexpr const char* kOutputSignature = "rootsim-output";

// the text written: "rootsim-output rootsim <version>"
inline const char* outputSignatureText() {
  static const std::string s = std::string(kOutputSignature) + " rootsim " + kVersion;
  return s.c_str();
}

}  // namespace rootsim
