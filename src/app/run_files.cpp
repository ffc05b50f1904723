// how `render`, `montage` and `export` claim their outputs
#include "run_files.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <utility>

#include "rootsim/errors.hpp"
#include "rootsim/video_writer.hpp"
#include "rootsim/write_rule.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

void registerSignatureChecks() {
  static std::once_flag once;
  std::call_once(once, [] {
    registerSignatureCheck(OutputFormat::Mp4, [](const fs::path& f) { return whyNotSignedMovie(f.string()); });
  });
}

Outputs claimOutputs(const std::string& mp4, const fs::path& png, const std::string& pngDir, const WriteRule& rule,
                     const char* pngFlag) {
  registerSignatureChecks();
  Outputs o;
  std::vector<std::pair<const char*, fs::path>> all;
  if (!mp4.empty()) all.emplace_back("--mp4", mp4);
  if (!png.empty()) all.emplace_back(pngFlag, png);
  if (!pngDir.empty()) all.emplace_back("--png-dir", pngDir);
  // no output may be another, or lie inside the frame folder (replaced whole)
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = 0; j < all.size(); ++j) {
      if (i == j) continue;
      const fs::path a = fs::absolute(all[i].second).lexically_normal(), b = fs::absolute(all[j].second).lexically_normal();
      const auto rel = a.lexically_relative(b);
      if (a == b || (std::string(all[j].first) == "--png-dir" && !rel.empty() && *rel.begin() != ".."))
        throw SceneError(std::string(all[i].first) + " " + all[i].second.string() + ": the same path as, or inside, " +
                         all[j].first + " " + all[j].second.string());
    }
  for (const auto& [flag, path] : all) {
    // locked first, then checked: a second process cannot slip in between
    if (std::string(flag) == "--png-dir") {
      checkOutputName(path.string(), flag);
      claimFolder(path, framesFolder(), rule, flag, true);
      continue;  // StagedFolder locks it when the frames are written
    }
    checkOutputName(path.string(), flag);
    const fs::path dir = fs::absolute(path).parent_path();
    if (!fs::is_directory(dir)) throw SceneError(std::string(flag) + " " + path.string() + ": folder " + dir.string() + " not found");
    o.locks.push_back(lockOutput(path, flag));
    claimFile(path, rule, flag, std::string(flag) == "--mp4" ? OutputFormat::Mp4 : OutputFormat::Png);
  }
  return o;
}

MovieProgress progressLines(bool quiet, const std::string& what) {
  if (quiet) return {};
  return [what, next = 0](int done, int total) mutable {
    const int percent = 100 * done / total;
    if (percent < next && done != total) return;
    std::fprintf(stderr, "%s: frame %d/%d (%d %%)\n", what.c_str(), done, total, percent);
    next = percent / 10 * 10 + 10;
  };
}

}  // namespace rootsim::app
