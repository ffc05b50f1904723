// open_in_paraview.py and the ParaView folder of `export --paraview` (paraview.hpp, docs/paraview.md)
#include "rootsim/paraview.hpp"

#include <cmath>
#include <string>

#include "rootsim/environment.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/signature.hpp"
#include "rootsim/units.hpp"
#include "rootsim/vtk.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {
// the script, with @NAME@ for the values of this run
constexpr const char* kScript = R"PY(# open_in_paraview.py: @SIGNATURE@ (docs/paraview.md)
"""Opens the rootsim export in this folder in ParaView: the root as a tube with its two stripes along the
material directions +d1 (pink) and -d1 (orange), on the plate with its 1 mm grid, seen from above (down
the plate normal, downhill down the screen), the time slider stepping through the snapshots (growth time
in hours).

  paraview --script=open_in_paraview.py        the GUI
  pvpython open_in_paraview.py                 builds the pipeline (add --interact for a window)
  pvpython --force-offscreen-rendering open_in_paraview.py [--size W H] [--at-h H] --screenshot FILE.png

Options are taken in order: --at-h H goes to the last snapshot at or before growth time H [h],
--screenshot FILE saves the view as it is then (several --at-h/--screenshot pairs make several pictures
in one start), --size W H sets the picture's size in pixels (default 1200 800).

The pipeline, for each root: root.pvd, or a plate's NAME.pvd (the snapshots, point data per node) -> Tube (radius from the point data
radius_mm, 48 sides) -> Calculator "stripe" = dot(TubeNormals, d1), the cosine of the angle between the
tube surface's normal and the material direction d1 at each tube vertex -> coloured through a lookup table
with three bands: pink above cos 38 deg (the normal within 38 deg of +d1), orange below -cos 38 deg
(within 38 deg of -d1), ivory between, as rootsim's renderer draws the stripes.
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403 (ParaView's own scripting interface)

# the folder rootsim wrote this script into (ParaView's GUI runs a script without its file name)
WRITTEN_TO = @FOLDER@
# each root's name and .pvd: one root's export has root.pvd; a plate's a NAME.pvd per root (a lateral
# root's lists empty.vtp for the plate's snapshots before it emerged)
ROOTS = @ROOTS@


def here():
    """The folder of this script: its own name's (pvpython), else the one rootsim wrote it into
    (paraview --script=, the Python shell's Run Script), else the working folder."""
    if "__file__" in globals():
        return os.path.dirname(os.path.abspath(__file__))
    if os.path.isfile(os.path.join(WRITTEN_TO, ROOTS[0][1])):
        return WRITTEN_TO
    return os.getcwd()


HERE = here()

# the plate in the lab frame [mm] (written by rootsim for this run)
PLATE_NORMAL = @PLATE_NORMAL@  # unit normal, to the side the root lies on: the camera looks down it
UPHILL = @UPHILL@  # unit, up the plate: up the screen
LATERAL = @LATERAL@  # unit, across the plate: to the right on the screen
EXTENT_MM = @EXTENT@  # the plate's extent in plate coordinates: lateral from, to; uphill from, to
STRIPE_COS = @STRIPE_COS@  # cos of the stripes' half width (@STRIPE_DEG@ deg)
BODY = @BODY@  # ivory
PLUS = @PLUS@  # +d1 stripe: pink
MINUS = @MINUS@  # -d1 stripe: orange
TUBE_SIDES = 48


def build():
    """The pipeline, the colours and the top camera; returns the render view."""
    pipes = []
    for name, pvd in ROOTS:
        # one root: "root", "tube", "stripes"; a plate's roots: "NAME", "NAME tube", "NAME stripes"
        tag = "" if len(ROOTS) == 1 else name + " "
        root = PVDReader(registrationName=name, FileName=os.path.join(HERE, pvd))
        tube = Tube(registrationName=tag + "tube", Input=root)
        tube.Scalars = ["POINTS", "radius_mm"]
        tube.VaryRadius = "By Absolute Scalar"
        tube.NumberofSides = TUBE_SIDES
        tube.Capping = 1
        stripes = Calculator(registrationName=tag + "stripes", Input=tube)
        stripes.Function = "dot(TubeNormals, d1)"
        stripes.ResultArrayName = "stripe"
        pipes.append((root, tube, stripes))
    plate = XMLPolyDataReader(registrationName="plate", FileName=[os.path.join(HERE, "plate.vtp")])

    view = GetActiveViewOrCreate("RenderView")
    try:
        view.UseColorPaletteForBackground = 0  # ParaView >= 5.10
    except AttributeError:
        pass
    view.Background = [1.0, 1.0, 1.0]
    view.OrientationAxesVisibility = 0

    # the stripes: three bands of the cosine; the LUT keeps this range whatever the data's
    lut = GetColorTransferFunction("stripe")
    lut.AutomaticRescaleRangeMode = "Never"
    lut.ColorSpace = "RGB"
    eps = 1e-6
    lut.RGBPoints = ([-1.0] + list(MINUS) + [-STRIPE_COS] + list(MINUS) + [-STRIPE_COS + eps] + list(BODY) +
                     [STRIPE_COS - eps] + list(BODY) + [STRIPE_COS] + list(PLUS) + [1.0] + list(PLUS))
    lut.Discretize = 0
    for root, tube, stripes in pipes:
        tubeShow = Show(stripes, view)
        ColorBy(tubeShow, ("POINTS", "stripe"))
        tubeShow.LookupTable = lut
        tubeShow.SetScalarBarVisibility(view, False)
        tubeShow.Specular = 0.3

    # the plate, its grid and the obstacles: the cell array "part" (0 plate, 1 grid, 2 obstacle)
    plateShow = Show(plate, view)
    part = GetColorTransferFunction("part")
    part.InterpretValuesAsCategories = 1
    part.Annotations = ["0", "plate", "1", "grid (1 mm)", "2", "obstacle"]
    part.IndexedColors = [0.97, 0.97, 0.95, 0.62, 0.65, 0.70, 0.45, 0.40, 0.36]
    ColorBy(plateShow, ("CELLS", "part"))
    plateShow.LookupTable = part
    plateShow.SetScalarBarVisibility(view, False)
    plateShow.LineWidth = 1.0
    plateShow.Ambient = 1.0  # unlit: the plate's own colours, as bright from every side
    plateShow.Diffuse = 0.0

    # the growth time of the snapshot shown
    clock = AnnotateTime(registrationName="time")
    clock.Format = "t = {time:.1f} h"
    clockShow = Show(clock, view)
    clockShow.Color = [0.1, 0.1, 0.1]
    clockShow.FontSize = 20
    clockShow.WindowLocation = "Upper Left Corner"
    for root, tube, stripes in pipes:
        Hide(root, view)
        Hide(tube, view)

    # the time slider steps through the snapshots
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.PlayMode = "Snap To TimeSteps"
    times = list(GetTimeKeeper().TimestepValues)
    if times:
        scene.AnimationTime = times[-1]
    top(view)
    SetActiveSource(pipes[-1][2])
    return view


def top(view):
    """The top camera: parallel projection down the plate normal, uphill up the screen, the plate filling
    the view."""
    u0, u1, v0, v1 = EXTENT_MM
    u, v = 0.5 * (u0 + u1), 0.5 * (v0 + v1)
    centre = [u * LATERAL[k] + v * UPHILL[k] for k in range(3)]
    size = view.ViewSize
    aspect = float(size[0]) / float(size[1]) if size[1] > 0 else 1.5
    half = 0.5 * max(v1 - v0, (u1 - u0) / aspect)
    distance = 10.0 * (half + 1.0)
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[k] + distance * PLATE_NORMAL[k] for k in range(3)]
    view.CameraViewUp = list(UPHILL)
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 1.02 * half
    view.CenterOfRotation = centre


def go_to(hours):
    """The last snapshot at or before growth time `hours` (the first one if none is)."""
    times = list(GetTimeKeeper().TimestepValues)
    if not times:
        return
    at = [t for t in times if t <= hours]
    GetAnimationScene().AnimationTime = at[-1] if at else times[0]


def main(argv):
    size = [1200, 800]
    args = list(argv)
    if "--size" in args:
        i = args.index("--size")
        size = [int(args[i + 1]), int(args[i + 2])]
    if "--screenshot" in args or "--size" in args:
        GetActiveViewOrCreate("RenderView").ViewSize = size
    view = build()
    i = 0
    while i < len(args):
        a = args[i]
        if a == "--at-h":
            go_to(float(args[i + 1]))
            i += 2
        elif a == "--screenshot":
            Render(view)
            SaveScreenshot(args[i + 1], view, ImageResolution=size)
            i += 2
        elif a == "--size":
            i += 3
        else:
            i += 1
    Render(view)
    if "--interact" in args:
        Interact(view)


main(sys.argv[1:] if "__file__" in globals() and sys.argv and sys.argv[0].endswith(".py") else [])
)PY";

std::string tuple(const double* v, int n) {
  std::string s = "(";
  for (int k = 0; k < n; ++k) s += (k ? ", " : "") + numberText(v[k]);
  return s + ")";
}
std::string tuple(const Eigen::Vector3d& v) { return tuple(v.data(), 3); }

void replaceAll(std::string& s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
}
}  // namespace

// a Python string literal (UTF-8 bytes kept; backslash, quote and newline escaped)
static std::string pyString(const std::string& text) {
  std::string lit = "\"";
  for (char c : text) {
    if (c == '\\' || c == '"') lit += '\\';
    if (c == '\n') {
      lit += "\\n";
      continue;
    }
    lit += c;
  }
  return lit + '"';
}

std::string paraviewScript(const SceneInfo& info, const std::array<double, 4>& extentMm, const fs::path& folder,
                           const std::vector<std::pair<std::string, std::string>>& roots) {
  const PlateFrame plate = PlateFrame::tilted(info.alphaDeg * units::deg);
  const StripeStyle style;
  std::string s = kScript;
  const std::string lit = pyString(fs::absolute(folder).lexically_normal().string());
  std::string rootList = "[";
  for (const auto& [name, pvd] : roots) rootList += (rootList.size() > 1 ? ", (" : "(") + pyString(name) + ", " + pyString(pvd) + ")";
  rootList += "]";
  replaceAll(s, "@SIGNATURE@", std::string("written by ") + outputSignatureText());
  replaceAll(s, "@PLATE_NORMAL@", tuple(plate.normal));
  replaceAll(s, "@UPHILL@", tuple(plate.uphill()));
  replaceAll(s, "@LATERAL@", tuple(plate.lateral));
  replaceAll(s, "@EXTENT@", tuple(extentMm.data(), 4));
  replaceAll(s, "@STRIPE_COS@", numberText(std::cos(style.halfWidthDeg * units::deg)));
  replaceAll(s, "@STRIPE_DEG@", numberText(style.halfWidthDeg));
  replaceAll(s, "@BODY@", tuple(style.body.data(), 3));
  replaceAll(s, "@PLUS@", tuple(style.plus.data(), 3));
  replaceAll(s, "@MINUS@", tuple(style.minus.data(), 3));
  replaceAll(s, "@ROOTS@", rootList);
  replaceAll(s, "@FOLDER@", lit);  // last: a folder name holding "@...@" stays as it is
  return s;
}

void writeParaviewFiles(const fs::path& dir, const std::vector<Snapshot>& snaps, const SceneInfo& info,
                        const fs::path& finalDir) {
  std::vector<std::pair<double, std::string>> entries;
  for (const Snapshot& s : snaps) {
    const std::string name = vtpFileName(s);
    writeFileAtomic(dir / name, snapshotVtp(s, info));
    entries.emplace_back(s.timeH, name);
  }
  writeFileAtomic(dir / "root.pvd", pvdText(entries));
  writeFileAtomic(dir / "plate.vtp", plateVtp(info, snaps));
  writeFileAtomic(dir / "open_in_paraview.py",
                  paraviewScript(info, plateExtentMm(info, snaps), finalDir.empty() ? dir : finalDir));
}

void writeParaviewPlateFiles(const fs::path& dir, const std::vector<RootSeries>& roots, const std::vector<double>& timesH,
                             const SceneInfo& info, const fs::path& finalDir) {
  std::vector<Snapshot> all;
  std::vector<std::pair<std::string, std::string>> pvds;
  bool empty = false;
  for (const RootSeries& r : roots) {
    // a root's own folder: a lateral root's files may share step numbers with its parent's
    fs::create_directory(dir / r.name);
    std::vector<std::pair<double, std::string>> entries;
    for (int f = 0; f < r.firstFrame && f < static_cast<int>(timesH.size()); ++f)
      entries.emplace_back(timesH[static_cast<std::size_t>(f)], "empty.vtp"), empty = true;
    for (const Snapshot& s : r.snaps) {
      const std::string name = r.name + "/" + vtpFileName(s);
      writeFileAtomic(dir / name, snapshotVtp(s, info));
      entries.emplace_back(s.timeH, name);
      all.push_back(s);
    }
    writeFileAtomic(dir / (r.name + ".pvd"), pvdText(entries));
    pvds.emplace_back(r.name, r.name + ".pvd");
  }
  // no root yet: no points, and the point arrays the script's pipeline reads (radius_mm, d1)
  if (empty)
    writeFileAtomic(dir / "empty.vtp",
                    "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
                    "<PolyData><Piece NumberOfPoints=\"0\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
                    "NumberOfPolys=\"0\">\n<PointData><DataArray type=\"Float64\" Name=\"radius_mm\" format=\"ascii\"/>"
                    "<DataArray type=\"Float64\" Name=\"d1\" NumberOfComponents=\"3\" format=\"ascii\"/></PointData>\n"
                    "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\"/></Points>\n"
                    "</Piece></PolyData>\n</VTKFile>\n");
  writeFileAtomic(dir / "plate.vtp", plateVtp(info, all));
  writeFileAtomic(dir / "open_in_paraview.py",
                  paraviewScript(info, plateExtentMm(info, all), finalDir.empty() ? dir : finalDir, pvds));
}

}  // namespace rootsim
