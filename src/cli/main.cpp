// rootsim command line (CLI11 only here): parse, call the library, turn exceptions into exit codes
// 0 success, 1 run failed, 2 bad usage or bad scene (docs/cli.md).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <system_error>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "options.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/relax.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/version.hpp"

using namespace rootsim;

namespace {
// a command's options from its table (options.hpp) into CLI11, bound to the members of opts
void addOptions(CLI::App* c, const cli::CommandSpec& spec, void* opts) {
  for (const cli::OptionSpec& s : spec.options) {
    void* field = s.field(opts);
    CLI::Option* o = nullptr;
    switch (s.kind) {
      case cli::OptionKind::Text: o = c->add_option(s.flag, *static_cast<std::string*>(field), s.help); break;
      case cli::OptionKind::Texts: o = c->add_option(s.flag, *static_cast<std::vector<std::string>*>(field), s.help); break;
      case cli::OptionKind::Int: o = c->add_option(s.flag, *static_cast<int*>(field), s.help); break;
      case cli::OptionKind::Real: o = c->add_option(s.flag, *static_cast<double*>(field), s.help); break;
      case cli::OptionKind::Flag: o = c->add_flag(s.flag, *static_cast<bool*>(field), s.help); break;
    }
    if (s.required) o->required();
    if (s.hasRange) {
      if (s.kind == cli::OptionKind::Int) o->check(CLI::Range(static_cast<int>(s.lo), static_cast<int>(s.hi)));
      else o->check(CLI::Range(s.lo, s.hi));
    }
    if (!s.choices.empty()) o->check(CLI::IsMember(s.choices));
  }
}
}  // namespace

// CLI11's parse errors rewritten to the one line every usage error is (docs/cli.md): `rootsim: error: `, the
// command or flag named, the closest valid one for a near miss; exit 2 (help and --version: exit 0)
static int usageError(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  if (e.get_exit_code() == 0) return app.exit(e);
  std::vector<std::string> commands;
  CLI::App* sub = nullptr;
  for (CLI::App* s : app.get_subcommands([](CLI::App*) { return true; })) {
    commands.push_back(s->get_name());
    for (int i = 1; i < argc && !sub; ++i)
      if (s->get_name() == argv[i]) sub = s;
  }
  std::string list;
  for (const std::string& c : commands) list += (list.empty() ? "" : ", ") + c;
  auto fail = [](const std::string& line) {
    std::string one = line;
    for (char& c : one)
      if (c == '\n' || c == '\r') c = ' ';
    std::fprintf(stderr, "rootsim: error: %s\n", printable(one).c_str());
    return 2;
  };
  if (!sub) {
    // the first word that is not a flag is the command the user meant
    for (int i = 1; i < argc; ++i)
      if (argv[i][0] != '-') {
        const std::string near = closestName(argv[i], commands);
        return fail("unknown command " + std::string(argv[i]) + (near.empty() ? "" : " (did you mean " + near + "?)") +
                    "; the commands: " + list);
      }
    if (dynamic_cast<const CLI::ExtrasError*>(&e) == nullptr)
      return fail("a command is required: " + list + " (rootsim --help)");
  }
  const std::string where = sub ? sub->get_name() : std::string("rootsim");
  std::string msg = e.what();
  auto after = [&](const std::string& head) { return msg.substr(msg.find(head) + head.size()); };
  auto flagNames = [&] {
    std::vector<std::string> names;
    const CLI::App* a = sub ? sub : &app;
    for (const CLI::Option* o : a->get_options())
      for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
    return names;
  };
  if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
    // "The following argument(s) was/were not expected: A B" (CLI11 lists them last first): a flag first
    std::vector<std::string> words;
    std::istringstream in(after(": "));
    for (std::string w; in >> w;) words.push_back(w);
    std::string first = words.empty() ? std::string() : words.back();
    for (const std::string& w : words)
      if (w[0] == '-') first = w;
    if (!first.empty() && first[0] == '-') {
      const std::string flag = first.substr(0, first.find('='));
      const std::string near = closestName(flag, flagNames());
      return fail("unknown flag " + flag + " for " + where + (near.empty() ? "" : " (did you mean " + near + "?)") + " (rootsim " +
                  where + " --help)");
    }
    return fail(where + ": unexpected argument " + first + " (rootsim " + where + " --help)");
  }
  if (dynamic_cast<const CLI::ConversionError*>(&e) && msg.find("Could not convert: ") != std::string::npos) {
    // "Could not convert: --at-h = abc"
    const std::string rest = after("Could not convert: ");
    const std::size_t eq = rest.find(" = ");
    const std::string name = rest.substr(0, eq), value = eq == std::string::npos ? std::string() : rest.substr(eq + 3);
    std::string expected = "a number";
    if (const CLI::Option* o = (sub ? sub : &app)->get_option_no_throw(name))
      if (o->get_type_name() == "INT" || o->get_type_name() == "UINT") expected = "an integer";
    return fail(name + " " + value + ": expected " + expected);
  }
  return fail(where + ": " + msg);
}

namespace {

// every command from its table: its options struct, CLI11's subcommand bound to it
struct Registered {
  const cli::CommandSpec* spec;
  std::shared_ptr<void> opts;
  CLI::App* app;
};
std::vector<Registered> registerCommands(CLI::App& app) {
  std::vector<Registered> registered;
  for (const cli::CommandSpec& spec : cli::commands()) {
    Registered r{&spec, spec.make(), app.add_subcommand(spec.name, spec.help)};
    addOptions(r.app, spec, r.opts.get());
    registered.push_back(std::move(r));
  }
  return registered;
}

// a path option given an empty value ("--out ''") is refused, never taken for its default: false after
// saying so
bool noEmptyValues(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands())
    for (const CLI::Option* opt : sub->get_options())
      if (opt->count() > 0 && opt->get_type_size() != 0)
        for (const std::string& v : opt->results())
          if (v.empty()) {
            std::fprintf(stderr, "rootsim: error: %s: empty value (give a path or value, or leave the option out)\n",
                         opt->get_name().c_str());
            return false;
          }
  return true;
}

// the parsed command run, its exceptions turned into exit codes: bad input 2, a failed run 1
int runParsed(CLI::App& app, const std::vector<Registered>& registered) {
  try {
    for (const Registered& r : registered)
      if (r.app->parsed()) return r.spec->run(r.opts.get());
  } catch (const SceneError& e) {
    std::fprintf(stderr, "rootsim: error: %s\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // a path rootsim may not read or write (an unreadable run directory, a folder without write permission):
    // the user's to fix, named with what to do
    const std::string path = !e.path1().empty() ? e.path1().string() : std::string("a path given");
    if (e.code() == std::errc::permission_denied || e.code() == std::errc::operation_not_permitted) {
      std::fprintf(stderr, "rootsim: error: %s: permission denied (rootsim cannot read or write it: check its permissions, "
                           "e.g. ls -ld, or give another path)\n", printable(path).c_str());
      return 2;
    }
    std::fprintf(stderr, "rootsim: run failed: %s: %s\n", printable(path).c_str(), e.code().message().c_str());
    return 1;
  } catch (const RelaxError& e) {
    std::fprintf(stderr, "rootsim: run failed: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::string command = "rootsim";
    for (const CLI::App* sub : app.get_subcommands()) command += " " + sub->get_name();
    std::fprintf(stderr, "rootsim: run failed: %s\n", failureText(e, command).c_str());
    return 1;
  }
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rootsim: growing Cosserat-rod roots on tilted plates (Cosserat mechanics, growth, movies)"};
  app.fallthrough();
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("rootsim ") + kVersion);
  const std::vector<Registered> registered = registerCommands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return usageError(app, e, argc, argv);
  }
  if (!noEmptyValues(app)) return 2;
  // the options whose presence matters (a --field-mm without a follow window to size is refused by
  // app::parseLook, not ignored; run --movie without --camera: the inset look; render --frame 0)
  for (const Registered& r : registered)
    for (const cli::OptionSpec& s : r.spec->options)
      cli::markGiven(s, r.opts.get(), r.app->get_option(s.flag.substr(s.flag.rfind(',') + 1))->count() > 0);
  return runParsed(app, registered);
}
