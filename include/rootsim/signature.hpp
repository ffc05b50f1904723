#pragma once
// The signature rootsim writes into every file it may later be asked to replace at a user's path, in
// the format's metadata place and followed by " sha256:<hash of the content>" (RSML: the comment on
// line 2; GLB: asset.generator, the hash in asset.extras; PNG: a tEXt "Software" chunk; MP4: the
// "comment" tag). The write rule (write_rule.hpp, whyNotSigned) replaces a lone file only when that
// place parses and the content still matches. Header only: the renderer writes it without rootsim_io.
#include <string>

#include "rootsim/version.hpp"

namespace rootsim {

inline constexpr const char* kOutputSignature = "rootsim-output";

// the text written: "rootsim-output rootsim <version>"
inline const char* outputSignatureText() {
  // appended in place: gcc 12's -Warray-bounds misreads the inlined `string + const char*` chain here
  static const std::string s = [] {
    std::string t(kOutputSignature);
    t.append(" rootsim ").append(kVersion);
    return t;
  }();
  return s.c_str();
}

}  // namespace rootsim
