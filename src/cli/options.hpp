#pragma once
// Every command's options, declared once (name, type, default, unit, help): main.cpp registers the CLI11
// flags from this table, the Python binding reads rootsim.<command>'s keywords through it, and
// rootsim_options_doc writes docs/cli.md's option tables from it. CLI11-free and pybind11-free.
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <typeindex>
#include <type_traits>
#include <utility>
#include <vector>

namespace rootsim::cli {

enum class OptionKind { Text, Texts, Int, Real, Flag };

struct OptionSpec {
  std::string flag;       // as CLI11 takes it: "--fps", "-j,--jobs", or a positional's name ("run_dir")
  OptionKind kind = OptionKind::Text;
  std::string unit;       // "h", "mm", "px/mm", ... ("" for none)
  std::string help;
  bool required = false;
  bool hasRange = false;  // CLI11's Range check [lo, hi] (its own message: "Value 0 not in range 1 to 240")
  double lo = 0, hi = 0;
  std::vector<std::string> choices;  // CLI11's IsMember check (empty: any value)
  std::string python;     // the Python keyword when it is not the flag's name ("" : pythonName's rule)
  std::function<void*(void*)> field;   // the member it sets, in the command's options struct
  std::function<bool*(void*)> given;   // set to whether it was given (null: not recorded)

  bool positional() const { return flag[0] != '-'; }
  // "--no-overlays" is Python's overlays=False: a flag whose keyword is its negation
  bool negated() const { return kind == OptionKind::Flag && longName().rfind("no-", 0) == 0; }
  // the long name without dashes: "jobs" of "-j,--jobs", "at-h" of "--at-h", "run_dir"
  std::string longName() const;
  // rootsim.<command>'s keyword: the long name with '-' as '_', "--no-X" as X ("overlays")
  std::string pythonName() const;
  // the name docs show: "--at-h", "-j, --jobs", "run_dir"
  std::string displayName() const;
};

struct CommandSpec {
  std::string name, help;
  std::vector<OptionSpec> options;
  std::type_index type = typeid(void);              // the options struct
  std::function<std::shared_ptr<void>()> make;      // a default options struct (with the command's presets)
  std::function<int(void*)> run;                    // the command (exit code; throws as commands.hpp says)

  // a default options struct of type O (std::logic_error when O is not this command's)
  template <class O>
  std::shared_ptr<O> makeAs() const {
    if (type != std::type_index(typeid(O))) throw std::logic_error("options of " + name + ": another struct");
    return std::static_pointer_cast<O>(make());
  }
  const OptionSpec* find(const std::string& pythonName) const;
};

// the commands in the order `rootsim --help` lists them
const std::vector<CommandSpec>& commands();
const CommandSpec& command(const std::string& name);

// an option's default, as text: the default options struct's value ("30", "top"), "" when the default is
// "not given" (an empty text, an unset number: the help says what is used then)
std::string defaultText(const CommandSpec& c, const OptionSpec& o);

// Python's value of an option, applied to an options struct: the setters a binding calls, kind checked
// (std::logic_error for a kind mismatch: a binding bug)
void setText(const OptionSpec& o, void* opts, const std::string& v);
void setTexts(const OptionSpec& o, void* opts, const std::vector<std::string>& v);
void setInt(const OptionSpec& o, void* opts, int v);
void setReal(const OptionSpec& o, void* opts, double v);
void setFlag(const OptionSpec& o, void* opts, bool v);  // the flag's own sense (negated() already undone)
void markGiven(const OptionSpec& o, void* opts, bool given);
// the table's checks (range, choices) on a value given other than through CLI11 (Python's keywords):
// "" when it passes, else the message, as CLI11's ("sweep: --jobs: Value 0 not in range 1 to 1024")
std::string checkNumber(const CommandSpec& c, const OptionSpec& o, double v);
std::string checkText(const CommandSpec& c, const OptionSpec& o, const std::string& v);

// the markdown tables of docs/cli.md's options section (one per command)
std::string optionsMarkdown();

}  // namespace rootsim::cli
