// rootsim command line (CLI11 only here): parse, call the library, turn exceptions into exit codes
// 0 success, 1 run failed, 2 bad usage or bad scene (docs/cli.md).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <system_error>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/relax.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/version.hpp"

using namespace rootsim;

namespace {
// the movie look flags shared by run --movie and render
void addLookOptions(CLI::App* c, app::LookOptions& look) {
  c->add_option("--camera", look.camera, "fit (whole root; render's default) or follow (a window following the growth zone); run --movie without --camera: fit with a follow inset");
  c->add_option("--field-mm", look.fieldMm, "follow window width [mm] (default 2); with --camera follow or --inset, or alone with run --movie (its default inset)");
  c->add_flag("--inset", look.inset, "fit view with a follow window in a free corner, its region marked");
  c->add_option("--color-by", look.colorBy, "colour the tube: curvature, kappa1, kappa2, twist (signed: a diverging map centred on 0), kappa0, stretch or contact");
  c->add_option("--plot", look.plot, "panel of time series: any of theta_tip,Eb,Et,Wr,Tw (comma separated)");
  c->add_flag("--shadows", look.shadows, "cast the root's shadow on the plate and on itself (shadow map)");
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

int main(int argc, char** argv) {
  CLI::App app{"rootsim: growing Cosserat-rod roots on tilted plates (Cosserat mechanics, growth, movies)"};
  app.fallthrough();
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("rootsim ") + kVersion);

  cli::RunOptions run;
  CLI::App* cRun = app.add_subcommand("run", "simulate a scene and write a run directory");
  cRun->add_option("scene", run.scene, "scene file (TOML)")->required();
  cRun->add_option("--set", run.sets, "override a scene key: section.key=value (repeatable)");
  cRun->add_option("--out", run.out, "run directory (default: runs/<scene name>)");
  cRun->add_flag("--movie", run.movie, "also render movie.mp4 and final_top.png (its last frame) into the run directory; without --camera or --inset: the whole root with a follow inset (--inset)");
  addLookOptions(cRun, run.look);
  cRun->add_flag("--force", run.force,
                 "replace an earlier run (or interrupted run) at --out; folders rootsim did not write are never touched");
  cRun->add_flag("--resume", run.resume,
                 "continue a killed run from its last checkpoint in DIR.partial (a complete DIR: nothing to do)");
  cRun->add_flag("--quiet", run.quiet, "no progress output");

  cli::CheckOptions check;
  CLI::App* cCheck = app.add_subcommand("check", "validate a scene; print resolved keys and theory");
  cCheck->add_option("scene", check.scene, "scene file (TOML)")->required();
  cCheck->add_option("--set", check.sets, "override a scene key: section.key=value (repeatable)");

  app::RenderOptions render;
  CLI::App* cRender = app.add_subcommand("render", "render a saved run (its trajectory) to MP4 / PNG frames");
  cRender->add_option("run_dir", render.runDir, "run directory")->required();
  cRender->add_option("--mp4", render.mp4, "movie file (with no output flag: RUN_DIR/movie.mp4 + RUN_DIR/final_top.png)");
  cRender->add_option("--png-dir", render.pngDir, "write every frame as PNG into this folder");
  cRender->add_option("--final-png", render.finalPng, "write the movie's last frame (the same look) as PNG");
  cRender->add_option("--png", render.png, "a still: one frame of the movie these flags make, as PNG (with --at-h or --frame)");
  cRender->add_option("--at-h", render.atH, "the still's growth time [h]: the snapshot nearest H (ties to the earlier); outside the run's snapshots: exit 2");
  cRender->add_option("--frame", render.frame, "the still's frame number N (0-based, as the movie's frame_N.png)");
  cRender->add_option("--from-h", render.fromH, "the movie (or still) starts at the first snapshot at or after H hours");
  cRender->add_option("--to-h", render.toH, "the movie (or still) ends at the last snapshot at or before H hours");
  cRender->add_option("--hours-per-second", render.hoursPerSecond,
                      "playback speed: growth hours per second of movie at --fps; frame f shows the snapshot nearest "
                      "t_first + f * H / fps (skipping or repeating snapshots); default one frame per snapshot");
  cRender->add_option("--view", render.view, "top or 3d")->check(CLI::IsMember({"top", "3d"}));
  cRender->add_option("--size", render.size, "frame size WxH (even numbers), or auto (default): 1280x720, or 720x1280 for a root growing mostly downhill");
  cRender->add_option("--fps", render.fps, "frames per second")->check(CLI::Range(1, 240));
  cRender->add_option("--crf", render.crf, "H.264 quality, 0 (lossless) .. 51")->check(CLI::Range(0, 51));
  cRender->add_flag("--whiskers", render.whiskers, "draw thin +d1 (pink) / -d1 (orange) whiskers");
  cRender->add_flag("--transparent", render.transparent, "PNG pictures without the plate (--png-dir, --png or --final-png)");
  cRender->add_flag("--no-overlays", render.noOverlays, "no time, scale bar or parameters");
  cRender->add_option("--shader-dir", render.shaderDir,
                      "development: load tube/plane .vert/.frag from DIR instead of the built-in shaders");
  addLookOptions(cRender, render.look);
  cRender->add_option("--trace", render.trace.trace, "a traced root (RSML) drawn over every frame, aligned at the seed (docs/experiments.md)");
  cRender->add_option("--trace-root", render.trace.root, "the traced root: its id, #k, or plant/root (default: the file's one primary root)");
  cRender->add_option("--trace-px-per-mm", render.trace.pxPerMm, "pixels per millimetre, for a trace whose unit is pixel");
  cRender->add_option("--trace-downhill", render.trace.downhill, "the plate's downhill in the trace: +y (default), -y, or an angle in degrees");
  render.trace.flagPrefix = "--trace-";
  cRender->add_option("--root", render.root, "a plate's run: the root NAME drawn last, the one --camera follow follows (docs/plate.md)");
  cRender->add_flag("--plate-view", render.plateView, "a plate's run: frame the sown area with a margin, the plate outlined (docs/plate.md)");
  cRender->add_flag("--whole-plate", render.wholePlate, "with --plate-view: frame the whole plate");
  cRender->add_option("--scan", render.scanPxPerMm, "a plate's run: a scanner's picture of the whole plate at PX pixels per mm (light roots on a dark plate, no stripes or overlays), the last snapshot or --at-h/--frame, into --png FILE");
  cRender->add_flag("--force", render.force, "replace outputs rootsim wrote earlier (never a file rootsim did not write)");
  cRender->add_flag("--quiet", render.quiet, "no progress output");

  cli::ModesOptions modes;
  CLI::App* cModes = app.add_subcommand("modes", "the softest stiffness modes of a run's final state (modes.csv, modes.vtp)");
  cModes->add_option("run_dir", modes.runDir, "run directory")->required();
  cModes->add_option("--count", modes.count, "number of modes (default 6)")->check(CLI::Range(1, 1000));
  cModes->add_option("--root", modes.root, "a plate's run: the root NAME (or pass its folder roots/NAME)");
  cModes->add_flag("--force", modes.force, "replace modes.csv and modes.vtp written earlier");
  cModes->add_flag("--quiet", modes.quiet, "no progress output");

  app::ExportOptions exportOpts;
  CLI::App* cExport = app.add_subcommand("export", "a saved run's root in other programs' formats (RSML, glTF, ParaView)");
  cExport->add_option("run_dir", exportOpts.runDir, "run directory")->required();
  cExport->add_option("--rsml", exportOpts.rsml, "RSML 1.0 file (plate coordinates in mm, origin at the seed; docs/rsml.md)");
  cExport->add_option("--gltf", exportOpts.gltf, "glTF 2.0 binary FILE.glb for Blender and the web: the root with its stripes, the plate, obstacles; every snapshot animated, or one with --at-h (docs/gltf.md)");
  cExport->add_option("--paraview", exportOpts.paraview, "ParaView folder: the snapshots (.vtp with point data), root.pvd, plate.vtp and open_in_paraview.py, which shows the striped tube on the plate (docs/paraview.md)");
  cExport->add_option("--at-h", exportOpts.atH, "the snapshot nearest H hours (ties to the earlier; default: RSML the final one, glTF and ParaView every snapshot); outside the run's snapshots: exit 2");
  cExport->add_option("--every-h", exportOpts.everyH, "one file every H hours from the first snapshot, FILE_t<time>h.EXT (docs/rsml.md, Choosing the time); --gltf: those snapshots animated in its one file");
  cExport->add_flag("--force", exportOpts.force, "replace outputs rootsim wrote earlier (never a file rootsim did not write)");
  cExport->add_flag("--quiet", exportOpts.quiet, "no progress output");

  app::AnalyzeOptions analyze;
  CLI::App* cAnalyze = app.add_subcommand("analyze", "traits and run observables of every root of traced (or exported) RSML files: analysis.csv, analysis.json");
  cAnalyze->add_option("files", analyze.files, "RSML files (several files of one plate at several times give growth rates)")->required();
  cAnalyze->add_option("--px-per-mm", analyze.pxPerMm, "pixels per millimetre, for a file whose unit is pixel");
  cAnalyze->add_option("--downhill", analyze.downhill, "the plate's downhill in the file: +y (default: a scan with the plate upright), -y, or an angle in degrees from +y towards +x");
  cAnalyze->add_option("--times", analyze.times, "growth time of each file [h], comma separated (default: the file's time_h property)");
  cAnalyze->add_option("--ds-mm", analyze.dsMm, "resampling step of the shape analysis [mm]; 0: the trace's own points (default: 0 for a rootsim export, else 0.05)");
  cAnalyze->add_option("--exclude-tip-mm", analyze.excludeTipMm, "leave the last part out of the shape analysis, as runs leave out their growth zone [mm] (default: the file's growth.growth_zone_mm, else 0)");
  cAnalyze->add_option("--radius-mm", analyze.radiusMm, "root radius R for the peaks' hysteresis [mm] (default: the file's root.radius_mm, else half the median diameter, else 0.1)");
  cAnalyze->add_option("--out", analyze.out, "output folder (default analysis/<first file's stem>)");
  cAnalyze->add_flag("--force", analyze.force, "replace an analysis folder rootsim wrote earlier");
  cAnalyze->add_flag("--quiet", analyze.quiet, "no progress output");

  // the traced root's flags, shared by compare and fit
  auto traceFlags = [](CLI::App* c, app::TraceFlags& t) {
    c->add_option("--root", t.root, "the traced root: its id, #k, or plant/root (default: the file's one primary root)");
    c->add_option("--px-per-mm", t.pxPerMm, "pixels per millimetre, for a trace whose unit is pixel");
    c->add_option("--downhill", t.downhill, "the plate's downhill in the trace: +y (default), -y, or an angle in degrees from +y towards +x");
    c->add_option("--sigma-mm", t.sigmaMm, "position uncertainty of a traced point [mm] (default: one pixel of a pixel file, else 0.05)");
  };
  app::CompareOptions compare;
  CLI::App* cCompare = app.add_subcommand("compare", "a traced root (RSML) over a run's root: picture, observables side by side, shape distances");
  cCompare->add_option("run_dir", compare.runDir, "run directory")->required();
  cCompare->add_option("trace", compare.trace.trace, "RSML file")->required();
  traceFlags(cCompare, compare.trace);
  cCompare->add_option("--at-h", compare.atH, "the run's snapshot nearest this time [h] (default: the first as long as the trace)");
  cCompare->add_option("--out", compare.out, "output folder (default compare/<run>_vs_<trace>)");
  cCompare->add_option("--groups", compare.groups, "a plate's run: a sample sheet pairing plants with seedlings (plant,seedling)");
  cCompare->add_flag("--force", compare.force, "replace a compare folder rootsim wrote earlier");
  cCompare->add_flag("--quiet", compare.quiet, "no progress output");

  app::FitOptions fit;
  CLI::App* cFit = app.add_subcommand("fit", "fit free scene keys to a traced root (RSML): fit.json, the best fit's picture, the landscape");
  cFit->add_option("trace", fit.trace.trace, "RSML file")->required();
  cFit->add_option("--scene", fit.scene, "base scene (TOML)")->required();
  cFit->add_option("--free", fit.free, "free keys and their bounds: KEY=LO:HI[,KEY=LO:HI...]")->required();
  traceFlags(cFit, fit.trace);
  cFit->add_option("--objective", fit.objective, "observables (chi-square of skew, wavelength, amplitude; the default for a trace of one time), shape (the centreline at 8 fractions of its length) or timelapse (length, tip position and tip angle at every observation time; the default for a 2D+t trace)");
  cFit->add_option("-j,--jobs", fit.jobs, "simultaneous runs");
  cFit->add_option("--budget", fit.budget, "most runs (default 150)");
  cFit->add_option("--out", fit.out, "the fit's folder (resumable: a killed fit continues where it stopped)")->required();
  cFit->add_flag("--force", fit.force, "start again in a fit folder of another scene or trace");
  cFit->add_flag("--quiet", fit.quiet, "no progress output");

  app::MontageOptions montage;
  CLI::App* cMontage = app.add_subcommand("montage", "several runs side by side on one scale and one clock");
  cMontage->add_option("run_dirs", montage.runDirs, "run directories");
  cMontage->add_option("--mp4", montage.mp4, "movie file");
  cMontage->add_option("--png-dir", montage.pngDir, "write every frame as PNG into this folder");
  cMontage->add_option("--size", montage.size, "frame size WxH (even numbers), default 1280x720");
  cMontage->add_option("--labels", montage.labels, "one label per run, comma separated (default: the scene keys that differ)");
  cMontage->add_option("--view", montage.view, "top or 3d");
  cMontage->add_option("--fps", montage.fps, "frames per second")->check(CLI::Range(1, 240));
  cMontage->add_option("--crf", montage.crf, "H.264 quality, 0 (lossless) .. 51")->check(CLI::Range(0, 51));
  cMontage->add_option("--color-by", montage.colorBy, "colour the tubes: curvature, kappa1, kappa2, twist (signed: a diverging map centred on 0), kappa0, stretch or contact");
  cMontage->add_flag("--shadows", montage.shadows, "cast the roots' shadows on the plate");
  cMontage->add_flag("--force", montage.force, "replace outputs rootsim wrote earlier (never a file rootsim did not write)");
  cMontage->add_flag("--quiet", montage.quiet, "no progress output");

  cli::SweepCliOptions sweep;
  CLI::App* cSweep = app.add_subcommand("sweep", "run a grid of scenes (resumable, shardable); writes table.csv");
  cSweep->add_option("sweep", sweep.sweep, "sweep file (TOML: [sweep] scene, [grid], [set])")->required();
  cSweep->add_option("-j,--jobs", sweep.jobs, "parallel runs")->check(CLI::Range(1, 1024));
  cSweep->add_option("--shard", sweep.shard, "K/N: run only points with index % N == K-1 (for clusters)");
  cSweep->add_option("--out", sweep.out, "sweep folder (default: runs/<sweep name>)");
  cSweep->add_flag("--force", sweep.force, "rerun points run with another scene or that failed before");
  cSweep->add_flag("--quiet", sweep.quiet, "no progress output");

  cli::FigureCliOptions figure;
  CLI::App* cFigure = app.add_subcommand("figure", "make the paper's figure panels (PDF + SVG + PNG) and report.md");
  cFigure->add_option("name", figure.name, "fig2a fig2b fig2cde fig3a fig3b fig3d fig3d_gamma1 fig3d_apical fig4a fig4g, or all")->required();
  cFigure->add_flag("--quick", figure.quick, "coarsened runs (for CI)");
  cFigure->add_option("--out", figure.out, "output folder (default: figures)");
  cFigure->add_option("-j,--jobs", figure.jobs, "parallel simulations")->check(CLI::Range(1, 1024));
  cFigure->add_flag("--force", figure.force, "replace panels rootsim wrote earlier in --out");
  cFigure->add_flag("--quiet", figure.quiet, "no progress output");
  cFigure->add_option("--dpi", figure.dpi, "PNG resolution, stored in the PNG (default 300)")->check(CLI::Range(10.0, 2400.0));
  cFigure->add_option("--width-mm", figure.widthMm, "physical width of each panel, e.g. 85 or 180 (a journal column)")
      ->check(CLI::Range(10.0, 1000.0));
  cFigure->add_flag("--no-title", figure.noTitle, "panels without their figure title (the caption goes with the paper)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return usageError(app, e, argc, argv);
  }
  // a path option given an empty value ("--out ''") is refused, never taken for its default
  for (CLI::App* sub : app.get_subcommands())
    for (const CLI::Option* opt : sub->get_options())
      if (opt->count() > 0 && opt->get_type_size() != 0)
        for (const std::string& v : opt->results())
          if (v.empty()) {
            std::fprintf(stderr, "rootsim: error: %s: empty value (give a path or value, or leave the option out)\n",
                         opt->get_name().c_str());
            return 2;
          }
  // a --field-mm without a follow window to size is refused (app::parseLook), not ignored
  run.look.fieldGiven = cRun->get_option("--field-mm")->count() > 0;
  render.look.fieldGiven = cRender->get_option("--field-mm")->count() > 0;
  // run --movie without --camera or --inset: the inset look (app::renderRunMovie); render keeps fit
  run.look.cameraGiven = cRun->get_option("--camera")->count() > 0;
  run.look.insetByDefault = true;  // and --field-mm alone sizes that inset
  render.look.cameraGiven = cRender->get_option("--camera")->count() > 0;
  render.frameGiven = cRender->get_option("--frame")->count() > 0;
  try {
    if (cRun->parsed()) return cli::runCommand(run);
    if (cCheck->parsed()) return cli::checkCommand(check);
    if (cRender->parsed()) return cli::renderCommand(render);
    if (cMontage->parsed()) return cli::montageCommand(montage);
    if (cSweep->parsed()) return cli::sweepCommand(sweep);
    if (cModes->parsed()) return cli::modesCommand(modes);
    if (cExport->parsed()) return cli::exportCommand(exportOpts);
    if (cAnalyze->parsed()) return cli::analyzeCommand(analyze);
    if (cCompare->parsed()) return cli::compareCommand(compare);
    if (cFit->parsed()) return cli::fitCommand(fit);
    if (cFigure->parsed()) return cli::figureCommand(figure);
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
