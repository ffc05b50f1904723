// rendering costs of a 300-element waving, twisted root at 1280x720 and 1920x1080 (4x MSAA):
// scene build, draw + readback, PNG, H.264 encode, and the end-to-end movie rate with drawing and
// encoding overlapped (renderMovie), plain and with the movie looks (follow camera, colours, plot
// panel, shadows) up to 4K. Run: bench_render --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <stb_image_write.h>

#include "render_test_util.hpp"
#include "rootsim/compose.hpp"
#include "rootsim/gl_renderer.hpp"
#include "rootsim/movie.hpp"
#include "rootsim/png.hpp"
#include "rootsim/png_encode.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/video_writer.hpp"

using namespace rootsim;

namespace {

constexpr int kElements = 300;

// a root lying on a 40 deg plate, waving sideways (amplitude 1 mm, wavelength 8 mm), 30 mm long,
// its d1 turning by a quarter turn per wavelength; k shifts the wave (a different frame each k)
Snapshot wavingRoot(int k) {
  const double a = 40.0 * std::numbers::pi / 180.0, R = 1e-4, L = 30e-3;
  const Eigen::Vector3d n(0, -std::cos(a), std::sin(a)), down(0, -std::sin(a), -std::cos(a)), lat(1, 0, 0);
  Snapshot s;
  s.step = k;
  s.timeH = 0.05 * k;
  s.x.resize(3, kElements + 1);
  s.d1.resize(3, kElements);
  s.d3.resize(3, kElements);
  s.radius = Eigen::VectorXd::Constant(kElements, R);
  const double phase = 0.2 * k;
  for (int i = 0; i <= kElements; ++i) {
    const double t = L * i / kElements;
    s.x.col(i) = t * down + 1e-3 * std::sin(2 * std::numbers::pi * t / 8e-3 + phase) * lat + R * n;
  }
  for (int e = 0; e < kElements; ++e) {
    const Eigen::Vector3d d3 = (s.x.col(e + 1) - s.x.col(e)).normalized();
    const double th = 0.5 * std::numbers::pi * (L * (e + 0.5) / kElements) / 8e-3;
    Eigen::Vector3d d1 = std::cos(th) * lat + std::sin(th) * n;
    d1 = (d1 - d1.dot(d3) * d3).normalized();
    s.d3.col(e) = d3;
    s.d1.col(e) = d1;
  }
  return s;
}

SceneInfo info() {
  SceneInfo si;
  si.alphaDeg = 40;
  si.beta = 0.2;
  si.gamma = 0.1;
  return si;
}

void BM_BuildScene(benchmark::State& st) {
  const Snapshot s = wavingRoot(0);
  const View v = rtest::viewOf(1920, 1080);
  const Framing f = frameFor({s}, info(), v);
  for (auto _ : st) benchmark::DoNotOptimize(buildRenderScene(s, info(), v, f));
}
BENCHMARK(BM_BuildScene)->Unit(benchmark::kMillisecond);

// draw + MSAA resolve + glReadPixels + overlays, one thread feeding llvmpipe; third argument 0:
// transparent background (no plate), to show what the plate costs
void BM_DrawReadback(benchmark::State& st) {
  const int w = static_cast<int>(st.range(0)), h = static_cast<int>(st.range(1));
  const Snapshot s = wavingRoot(0);
  View v = rtest::viewOf(w, h);
  v.transparent = st.range(2) == 0;
  const RenderScene rs = buildRenderScene(s, info(), v, frameFor({s}, info(), v));
  GlRenderer r(w, h);
  Image img;
  for (auto _ : st) r.render(rs, img);
  st.counters["samples"] = r.samples();
  st.SetItemsProcessed(st.iterations());
}
BENCHMARK(BM_DrawReadback)->Args({1280, 720, 1})->Args({1920, 1080, 1})->Args({1920, 1080, 0})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Png(benchmark::State& st) {
  const int w = static_cast<int>(st.range(0)), h = static_cast<int>(st.range(1));
  const Snapshot s = wavingRoot(0);
  const View v = rtest::viewOf(w, h);
  GlRenderer r(w, h);
  const Image img = r.render(buildRenderScene(s, info(), v, frameFor({s}, info(), v)));
  const std::string path = (rtest::scratch("bench") / "bench.png").string();
  for (auto _ : st) writePng(path, img);
  st.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
  std::filesystem::remove(path);
}
BENCHMARK(BM_Png)->Args({1920, 1080})->Unit(benchmark::kMillisecond)->UseRealTime();

// a frame's PNG in memory at the renderer's settings (zlib level 1, "sub" filter): arg 0 libpng
// (encodeSignedPng, what writePng writes), arg 1 stb's writer at the same settings, the encoder libpng replaced
void BM_PngEncoder(benchmark::State& st) {
  const int w = 1920, h = 1080;
  const Snapshot s = wavingRoot(0);
  const View v = rtest::viewOf(w, h);
  GlRenderer r(w, h);
  const Image img = r.render(buildRenderScene(s, info(), v, frameFor({s}, info(), v)));
  std::size_t bytes = 0;
  if (st.range(0) == 0) {
    PngOptions o;
    o.compressionLevel = 1;
    o.filters = PNG_FILTER_SUB;
    std::string why;
    for (auto _ : st) bytes = encodeSignedPng({img.rgba.data(), w, h, 4, 4 * static_cast<std::size_t>(w)}, o, &why).size();
  } else {
    stbi_write_png_compression_level = 1;
    stbi_write_force_png_filter = 1;
    std::string out;
    auto append = [](void* ctx, void* data, int size) {
      static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
    };
    for (auto _ : st) {
      out.clear();
      stbi_write_png_to_func(append, &out, w, h, 4, img.rgba.data(), 4 * w);
      bytes = out.size();
    }
  }
  st.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_PngEncoder)->ArgName("stb")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// swscale + x264 (crf 18, preset veryfast) per frame, on frames that change like a movie's
void BM_Encode(benchmark::State& st) {
  const int w = static_cast<int>(st.range(0)), h = static_cast<int>(st.range(1));
  const View v = rtest::viewOf(w, h);
  std::vector<Snapshot> snaps;
  for (int k = 0; k < 8; ++k) snaps.push_back(wavingRoot(k));
  const Framing f = frameFor(snaps, info(), v);
  GlRenderer r(w, h);
  std::vector<Image> frames;
  for (const Snapshot& s : snaps) frames.push_back(r.render(buildRenderScene(s, info(), v, f)));
  const std::string path = (rtest::scratch("bench") / "bench.mp4").string();
  VideoWriter out(path, w, h);
  std::size_t i = 0;
  for (auto _ : st) out.add(frames[i++ % frames.size()]);
  out.finish();
  std::filesystem::remove(path);
  st.SetItemsProcessed(st.iterations());
}
BENCHMARK(BM_Encode)->Args({1280, 720})->Args({1920, 1080})->Unit(benchmark::kMillisecond)->UseRealTime();

// end to end: snapshots -> MP4 (build, draw, readback, overlays | swscale, x264) per iteration;
// items/s and the fps counter are the movie's frame rate. Arguments: width, height, look (0 plain fit
// view, 1 follow camera 2 mm + curvature colours + a panel of all five time series, 2 plain + shadows,
// 3 the look of 1 + shadows), frames

PlotSeries series(const char* name, double phase) {
  PlotSeries s;
  s.name = name;
  s.unit = "J";
  s.siPrefix = true;
  for (int i = 0; i <= 600; ++i) {
    s.timeH.push_back(0.05 * i);
    s.value.push_back(1e-9 * (1.0 + std::sin(0.1 * i + phase)));
  }
  return s;
}

// one composed frame without encoding (scene build, draw, readback, overlays, inset, panel), so the
// looks' drawing costs can be told apart from the encoder's; arguments as BM_Movie without frames,
// plus look 4: the follow camera alone
void BM_Compose(benchmark::State& st) {
  const int w = static_cast<int>(st.range(0)), h = static_cast<int>(st.range(1));
  const int look = static_cast<int>(st.range(2));
  std::vector<Snapshot> snaps;
  for (int k = 0; k < 8; ++k) snaps.push_back(wavingRoot(k));
  MovieJob job;
  job.view = rtest::viewOf(w, h);
  if (look == 1 || look == 3 || look == 4) {
    job.camera = CameraMode::Follow;
    job.fieldMm = 2.0;
  }
  if (look == 1 || look == 3) {
    job.view.colourBy = ColourField::Curvature;
    job.view.colourRange = fieldRange(snaps, info(), job.view.colourBy);
  }
  if (look == 1 || look == 3)
    for (const char* n : {"theta", "Eb", "Et", "Wr", "Tw"}) job.plots.push_back(series(n, n[0]));
  job.view.shadows = look == 2 || look == 3;
  FrameComposer comp(info(), job, planFrames(snaps, info(), job));
  Image img;
  int k = 0;
  for (auto _ : st) {
    comp.compose(snaps[static_cast<std::size_t>(k % 8)], k % 8, img);
    ++k;
  }
  st.SetItemsProcessed(st.iterations());
}
BENCHMARK(BM_Compose)
    ->ArgNames({"w", "h", "look"})
    ->Args({1280, 720, 0})
    ->Args({1280, 720, 1})
    ->Args({1280, 720, 2})
    ->Args({1280, 720, 4})
    ->Args({1920, 1080, 0})
    ->Args({1920, 1080, 1})
    ->Args({1920, 1080, 2})
    ->Args({1920, 1080, 4})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_Movie(benchmark::State& st) {
  const int w = static_cast<int>(st.range(0)), h = static_cast<int>(st.range(1));
  const int look = static_cast<int>(st.range(2)), frames = static_cast<int>(st.range(3));
  std::vector<Snapshot> snaps;
  for (int k = 0; k < frames; ++k) snaps.push_back(wavingRoot(k));
  MovieJob job;
  job.view = rtest::viewOf(w, h);
  job.mp4 = (rtest::scratch("bench") / "movie.mp4").string();
  if (look == 1 || look == 3) {
    job.camera = CameraMode::Follow;
    job.fieldMm = 2.0;
    job.view.colourBy = ColourField::Curvature;
    for (const char* n : {"theta", "Eb", "Et", "Wr", "Tw"}) job.plots.push_back(series(n, n[0]));
  }
  job.view.shadows = look >= 2;
  for (auto _ : st) renderMovie(snaps, info(), job);
  std::filesystem::remove(job.mp4);
  st.SetItemsProcessed(st.iterations() * frames);
  st.counters["fps"] = benchmark::Counter(static_cast<double>(st.iterations() * frames), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Movie)
    ->ArgNames({"w", "h", "look", "frames"})
    ->Args({1280, 720, 0, 60})
    ->Args({1920, 1080, 0, 60})
    ->Args({1280, 720, 1, 60})
    ->Args({1920, 1080, 1, 60})
    ->Args({1280, 720, 2, 60})
    ->Args({1920, 1080, 2, 60})
    ->Args({1920, 1080, 3, 60})
    ->Args({3840, 2160, 0, 20})
    ->Args({3840, 2160, 3, 20})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
