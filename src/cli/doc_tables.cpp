// rootsim_doc_tables: writes (--write) or checks (--check) the generated tables of a docs page: the text
// between "<!-- generated: NAME -->" and "<!-- end generated: NAME -->" is the table NAME from its one
// declaration (options: every command's options, options.hpp; timeseries and shape: timeseries.csv's
// and shape.csv's columns, csv.hpp). Ctests run --check on docs/cli.md and docs/outputs.md.
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "options.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/scene.hpp"

namespace {

// timeseries.csv's columns (timeseriesColumns)
std::string timeseriesMarkdown() {
  std::string md = "| column | unit | holds |\n|---|---|---|\n";
  for (const rootsim::RecordColumn& c : rootsim::timeseriesColumns())
    md += std::string("| `") + c.name + "` | " + c.unit + " | " + c.help + (c.whole ? " (an integer)" : "") + " |\n";
  return md;
}

// shape.csv's columns (shapeColumns)
std::string shapeMarkdown() {
  std::string md = "| column | unit | holds |\n|---|---|---|\n";
  for (const rootsim::ShapeColumn& c : rootsim::shapeColumns())
    md += std::string("| `") + c.name + "` | " + c.unit + " | " + c.help + " |\n";
  return md;
}

const std::map<std::string, std::string>& tables() {
  static const std::map<std::string, std::string> t = {{"options", rootsim::cli::optionsMarkdown()},
                                                             {"timeseries", timeseriesMarkdown()},
                                                             {"shape", shapeMarkdown()},
                                                             {"plate_keys", rootsim::plateKeysMarkdown("plate")},
                                                             {"population_keys", rootsim::plateKeysMarkdown("population")},
                                                             {"seedling_keys", rootsim::plateKeysMarkdown("seedling")},
                                                             {"laterals_keys", rootsim::plateKeysMarkdown("laterals")}};
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc == 3 ? argv[1] : "";
  if (mode != "--check" && mode != "--write") {
    std::fprintf(stderr, "usage: rootsim_doc_tables --check|--write DOCS_PAGE.md\n");
    return 2;
  }
  const std::string path = argv[2];
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "rootsim_doc_tables: cannot read %s\n", path.c_str());
    return 2;
  }
  std::stringstream buf;
  buf << in.rdbuf();
  const std::string text = buf.str();
  std::string out = text;
  int found = 0;
  for (const auto& [name, table] : tables()) {
    const std::string begin = "<!-- generated: " + name + " -->\n", end = "<!-- end generated: " + name + " -->";
    const std::size_t a = out.find(begin);
    if (a == std::string::npos) continue;
    const std::size_t b = out.find(end, a);
    if (b == std::string::npos) {
      std::fprintf(stderr, "rootsim_doc_tables: %s: \"%s\" without its end marker\n", path.c_str(), name.c_str());
      return 2;
    }
    out.replace(a + begin.size(), b - a - begin.size(), "\n" + table);
    ++found;
  }
  if (found == 0 && mode == "--check") {
    std::fprintf(stderr, "rootsim_doc_tables: %s has no generated table\n", path.c_str());
    return 2;
  }
  if (mode == "--write") {
    if (out != text) std::ofstream(path, std::ios::binary) << out;
    return 0;
  }
  if (out != text) {
    std::fprintf(stderr, "rootsim_doc_tables: %s: the generated tables differ from their declarations; "
                         "run: build/rootsim_doc_tables --write %s\n", path.c_str(), path.c_str());
    return 1;
  }
  return 0;
}
