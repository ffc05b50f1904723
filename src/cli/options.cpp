// the commands' options, declared once (options.hpp): name, type, default (the options struct's own),
// unit, help, CLI11's checks, and the member each sets
#include "options.hpp"

#include <cstdio>

#include "commands.hpp"
#include "rootsim/number_text.hpp"

namespace rootsim::cli {

namespace {

template <class T>
constexpr OptionKind kindOf() {
  if constexpr (std::is_same_v<T, std::string>) return OptionKind::Text;
  else if constexpr (std::is_same_v<T, std::vector<std::string>>) return OptionKind::Texts;
  else if constexpr (std::is_same_v<T, bool>) return OptionKind::Flag;
  else if constexpr (std::is_same_v<T, int>) return OptionKind::Int;
  else {
    static_assert(std::is_same_v<T, double>, "an option is a text, texts, int, double or flag");
    return OptionKind::Real;
  }
}

// a command's table, built in the order --help lists it; the modifiers apply to the option added last
template <class O>
class Table {
 public:
  Table(std::string name, std::string help) {
    c_.name = std::move(name);
    c_.help = std::move(help);
    c_.type = typeid(O);
  }
  // an option or flag; field(o) is the member it sets
  template <class F>
  Table& opt(std::string flag, F field, std::string unit, std::string help) {
    using T = std::remove_reference_t<std::invoke_result_t<F&, O&>>;
    OptionSpec s;
    s.flag = std::move(flag);
    s.kind = kindOf<T>();
    s.unit = std::move(unit);
    s.help = std::move(help);
    s.field = [field](void* p) mutable -> void* { return &field(*static_cast<O*>(p)); };
    c_.options.push_back(std::move(s));
    return *this;
  }
  Table& required() {
    c_.options.back().required = true;
    return *this;
  }
  Table& range(double lo, double hi) {
    OptionSpec& s = c_.options.back();
    s.hasRange = true;
    s.lo = lo;
    s.hi = hi;
    return *this;
  }
  Table& choices(std::vector<std::string> v) {
    c_.options.back().choices = std::move(v);
    return *this;
  }
  Table& python(std::string name) {
    c_.options.back().python = std::move(name);
    return *this;
  }
  // given(o) records whether the option was given
  template <class G>
  Table& given(G g) {
    c_.options.back().given = [g](void* p) mutable -> bool* { return &g(*static_cast<O*>(p)); };
    return *this;
  }
  // the command's presets on a fresh options struct, and the command
  CommandSpec done(std::function<void(O&)> preset, int (*run)(const O&)) {
    c_.make = [preset]() -> std::shared_ptr<void> {
      auto o = std::make_shared<O>();
      if (preset) preset(*o);
      return o;
    };
    c_.run = [run](void* p) { return run(*static_cast<const O*>(p)); };
    return std::move(c_);
  }

 private:
  CommandSpec c_;
};

#define FIELD(member) [](O& o) -> auto& { return o.member; }

// the movie look, shared by run --movie and render
template <class O>
void lookOptions(Table<O>& t) {
  t.opt("--camera", FIELD(look.camera), "", "fit (whole root; render's default) or follow (a window following the growth zone); run --movie without --camera: fit with a follow inset")
      .given(FIELD(look.cameraGiven))
      .opt("--field-mm", FIELD(look.fieldMm), "mm", "follow window width [mm] (default 2); with --camera follow or --inset, or alone with run --movie (its default inset)")
      .given(FIELD(look.fieldGiven))
      .opt("--inset", FIELD(look.inset), "", "fit view with a follow window in a free corner, its region marked")
      .opt("--color-by", FIELD(look.colorBy), "", "colour the tube: curvature, kappa1, kappa2, twist (signed: a diverging map centred on 0), kappa0, stretch or contact")
      .opt("--plot", FIELD(look.plot), "", "panel of time series: any of theta_tip,Eb,Et,Wr,Tw (comma separated)")
      .opt("--shadows", FIELD(look.shadows), "", "cast the root's shadow on the plate and on itself (shadow map)");
}

// the traced root's flags, shared by compare and fit
template <class O>
void traceOptions(Table<O>& t) {
  t.opt("--root", FIELD(trace.root), "", "the traced root: its id, #k, or plant/root (default: the file's one primary root)")
      .opt("--px-per-mm", FIELD(trace.pxPerMm), "px/mm", "pixels per millimetre, for a trace whose unit is pixel")
      .opt("--downhill", FIELD(trace.downhill), "", "the plate's downhill in the trace: +y (default), -y, or an angle in degrees from +y towards +x")
      .opt("--sigma-mm", FIELD(trace.sigmaMm), "mm", "position uncertainty of a traced point [mm] (default: the trace's estimated noise_mm, at least a pixel / sqrt(12); a rootsim export or a root of fewer than 9 points: a pixel, else 0.05)");
}

CommandSpec runSpec() {
  using O = RunOptions;
  Table<O> t("run", "simulate a scene and write a run directory");
  t.opt("scene", FIELD(scene), "", "scene file (TOML)").required().python("scene_or_path")
      .opt("--set", FIELD(sets), "", "override a scene key: section.key=value (repeatable)")
      .opt("--out", FIELD(out), "", "run directory (default: runs/<scene name>)")
      .opt("--movie", FIELD(movie), "", "also render movie.mp4 and final_top.png (its last frame) into the run directory; without --camera or --inset: the whole root with a follow inset (--inset)");
  lookOptions(t);
  t.opt("--force", FIELD(force), "", "replace an earlier run (or interrupted run) at --out; folders rootsim did not write are never touched")
      .opt("--resume", FIELD(resume), "", "continue a killed run from its last checkpoint in DIR.partial (a complete DIR: nothing to do)")
      .opt("--quiet", FIELD(quiet), "", "no progress output");
  // run --movie without --camera or --inset: the inset look (app::renderRunMovie); render keeps fit
  return t.done([](O& o) { o.look.insetByDefault = true; }, runCommand);
}

CommandSpec checkSpec() {
  using O = CheckOptions;
  Table<O> t("check", "validate a scene; print resolved keys and theory");
  t.opt("scene", FIELD(scene), "", "scene file (TOML)").required()
      .opt("--set", FIELD(sets), "", "override a scene key: section.key=value (repeatable)");
  return t.done(nullptr, checkCommand);
}

CommandSpec renderSpec() {
  using O = app::RenderOptions;
  Table<O> t("render", "render a saved run (its trajectory) to MP4 / PNG frames");
  t.opt("run_dir", FIELD(runDir), "", "run directory").required()
      .opt("--mp4", FIELD(mp4), "", "movie file (with no output flag: RUN_DIR/movie.mp4 + RUN_DIR/final_top.png)")
      .opt("--png-dir", FIELD(pngDir), "", "write every frame as PNG into this folder")
      .opt("--final-png", FIELD(finalPng), "", "write the movie's last frame (the same look) as PNG")
      .opt("--png", FIELD(png), "", "a still: one frame of the movie these flags make, as PNG (with --at-h or --frame)")
      .opt("--at-h", FIELD(atH), "h", "the still's growth time [h]: the snapshot nearest H (ties to the earlier); outside the run's snapshots: exit 2")
      .opt("--frame", FIELD(frame), "", "the still's frame number N (0-based, as the movie's frame_N.png)")
      .given(FIELD(frameGiven))
      .opt("--from-h", FIELD(fromH), "h", "the movie (or still) starts at the first snapshot at or after H hours")
      .opt("--to-h", FIELD(toH), "h", "the movie (or still) ends at the last snapshot at or before H hours")
      .opt("--hours-per-second", FIELD(hoursPerSecond), "h/s",
           "playback speed: growth hours per second of movie at --fps; frame f shows the snapshot nearest "
           "t_first + f * H / fps (skipping or repeating snapshots); default one frame per snapshot")
      .opt("--view", FIELD(view), "", "top or 3d").choices({"top", "3d"})
      .opt("--size", FIELD(size), "px", "frame size WxH (even numbers), or auto (default): 1280x720, or 720x1280 for a root growing mostly downhill")
      .opt("--fps", FIELD(fps), "1/s", "frames per second").range(1, 240)
      .opt("--crf", FIELD(crf), "", "H.264 quality, 0 (lossless) .. 51").range(0, 51)
      .opt("--whiskers", FIELD(whiskers), "", "draw thin +d1 (pink) / -d1 (orange) whiskers")
      .opt("--transparent", FIELD(transparent), "", "PNG pictures without the plate (--png-dir, --png or --final-png)")
      .opt("--no-overlays", FIELD(noOverlays), "", "no time, scale bar or parameters")
      .opt("--shader-dir", FIELD(shaderDir), "", "development: load tube/plane .vert/.frag from DIR instead of the built-in shaders");
  lookOptions(t);
  t.opt("--trace", FIELD(trace.trace), "", "a traced root (RSML) drawn over every frame, aligned at the seed (docs/experiments.md)")
      .opt("--trace-root", FIELD(trace.root), "", "the traced root: its id, #k, or plant/root (default: the file's one primary root)")
      .opt("--trace-px-per-mm", FIELD(trace.pxPerMm), "px/mm", "pixels per millimetre, for a trace whose unit is pixel")
      .opt("--trace-downhill", FIELD(trace.downhill), "", "the plate's downhill in the trace: +y (default), -y, or an angle in degrees")
      .opt("--root", FIELD(root), "", "a plate's run: the root NAME drawn last, the one --camera follow follows (docs/plate.md)")
      .opt("--plate-view", FIELD(plateView), "", "a plate's run: frame the sown area with a margin, the plate outlined (docs/plate.md)")
      .opt("--whole-plate", FIELD(wholePlate), "", "with --plate-view: frame the whole plate")
      .opt("--scan", FIELD(scanPxPerMm), "px/mm", "a plate's run: a scanner's picture of the whole plate at PX pixels per mm (light roots on a dark plate, no stripes or overlays), the last snapshot or --at-h/--frame, into --png FILE")
      .opt("--force", FIELD(force), "", "replace outputs rootsim wrote earlier (never a file rootsim did not write)")
      .opt("--quiet", FIELD(quiet), "", "no progress output");
  return t.done([](O& o) { o.trace.flagPrefix = "--trace-"; }, renderCommand);
}

CommandSpec modesSpec() {
  using O = ModesOptions;
  Table<O> t("modes", "the softest stiffness modes of a run's final state (modes.csv, modes.vtp)");
  t.opt("run_dir", FIELD(runDir), "", "run directory").required()
      .opt("--count", FIELD(count), "", "number of modes (default 6)").range(1, 1000)
      .opt("--root", FIELD(root), "", "a plate's run: the root NAME (or pass its folder roots/NAME)")
      .opt("--force", FIELD(force), "", "replace modes.csv and modes.vtp written earlier")
      .opt("--quiet", FIELD(quiet), "", "no progress output");
  return t.done(nullptr, modesCommand);
}

CommandSpec exportSpec() {
  using O = app::ExportOptions;
  Table<O> t("export", "a saved run's root in other programs' formats (RSML, glTF, ParaView)");
  t.opt("run_dir", FIELD(runDir), "", "run directory").required()
      .opt("--rsml", FIELD(rsml), "", "RSML 1.0 file (plate coordinates in mm, origin at the seed; docs/rsml.md)")
      .opt("--gltf", FIELD(gltf), "", "glTF 2.0 binary FILE.glb for Blender and the web: the root with its stripes, the plate, obstacles; every snapshot animated, or one with --at-h (docs/gltf.md)")
      .opt("--paraview", FIELD(paraview), "", "ParaView folder: the snapshots (.vtp with point data), root.pvd, plate.vtp and open_in_paraview.py, which shows the striped tube on the plate (docs/paraview.md)")
      .opt("--at-h", FIELD(atH), "h", "the snapshot nearest H hours (ties to the earlier; default: RSML the final one, glTF and ParaView every snapshot); outside the run's snapshots: exit 2")
      .opt("--every-h", FIELD(everyH), "h", "one file every H hours from the first snapshot, FILE_t<time>h.EXT (docs/rsml.md, Choosing the time); --gltf: those snapshots animated in its one file")
      .opt("--force", FIELD(force), "", "replace outputs rootsim wrote earlier (never a file rootsim did not write)")
      .opt("--quiet", FIELD(quiet), "", "no progress output");
  return t.done(nullptr, exportCommand);
}

CommandSpec analyzeSpec() {
  using O = app::AnalyzeOptions;
  Table<O> t("analyze", "traits and run observables of every root of traced (or exported) RSML files: analysis.csv, analysis.json");
  t.opt("files", FIELD(files), "", "RSML files (several files of one plate at several times give growth rates)").required()
      .opt("--px-per-mm", FIELD(pxPerMm), "px/mm", "pixels per millimetre, for a file whose unit is pixel")
      .opt("--downhill", FIELD(downhill), "", "the plate's downhill in the file: +y (default: a scan with the plate upright), -y, or an angle in degrees from +y towards +x")
      .opt("--times", FIELD(times), "h", "growth time of each file [h], comma separated (default: the file's time_h property)")
      .opt("--ds-mm", FIELD(dsMm), "mm", "resampling step of the shape analysis [mm]; 0: the trace's own points (default: 0 for a rootsim export, else 0.05)")
      .opt("--exclude-tip-mm", FIELD(excludeTipMm), "mm", "leave the last part out of the shape analysis, as runs leave out their growth zone [mm] (default: the file's growth.growth_zone_mm, else 0)")
      .opt("--radius-mm", FIELD(radiusMm), "mm", "root radius R for the peaks' hysteresis [mm] (default: the file's root.radius_mm, else half the median diameter, else 0.1)")
      .opt("--out", FIELD(out), "", "output folder (default analysis/<first file's stem>)")
      .opt("--force", FIELD(force), "", "replace an analysis folder rootsim wrote earlier")
      .opt("--quiet", FIELD(quiet), "", "no progress output");
  return t.done(nullptr, analyzeCommand);
}

CommandSpec compareSpec() {
  using O = app::CompareOptions;
  Table<O> t("compare", "a traced root (RSML) over a run's root: picture, observables side by side, shape distances");
  t.opt("run_dir", FIELD(runDir), "", "run directory").required()
      .opt("trace", FIELD(trace.trace), "", "RSML file").required();
  traceOptions(t);
  t.opt("--at-h", FIELD(atH), "h", "the run's snapshot nearest this time [h] (default: the first as long as the trace)")
      .opt("--out", FIELD(out), "", "output folder (default compare/<run>_vs_<trace>)")
      .opt("--groups", FIELD(groups), "", "a plate's run: a sample sheet pairing plants with seedlings (plant,seedling)")
      .opt("--force", FIELD(force), "", "replace a compare folder rootsim wrote earlier")
      .opt("--quiet", FIELD(quiet), "", "no progress output");
  return t.done(nullptr, compareCommand);
}

CommandSpec fitSpec() {
  using O = app::FitOptions;
  Table<O> t("fit", "fit free scene keys to a traced root (RSML): fit.json, the best fit's picture, the landscape");
  t.opt("trace", FIELD(trace.trace), "", "RSML file").required()
      .opt("more", FIELD(more), "", "more RSML files of the plate (with --groups)")
      .opt("--scene", FIELD(scene), "", "base scene (TOML)").required()
      .opt("--free", FIELD(free), "", "free keys and their bounds: KEY=LO:HI[,KEY=LO:HI...]").required();
  traceOptions(t);
  t.opt("--objective", FIELD(objective), "", "observables (chi-square of skew, wavelength, amplitude; the default for a trace of one time), shape (the centreline at 8 fractions of its length) or timelapse (length, tip position and tip angle at every observation time; the default for a 2D+t trace)")
      .opt("-j,--jobs", FIELD(jobs), "", "simultaneous runs")
      .opt("--budget", FIELD(budget), "", "most runs (default 150)")
      .opt("--groups", FIELD(groups), "", "a traced plate by group: a sample sheet (plant,group) naming each plant's group; each group's keys are fitted to its seedlings together, and every key compared between groups")
      .opt("--out", FIELD(out), "", "the fit's folder (resumable: a killed fit continues where it stopped)").required()
      .opt("--force", FIELD(force), "", "start again in a fit folder of another scene or trace")
      .opt("--design-only", FIELD(designOnly), "", "write the start design as a sweep file (each group's with --groups) and stop: run it with rootsim sweep DIR/design.toml --out DIR/runs --shard K/N (a cluster), then the fit again finds those runs")
      .opt("--quiet", FIELD(quiet), "", "no progress output");
  return t.done(nullptr, fitCommand);
}

CommandSpec montageSpec() {
  using O = app::MontageOptions;
  Table<O> t("montage", "several runs side by side on one scale and one clock");
  t.opt("run_dirs", FIELD(runDirs), "", "run directories")
      .opt("--mp4", FIELD(mp4), "", "movie file")
      .opt("--png-dir", FIELD(pngDir), "", "write every frame as PNG into this folder")
      .opt("--size", FIELD(size), "px", "frame size WxH (even numbers), default 1280x720")
      .opt("--labels", FIELD(labels), "", "one label per run, comma separated (default: the scene keys that differ)")
      .opt("--view", FIELD(view), "", "top or 3d")
      .opt("--fps", FIELD(fps), "1/s", "frames per second").range(1, 240)
      .opt("--crf", FIELD(crf), "", "H.264 quality, 0 (lossless) .. 51").range(0, 51)
      .opt("--color-by", FIELD(colorBy), "", "colour the tubes: curvature, kappa1, kappa2, twist (signed: a diverging map centred on 0), kappa0, stretch or contact")
      .opt("--shadows", FIELD(shadows), "", "cast the roots' shadows on the plate")
      .opt("--force", FIELD(force), "", "replace outputs rootsim wrote earlier (never a file rootsim did not write)")
      .opt("--quiet", FIELD(quiet), "", "no progress output");
  return t.done(nullptr, montageCommand);
}

CommandSpec sweepSpec() {
  using O = SweepCliOptions;
  Table<O> t("sweep", "run a grid of scenes (resumable, shardable); writes table.csv");
  t.opt("sweep", FIELD(sweep), "", "sweep file (TOML: [sweep] scene, [grid], [set])").required().python("sweep_file")
      .opt("-j,--jobs", FIELD(jobs), "", "parallel runs").range(1, 1024)
      .opt("--shard", FIELD(shard), "", "K/N: run only points with index % N == K-1 (for clusters)")
      .opt("--out", FIELD(out), "", "sweep folder (default: runs/<sweep name>)")
      .opt("--force", FIELD(force), "", "rerun points run with another scene or that failed before")
      .opt("--quiet", FIELD(quiet), "", "no progress output");
  return t.done(nullptr, sweepCommand);
}

CommandSpec figureSpec() {
  using O = FigureCliOptions;
  Table<O> t("figure", "make the paper's figure panels (PDF + SVG + PNG) and report.md");
  t.opt("name", FIELD(name), "", "fig2a fig2b fig2cde fig3a fig3b fig3d fig3d_gamma1 fig3d_apical fig4a fig4g, or all").required()
      .opt("--quick", FIELD(quick), "", "coarsened runs (for CI)")
      .opt("--out", FIELD(out), "", "output folder (default: figures)")
      .opt("-j,--jobs", FIELD(jobs), "", "parallel simulations").range(1, 1024)
      .opt("--force", FIELD(force), "", "replace panels rootsim wrote earlier in --out")
      .opt("--quiet", FIELD(quiet), "", "no progress output")
      .opt("--dpi", FIELD(dpi), "dpi", "PNG resolution, stored in the PNG (default 300)").range(10.0, 2400.0)
      .opt("--width-mm", FIELD(widthMm), "mm", "physical width of each panel, e.g. 85 or 180 (a journal column)").range(10.0, 1000.0)
      .opt("--no-title", FIELD(noTitle), "", "panels without their figure title (the caption goes with the paper)");
  return t.done(nullptr, figureCommand);
}

#undef FIELD

template <class T>
T& at(const OptionSpec& o, void* opts, OptionKind k) {
  if (o.kind != k) throw std::logic_error(o.flag + ": set as another kind of option");
  return *static_cast<T*>(o.field(opts));
}

// "|" inside a markdown table cell
std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += "\\|";
    else out += c;
  }
  return out;
}

}  // namespace

std::string OptionSpec::longName() const {
  const std::size_t comma = flag.rfind(',');
  std::string n = comma == std::string::npos ? flag : flag.substr(comma + 1);
  return n.substr(n.find_first_not_of('-'));
}

std::string OptionSpec::pythonName() const {
  if (!python.empty()) return python;
  std::string n = negated() ? longName().substr(3) : longName();
  for (char& c : n)
    if (c == '-') c = '_';
  return n;
}

std::string OptionSpec::displayName() const {
  if (positional()) return flag;
  const std::size_t comma = flag.rfind(',');
  return (comma == std::string::npos ? std::string() : flag.substr(0, comma) + ", ") + "--" + longName();
}

const OptionSpec* CommandSpec::find(const std::string& pythonName) const {
  for (const OptionSpec& o : options)
    if (o.pythonName() == pythonName) return &o;
  return nullptr;
}

const std::vector<CommandSpec>& commands() {
  static const std::vector<CommandSpec> all = {runSpec(),     checkSpec(),   renderSpec(), modesSpec(),
                                               exportSpec(),  analyzeSpec(), compareSpec(), fitSpec(),
                                               montageSpec(), sweepSpec(),   figureSpec()};
  return all;
}

const CommandSpec& command(const std::string& name) {
  for (const CommandSpec& c : commands())
    if (c.name == name) return c;
  throw std::logic_error("no command " + name);
}

std::string defaultText(const CommandSpec& c, const OptionSpec& o) {
  const std::shared_ptr<void> d = c.make();
  void* p = o.field(d.get());
  switch (o.kind) {
    case OptionKind::Text: return *static_cast<std::string*>(p);
    case OptionKind::Texts: return "";
    case OptionKind::Int: return std::to_string(*static_cast<int*>(p));
    case OptionKind::Real: {
      const double v = *static_cast<double*>(p);
      return v == app::AnalyzeOptions::kUnset ? std::string() : numberText(v);
    }
    case OptionKind::Flag: return "";
  }
  return "";
}

void setText(const OptionSpec& o, void* opts, const std::string& v) { at<std::string>(o, opts, OptionKind::Text) = v; }
void setTexts(const OptionSpec& o, void* opts, const std::vector<std::string>& v) {
  at<std::vector<std::string>>(o, opts, OptionKind::Texts) = v;
}
void setInt(const OptionSpec& o, void* opts, int v) { at<int>(o, opts, OptionKind::Int) = v; }
void setReal(const OptionSpec& o, void* opts, double v) { at<double>(o, opts, OptionKind::Real) = v; }
void setFlag(const OptionSpec& o, void* opts, bool v) { at<bool>(o, opts, OptionKind::Flag) = v; }
void markGiven(const OptionSpec& o, void* opts, bool given) {
  if (o.given) *o.given(opts) = given;
}

std::string checkNumber(const CommandSpec& c, const OptionSpec& o, double v) {
  // as CLI11's Range: a NaN passes on to the command's own check (which names it, e.g. figure's --dpi)
  if (!o.hasRange || !(v < o.lo || v > o.hi)) return "";
  return c.name + ": --" + o.longName() + ": Value " + numberText(v) + " not in range " + numberText(o.lo) + " to " +
         numberText(o.hi);
}

std::string checkText(const CommandSpec& c, const OptionSpec& o, const std::string& v) {
  if (o.choices.empty()) return "";
  std::string list;
  for (const std::string& ch : o.choices) {
    if (ch == v) return "";
    list += (list.empty() ? "" : ",") + ch;
  }
  return c.name + ": --" + o.longName() + ": " + v + " not in {" + list + "}";
}

std::string optionsMarkdown() {
  static const char* kKind[] = {"text", "texts", "integer", "number", "flag"};
  std::string md;
  for (const CommandSpec& c : commands()) {
    md += "### rootsim " + c.name + "\n\n" + c.help + "; in Python `rootsim." + c.name + "(...)`.\n\n";
    md += "| option | Python | type | default | unit | does |\n|---|---|---|---|---|---|\n";
    for (const OptionSpec& o : c.options) {
      std::string type = kKind[static_cast<int>(o.kind)];
      if (o.hasRange) type += " in [" + numberText(o.lo) + ", " + numberText(o.hi) + "]";
      if (!o.choices.empty()) {
        type += ": ";
        for (std::size_t k = 0; k < o.choices.size(); ++k) type += (k ? " \\| " : "") + o.choices[k];
      }
      if (o.required) type += ", required";
      const std::string def = defaultText(c, o);
      md += "| `" + o.displayName() + "` | `" + o.pythonName() + (o.negated() ? "=False" : "") + "` | " + type +
            " | " + (def.empty() ? "" : "`" + cell(def) + "`") + " | " + cell(o.unit) + " | " + cell(o.help) + " |\n";
    }
    md += "\n";
  }
  return md;
}

}  // namespace rootsim::cli
