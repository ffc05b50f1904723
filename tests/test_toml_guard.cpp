// the screen in front of toml++ (src/io/toml_guard.cpp): non-ASCII text outside comments, deep nesting and
// long keys are refused before toml++ parses them, in scene files, --set values and sweep files
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scene_support.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
using rootsim::test::errorOf;
using rootsim::test::sweepError;
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("toml_guard", name); }
}  // namespace

TEST_CASE("non-ASCII text is accepted in comments only (toml++ 3.3 has undefined behaviour on some of it)") {
  // comments may say 40 degrees with the sign, or alpha in Greek
  CHECK(errorOf("# tilt 40\xc2\xb0\n[plane]\nalpha_deg = 40 # \xce\xb1, and a '\"' in a comment\n") == "(no error)");
  // outside comments it is refused before toml++ sees it (upstream issues #190 and #295 of
  // marzer/tomlplusplus: these inputs reach __builtin_unreachable() in 3.3.0)
  CHECK(errorOf("[root]\nradius_mm = 0.1 \xcd\x88\n") ==
        "scenes/t.toml:2: non-ASCII character outside a comment (scene and sweep files are ASCII TOML; other text "
        "may only appear in # comments)");
  CHECK(errorOf("s = \"\"\"\\\n\xc2\xa7\"\"\"\n").find("scenes/t.toml:2: non-ASCII character outside a comment") == 0);
  CHECK(errorOf("[tropism]\nsensing = \"\xc3\xa9\" # \xc3\xa9\n").find("scenes/t.toml:2: non-ASCII") == 0);
  // a '#' inside a string starts no comment
  CHECK(errorOf("[tropism]\nsensing = \"a#\xc3\xa9\"\n").find("scenes/t.toml:2: non-ASCII") == 0);
  CHECK(errorOf("", {"tropism.beta=0.1 \xcd\x88"}) ==
        "--set tropism.beta=0.1 \xcd\x88: non-ASCII characters are not allowed (scene values are ASCII)");
}

TEST_CASE("deep nesting and long keys are refused before toml++ parses them (its recursion overflowed the stack)") {
  // a dotted key of 35 000 parts (80 kB) crashed toml++ with SIGSEGV; refused naming file:line and the limit
  std::string deep = "[root]\nradius_mm = 0.1\na";
  for (int i = 0; i < 40000; ++i) deep += ".a";
  CHECK(errorOf(deep + " = 1\n") ==
        "scenes/t.toml:3: a key nested more than 64 levels deep (its dotted parts, with those of its [table] header "
        "and of the inline tables around it; at most 64)");
  // the same in a [table] header, and counted with the header's parts
  std::string header = "[a";
  for (int i = 0; i < 64; ++i) header += ".b";
  CHECK(errorOf(header + "]\n").find("scenes/t.toml:1: a key nested more than 64 levels deep") == 0);
  std::string in63 = "[t.u]\nk";
  for (int i = 0; i < 62; ++i) in63 += ".b";  // 2 + 63 parts
  CHECK(errorOf(in63 + " = 1\n").find("scenes/t.toml:2: a key nested more than 64 levels deep") == 0);
  // 64 levels pass the screen (and are then refused as an unknown section by the schema)
  std::string at64 = "[t]\nk";
  for (int i = 0; i < 62; ++i) at64 += ".b";
  CHECK(errorOf(at64 + " = 1\n").find("scenes/t.toml:1: unknown section [t]") == 0);
  // inline arrays and tables
  const std::string arrays = "[load]\ntip_force_n = " + std::string(100000, '[') + std::string(100000, ']') + "\n";
  CHECK(errorOf(arrays) == "scenes/t.toml:2: arrays or inline tables nested more than 64 levels deep (with the dotted "
                           "parts of the keys around them; at most 64)");
  std::string tables = "[load]\ntip_force_n = ";
  for (int i = 0; i < 30000; ++i) tables += "{a = ";
  tables += "1" + std::string(30000, '}') + "\n";
  CHECK(errorOf(tables).find("scenes/t.toml:2: a") == 0);
  CHECK(errorOf(tables).find("nested more than 64 levels deep") != std::string::npos);
  // strings and comments hold brackets freely; a multi-line array counts its lines
  CHECK(errorOf("# [[[[[[[[\n[tropism]\nsensing = \"[[[[{{{{.a.a\" # {{{{\n") .find("sensing must be one of") != std::string::npos);
  CHECK(errorOf("[load]\ntip_force_n = [\n  0,\n  0,\n  " + std::string(70, '[') + "\n") .find("scenes/t.toml:5: arrays") == 0);
  // a key of more than 1024 bytes, bare or quoted
  CHECK(errorOf("[root]\n" + std::string(1025, 'k') + " = 1\n") ==
        "scenes/t.toml:2: a key longer than 1024 bytes (at most 1024)");
  CHECK(errorOf("[root]\n\"" + std::string(1030, 'k') + "\" = 1\n").find("scenes/t.toml:2: a key longer than 1024") == 0);
  CHECK(errorOf("[root]\n" + std::string(1024, 'k') + " = 1\n").find("unknown key root.kkk") != std::string::npos);
  // --set values and sweep files go through the same screen
  CHECK(errorOf("", {"load.tip_force_n=" + std::string(70, '[') + std::string(70, ']')}) ==
        "--set load.tip_force_n=" + std::string(70, '[') + std::string(70, ']') +
            ": arrays or inline tables nested more than 64 levels deep (with the dotted parts of the keys around "
            "them; at most 64)");
  const fs::path d = scratch("deep");
  { std::ofstream(d / "deep.toml") << "[sweep]\nscene = \"x.toml\"\n" << deep.substr(deep.rfind('\n') + 1) << " = 1\n"; }
  CHECK(sweepError(d / "deep.toml").find((d / "deep.toml").string() + ":3: a key nested more than 64 levels deep") == 0);
  fs::remove_all(d);
}
