#!/usr/bin/python3
"""Lists the source files under src/ without a test file of their own, and fails under 80 %.

A source file src/<dir>/<stem>.cpp is mirrored by tests/test_<stem>.cpp or tests/<sub>/test_<stem>.cpp
(tests/render/ for the renderer), a file holding at least one doctest TEST_CASE (tests/test_main.cpp,
doctest's main, mirrors nothing). Where one test file checks several sources through the same interface
(a command run through the binary, the renderer's pixels), EQUIVALENT below names it with the reason.
Every test_*.cpp must mirror a source file (by its name or in EQUIVALENT) or say in NOT_A_MIRROR what
it tests: a test file tests what its name says.
Usage: check_test_mirror.py [REPOSITORY] [--min-ratio 0.8]
"""
import pathlib
import re
import sys

# source -> (test file, why that file is its test)
EQUIVALENT = {
    "src/cli/main.cpp": ("tests/test_cli.cpp", "the command line, run as the binary"),
    "src/cli/commands.cpp": ("tests/test_cli.cpp", "each command, run as the binary"),
    "src/analysis/fit_trace.cpp": ("tests/test_compare_fit.cpp", "`rootsim fit` run as the binary"),
    "src/analysis/fit_output.cpp": ("tests/test_compare_fit.cpp", "the files `rootsim fit` writes"),
    "src/render/gl_renderer.cpp": ("tests/render/test_renderer.cpp", "pixels where the physics puts them"),
    "src/render/render_scene.cpp": ("tests/render/test_renderer.cpp", "the scene the renderer draws"),
    "src/render/compose.cpp": ("tests/render/test_legend.cpp", "the legend, arrow and scales composed"),
    "src/render/montage.cpp": ("tests/render/test_montage_labels.cpp", "labels placed under each root"),
    "src/app/montage_runs.cpp": ("tests/render/test_montage_labels.cpp", "the montage's labels and caption"),
    "src/render/png.cpp": ("tests/render/test_output.cpp", "PNG files read back independently"),
    "src/render/video_writer.cpp": ("tests/render/test_output.cpp", "MP4 files read back with libavformat"),
    "src/app/render_run.cpp": ("tests/render/test_stills.cpp", "`rootsim render` stills and windows"),
    "src/io/run_seams.cpp": ("tests/test_run_scene.cpp", "the production binary has no kill seam"),
    "src/figure/report_html.cpp": ("tests/figure/report_html_check.py", "report.html in headless chromium"),
}

# test files that mirror no single source, and what they test
NOT_A_MIRROR = {
    "tests/test_compare_fit.cpp": "the compare and fit commands (EQUIVALENT)",
    "tests/test_cli.cpp": "the command line (EQUIVALENT)",
    "tests/render/test_renderer.cpp": "the renderer's pixels (EQUIVALENT)",
    "tests/render/test_legend.cpp": "the renderer's overlays (EQUIVALENT)",
    "tests/render/test_montage_labels.cpp": "the montage (EQUIVALENT)",
    "tests/render/test_output.cpp": "PNG and MP4 files (EQUIVALENT)",
    "tests/render/test_stills.cpp": "`rootsim render`'s stills (EQUIVALENT)",
    "tests/test_outputs.cpp": "a run directory's files together (outputs.hpp): summary.json against the time series",
    "tests/test_number_text.cpp": "include/rootsim/number_text.hpp, header only (numbers as text for every library)",
    "tests/test_png_encode.cpp": "include/rootsim/png_encode.hpp, header only (the PNG encoder of the renderer and the figures)",
    "tests/test_high_water.cpp": "include/rootsim/high_water.hpp, header only (buffers that grow to their high-water mark and stay)",
    "tests/test_group_covariance.cpp": "the group mean's covariance of src/analysis/fit_groups.cpp (internal fit_parts.hpp), without running the binary",
    "tests/render/test_write_render.cpp": "the write rule (src/io/write_rule.cpp) where pictures are drawn",
}


def has_case(path: pathlib.Path) -> bool:
    if path.suffix == ".py":
        return path.is_file()
    return path.is_file() and re.search(r"^\s*TEST_CASE\(", path.read_text(errors="replace"), re.M) is not None


def main() -> int:
    args = sys.argv[1:]
    min_ratio = 0.8
    if "--min-ratio" in args:
        i = args.index("--min-ratio")
        min_ratio = float(args[i + 1])
        del args[i:i + 2]
    root = pathlib.Path(args[0] if args else ".").resolve()
    tests = root / "tests"
    sources = sorted(p.relative_to(root).as_posix() for p in (root / "src").rglob("*.cpp"))
    test_files = sorted(p for p in tests.rglob("test_*.cpp") if has_case(p))
    by_stem = {}
    for t in test_files:
        by_stem.setdefault(t.stem[len("test_"):], []).append(t.relative_to(root).as_posix())

    problems, missing, mirrored_tests = [], [], set()
    for src in sources:
        stem = pathlib.PurePosixPath(src).stem
        if src in EQUIVALENT:
            test, _ = EQUIVALENT[src]
            if not has_case(root / test):
                problems.append(f"{src}: its equivalent test {test} holds no test case")
            mirrored_tests.add(test)
        elif stem in by_stem:
            mirrored_tests.update(by_stem[stem])
        else:
            missing.append(src)
    for t in test_files:
        rel = t.relative_to(root).as_posix()
        if rel not in mirrored_tests and rel not in NOT_A_MIRROR:
            problems.append(f"{rel}: mirrors no source file under src/ and is not listed in NOT_A_MIRROR")
    for t in NOT_A_MIRROR:
        if not (root / t).is_file():
            problems.append(f"{t}: listed in NOT_A_MIRROR but absent")

    ratio = (len(sources) - len(missing)) / len(sources) if sources else 1.0
    for src in missing:
        print(f"no mirror test: {src}")
    for p in problems:
        print(f"error: {p}")
    print(f"{len(sources) - len(missing)} of {len(sources)} source files have their test file "
          f"({100 * ratio:.1f} %, at least {100 * min_ratio:.0f} % required)")
    return 1 if problems or ratio < min_ratio else 0


if __name__ == "__main__":
    sys.exit(main())
