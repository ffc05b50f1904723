"""rootsim.analyze is `rootsim analyze`: the same rows, the same option checks, nothing written."""
import math

import numpy as np
import pytest

import rootsim
from conftest import SOURCE, cli

# rootsim.analyze is in every build (the analysis library needs no renderer); export is the renderer's
needs_export = pytest.mark.skipif(not rootsim._rootsim.have_render, reason="rootsim.export: built without the renderer")

SMARTROOT = SOURCE / "tests/data/rsml/smartroot_pixels.rsml"


def test_rows_are_the_command_lines_csv(tmp_path):
    cli("analyze", SMARTROOT, "--out", tmp_path / "an", "--quiet")
    header, *lines = (tmp_path / "an" / "analysis.csv").read_text().splitlines()
    rows = rootsim.analyze(SMARTROOT)
    assert [list(r) for r in rows] == [header.split(",")] * len(lines)
    for row, line in zip(rows, lines):
        for (key, value), cell in zip(row.items(), line.split(",")):
            if isinstance(value, str):
                assert value == cell, key
            elif cell == "":
                assert math.isnan(value), key
            else:
                assert value == float(cell), key


@needs_export
def test_a_run_exported_gives_its_own_observables(tmp_path):
    run = rootsim.run(SOURCE / "scenes/fig2b_waving.toml", set={"growth.steps": 600}, out=tmp_path / "wave")
    rootsim.export(run.dir, rsml=tmp_path / "wave.rsml")
    (row,) = rootsim.analyze([tmp_path / "wave.rsml"])
    assert row["pattern"] == run.summary["pattern"]
    assert row["lateral_peaks"] == run.summary["lateral_peaks"]
    assert row["skew_deg"] == pytest.approx(run.summary["skew_deg"], rel=1e-9, abs=1e-9)
    # a trace's waves are taken about its own axis (its direction over whole waves), a run's summary across
    # downhill: they differ by the rotation through the skew alone, 1 - cos(skew) in each distance
    assert abs(row["skew_deg"]) < 2
    turn = 2 * (1 - math.cos(math.radians(row["skew_deg"]))) + 1e-9
    assert row["wavelength_mm"] == pytest.approx(run.summary["wavelength_mm"], rel=turn)
    assert row["amplitude_mm"] == pytest.approx(run.summary["amplitude_mm"], rel=turn)


def test_bad_options_raise_the_command_lines_message():
    with pytest.raises(rootsim.SceneError, match="--downhill sideways"):
        rootsim.analyze(SMARTROOT, downhill="sideways")
    with pytest.raises(rootsim.SceneError, match="--times 1.0,2.0: 2 time"):
        rootsim.analyze(SMARTROOT, times=[1, 2])
    with pytest.raises(rootsim.SceneError, match="not pixels"):
        rootsim.analyze(SMARTROOT, px_per_mm=20)


def test_rows_carry_the_noise_and_the_fields_traits(tmp_path):
    # a straight root 2 mm long at 20 px/mm drifting 0.5 mm sideways, in whole pixels with a 1 px zigzag
    pts = "".join(f'<point x="{100 + round(0.25 * i) + (i % 2)}" y="{50 + i}"/>' for i in range(41))
    f = tmp_path / "zig.rsml"
    f.write_text('<?xml version="1.0"?><rsml><metadata><version>1</version><unit>pixel</unit>'
                 '<resolution>1</resolution></metadata><scene><plant id="a"><root id="r"><geometry>'
                 f"<polyline>{pts}</polyline></geometry></root></plant></scene></rsml>")
    (row,) = rootsim.analyze(f, px_per_mm=20)
    for key in ("noise_mm", "smoothing_mm", "peak_threshold_mm", "theta_tip_deg", "straightness", "hgi", "vgi"):
        assert isinstance(row[key], float), key
    assert row["noise_mm"] > 0 and row["smoothing_mm"] > 0
    # straight, heading atan(0.25) = 14 degrees off downhill: skewing, without waves
    assert row["pattern"] == "skewing" and math.isnan(row["wavelength_mm"]) and math.isnan(row["amplitude_mm"])
    assert row["waves_note"].startswith("below the noise") or row["waves_note"].startswith("no lateral excursion")
    assert row["straightness"] > 0.99
    # the tip's displacement over the length, across and along downhill
    assert row["hgi"] == pytest.approx(0.5 / math.hypot(0.5, 2), rel=0.05)
    assert row["vgi"] == pytest.approx(2 / math.hypot(0.5, 2), rel=0.02)
    got = rootsim.analyze(f, px_per_mm=20)
    assert got.columns["noise_mm"].shape == (1,) and got.columns["straightness"][0] == row["straightness"]


RST = SOURCE / "tests/data/rsml/rst_2dt.rsml"


def test_columns_plants_and_growth_are_numpy_arrays_of_the_csv_files(tmp_path):
    cli("analyze", RST, "--out", tmp_path / "an", "--quiet")
    got = rootsim.analyze(RST)
    assert isinstance(got, rootsim.Analysis) and len(got) == 4
    for table, csv in ((got.columns, "analysis.csv"), (got.plants, "plants.csv"), (got.growth, "growth.csv")):
        header, *lines = (tmp_path / "an" / csv).read_text().splitlines()
        assert list(table) == header.split(",")
        cells = [line.split(",") for line in lines]
        for j, (name, values) in enumerate(table.items()):
            assert isinstance(values, np.ndarray) and len(values) == len(lines), name
            for value, row in zip(values, cells):
                if values.dtype.kind == "U":
                    assert value == row[j], name
                elif row[j] == "":
                    assert math.isnan(value), name
                else:
                    assert value == float(row[j]), name
    # the primary's L(t) at 0, 6, 12, 18 h: 1, 2, 4, 6 mm; its rate over the last interval
    primary = got.growth["root"] == "1.1"
    assert got.growth["time_h"][primary].tolist() == [0, 6, 12, 18]
    assert got.growth["length_mm"][primary] == pytest.approx([1, 2, 4, 6])
    assert got.columns["growth_rate_mm_per_h"][0] == pytest.approx(1 / 3)
    assert got.plants["lateral_density_per_mm"][0] == pytest.approx(2 / 3)
    assert got.warnings == []


def test_an_implausible_scale_is_a_warning(tmp_path):
    text = (SOURCE / "tests/data/rsml/smartroot_inch.rsml").read_text()
    (tmp_path / "dpi1.rsml").write_text(text.replace("<resolution>254.0</resolution>", "<resolution>1</resolution>"))
    got = rootsim.analyze(tmp_path / "dpi1.rsml")
    assert len(got.warnings) == 2
    assert "primary root #0/r1 is 2540 mm long, implausible for a seedling" in got.warnings[0]
    assert "<unit>inch</unit> and <resolution>1</resolution>" in got.warnings[0]
    assert got.plants["primary_length_mm"].tolist() == pytest.approx([2540, 1270])
