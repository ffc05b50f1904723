// the commands' option table (src/cli/options.hpp): names, defaults read from the options structs, the
// setters the Python binding calls, the records of what was given, the generated docs
#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "options.hpp"

using namespace rootsim;
using namespace rootsim::cli;

namespace {
const OptionSpec& option(const CommandSpec& c, const std::string& pythonName) {
  const OptionSpec* o = c.find(pythonName);
  REQUIRE_MESSAGE(o != nullptr, c.name << ": no option " << pythonName);
  return *o;
}
}  // namespace

TEST_CASE("every command's flags and Python keywords are unique and named by one rule") {
  std::set<std::string> commandNames;
  for (const CommandSpec& c : commands()) {
    CHECK(commandNames.insert(c.name).second);
    std::set<std::string> flags, keywords;
    for (const OptionSpec& o : c.options) {
      CHECK_MESSAGE(flags.insert(o.longName()).second, c.name << " " << o.flag);
      CHECK_MESSAGE(keywords.insert(o.pythonName()).second, c.name << " " << o.pythonName());
      CHECK_MESSAGE(!o.help.empty(), c.name << " " << o.flag);
      CHECK_MESSAGE(c.find(o.pythonName()) == &o, c.name << " " << o.flag);
    }
  }
  CHECK(commandNames.size() == 11);
  const CommandSpec& render = command("render");
  CHECK(option(render, "overlays").negated());
  CHECK(option(render, "overlays").displayName() == "--no-overlays");
  CHECK(option(render, "hours_per_second").displayName() == "--hours-per-second");
  CHECK(option(command("fit"), "jobs").displayName() == "-j, --jobs");
  CHECK(option(command("run"), "scene_or_path").displayName() == "scene");
  CHECK(option(command("run"), "scene_or_path").positional());
  CHECK(option(command("sweep"), "sweep_file").required);
}

TEST_CASE("defaults are the options structs' own and an unset number has none") {
  const CommandSpec& render = command("render");
  const app::RenderOptions d;
  CHECK(defaultText(render, option(render, "fps")) == std::to_string(d.fps));
  CHECK(defaultText(render, option(render, "view")) == d.view);
  CHECK(defaultText(render, option(render, "at_h")).empty());
  CHECK(defaultText(render, option(render, "field_mm")) == "2");
  const CommandSpec& figure = command("figure");
  CHECK(defaultText(figure, option(figure, "out")) == FigureCliOptions{}.out);
  CHECK(defaultText(figure, option(figure, "dpi")) == "300");
  // the command's presets apply to a fresh struct: render names its trace flags --trace-*, run --movie
  // without --camera takes the inset look
  CHECK(render.makeAs<app::RenderOptions>()->trace.flagPrefix == "--trace-");
  CHECK(command("run").makeAs<RunOptions>()->look.insetByDefault);
  CHECK_THROWS_AS(render.makeAs<app::ExportOptions>(), std::logic_error);
}

TEST_CASE("the setters write the member the table names and refuse another kind") {
  const CommandSpec& render = command("render");
  const auto o = render.makeAs<app::RenderOptions>();
  setInt(option(render, "fps"), o.get(), 12);
  setReal(option(render, "at_h"), o.get(), 1.5);
  setText(option(render, "camera"), o.get(), "follow");
  setText(option(render, "trace_root"), o.get(), "#2");
  setFlag(option(render, "overlays"), o.get(), true);
  CHECK(o->fps == 12);
  CHECK(o->atH == 1.5);
  CHECK(o->look.camera == "follow");
  CHECK(o->trace.root == "#2");
  CHECK(o->noOverlays);
  CHECK_FALSE(o->look.cameraGiven);
  markGiven(option(render, "camera"), o.get(), true);
  markGiven(option(render, "frame"), o.get(), true);
  markGiven(option(render, "fps"), o.get(), true);  // not recorded: nothing else changes
  CHECK(o->look.cameraGiven);
  CHECK(o->frameGiven);
  CHECK_FALSE(o->look.fieldGiven);
  CHECK_THROWS_AS(setText(option(render, "fps"), o.get(), "12"), std::logic_error);
  const CommandSpec& montage = command("montage");
  const auto m = montage.makeAs<app::MontageOptions>();
  setTexts(option(montage, "run_dirs"), m.get(), {"a", "b"});
  CHECK(m->runDirs == std::vector<std::string>{"a", "b"});
}

TEST_CASE("Python's values meet the command line's range and choice checks with its messages") {
  const CommandSpec& render = command("render");
  CHECK(checkNumber(render, option(render, "fps"), 240).empty());
  CHECK(checkNumber(render, option(render, "fps"), 0) == "render: --fps: Value 0 not in range 1 to 240");
  CHECK(checkNumber(render, option(render, "at_h"), -5).empty());  // no range: the command checks it
  const CommandSpec& figure = command("figure");
  CHECK(checkNumber(figure, option(figure, "dpi"), 2401) == "figure: --dpi: Value 2401 not in range 10 to 2400");
  CHECK(checkNumber(figure, option(figure, "dpi"), std::nan("")).empty());  // figure's own check names it
  CHECK(checkText(render, option(render, "view"), "3d").empty());
  CHECK(checkText(render, option(render, "view"), "side") == "render: --view: side not in {top,3d}");
  CHECK(checkText(command("montage"), option(command("montage"), "view"), "side").empty());
  CHECK(checkNumber(command("sweep"), option(command("sweep"), "jobs"), 0) == "sweep: --jobs: Value 0 not in range 1 to 1024");
}

TEST_CASE("the generated docs hold a table per command with every flag") {
  const std::string md = optionsMarkdown();
  for (const CommandSpec& c : commands()) {
    CHECK_MESSAGE(md.find("### rootsim " + c.name + "\n") != std::string::npos, c.name);
    for (const OptionSpec& o : c.options)
      CHECK_MESSAGE(md.find("| `" + o.displayName() + "` | `" + o.pythonName()) != std::string::npos, c.name << " " << o.flag);
  }
  CHECK(md.find("| `--fps` | `fps` | integer in [1, 240] | `30` |") != std::string::npos);
  CHECK(md.find("| `--no-overlays` | `overlays=False` | flag |") != std::string::npos);
}
