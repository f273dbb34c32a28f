"""`mcc sim --plot` and `--trace x.csv`, run as a user runs them (docs/SIMULATOR.md, "Plots and
traces"; docs/CLI.md, "mcc sim").

The fixture fixtures/plot_xy.prg is an Arcus pen plotter: a linearly interpolated X/Y move
(arcus-pmx-4ex-sa.txt L570-L575: "If more than 1 axis is specified, the motion will be linearly
interpolated"), an arc on X and Y (L592-L594, ARCP), output 1 switched on and off (DO1, L109-L110),
and Z and U never moved. The PMX-4EX-SA profile does not know the pulses per revolution (its
steps_per_rev is 0), so a user profile extends it with a scale.
"""

from __future__ import annotations

import csv
import io
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import SAMPLES, run_mcc

FIXTURE = Path(__file__).parent / "fixtures" / "plot_xy.prg"
CHROMIUM = next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome") if shutil.which(n)), None)


@pytest.fixture
def plotter(tmp_path: Path) -> Path:
    shutil.copy(FIXTURE, tmp_path / "plot_xy.prg")
    (tmp_path / "mm.toml").write_text('extends = "pmx-4ex-sa"\nname = "plotter-mm"\nsteps_per_rev = 1000\n'
                                      "[machine]\nmm_per_rev = 5\n")
    (tmp_path / "rev.toml").write_text('extends = "pmx-4ex-sa"\nname = "plotter-rev"\nsteps_per_rev = 1000\n')
    return tmp_path


def svg_text(svg: str) -> str:
    return " ".join(re.findall(r">([^<>]+)<", svg))


@pytest.mark.parametrize("name", ["run.jpg", "run", "run.svgz"])
def test_an_unknown_plot_suffix_is_a_usage_error_before_anything_runs(plotter: Path, name: str) -> None:
    result = run_mcc("sim", "plot_xy.prg", "--plot", name, cwd=plotter)
    assert result.returncode == 2, result
    assert "is not a plot format" in result.stderr and ".html" in result.stderr and ".pdf" in result.stderr
    assert "Traceback" not in result.stderr and not (plotter / name).exists()


def test_svg_has_a_legend_of_changes_moving_axes_in_mm_and_the_xy_path(plotter: Path) -> None:
    pytest.importorskip("matplotlib")
    result = run_mcc("sim", "plot_xy.prg", "--profile", "mm.toml", "--plot", "run.svg", cwd=plotter)
    assert result.returncode == 0, result.stderr
    text = svg_text((plotter / "run.svg").read_text(encoding="utf-8"))
    assert "plot_xy.prg" in text  # the title: the file's name relative to where mcc runs
    assert "output 1 \u2192 1 at 0.000 s (line 8)" in text and "output 1 \u2192 0 at" in text
    assert "(line 15)" in text
    assert "position (mm)" in text and "speed (mm/s)" in text and "steps" not in text
    assert "axis X" in text and "axis Y" in text and "axis Z" not in text and "axis U" not in text
    assert "never move (not shown): Z, U" in text
    assert text.index("axis X") < text.index("axis Y")
    assert "XY path of the moves that drive X and Y together" in text


def test_revolutions_and_rpm_where_the_profile_knows_steps_per_revolution(plotter: Path) -> None:
    pytest.importorskip("matplotlib")
    assert run_mcc("sim", "plot_xy.prg", "--profile", "rev.toml", "--plot", "rev.svg", cwd=plotter).returncode == 0
    text = svg_text((plotter / "rev.svg").read_text(encoding="utf-8"))
    assert "position (rev)" in text and "speed (rpm)" in text
    assert run_mcc("sim", "plot_xy.prg", "--plot", "steps.svg", cwd=plotter).returncode == 0
    text = svg_text((plotter / "steps.svg").read_text(encoding="utf-8"))
    assert "position (steps)" in text and "speed (steps/s)" in text  # the default profile does not know


def test_numbered_axes_in_natural_order(tmp_path: Path) -> None:
    """X150 axes are device addresses 1, 2, ... and its profiles know 4000 steps per revolution."""
    pytest.importorskip("matplotlib")
    sample = SAMPLES / "x150" / "01_feed_punch_cell.x150"
    result = run_mcc("sim", str(sample), "--plot", str(tmp_path / "x.svg"))
    assert result.returncode == 0, result.stderr
    text = svg_text((tmp_path / "x.svg").read_text(encoding="utf-8"))
    assert text.index("axis 1") < text.index("axis 2") and "speed (rpm)" in text


def test_axis_order_is_natural() -> None:
    from mcc.sim.plotdata import axis_order

    assert sorted(["U", "10", "Y", "2", "Z", "1", "X", "spindle"], key=axis_order) == \
        ["X", "Y", "Z", "U", "1", "2", "10", "spindle"]


@pytest.mark.parametrize("suffix, magic", [(".pdf", b"%PDF"), (".png", b"\x89PNG\r\n\x1a\n")])
def test_pdf_and_png_are_what_their_names_say(plotter: Path, suffix: str, magic: bytes) -> None:
    pytest.importorskip("matplotlib")
    assert run_mcc("sim", "plot_xy.prg", "--plot", "run" + suffix, cwd=plotter).returncode == 0
    assert (plotter / ("run" + suffix)).read_bytes().startswith(magic)


def test_html_is_one_self_contained_page(plotter: Path) -> None:
    result = run_mcc("sim", "plot_xy.prg", "--profile", "mm.toml", "--plot", "run.html", cwd=plotter)
    assert result.returncode == 0, result.stderr
    page = (plotter / "run.html").read_text(encoding="utf-8")
    assert page.startswith("<!DOCTYPE html>") and "<title>plot_xy.prg" in page
    assert not re.search(r"<(script|link|img|iframe)[^>]+(src|href)=", page)  # nothing fetched: no CDN
    assert not re.search(r"https?://(?!www\.w3\.org/2000/svg)", page)
    data = json.loads(re.search(r'<script type="application/json" id="mcc-data">(.*?)</script>', page, re.S)
                      .group(1).replace("<\\/", "</"))
    assert [a["name"] for a in data["axes"]] == ["X", "Y"] and data["still"] == ["Z", "U"]
    assert data["axes"][0]["unit"] == "mm" and data["axes"][0]["speedUnit"] == "mm/s"
    assert [c["label"] for c in data["changes"]][0] == "output 1 \u2192 1 at 0.000 s (line 8)"
    assert data["xy"]["x"] == "X" and len(data["xy"]["paths"]) >= 1


def test_html_zooms_and_hovers_in_headless_chromium(plotter: Path) -> None:
    """The page's own #selftest drives it in a real browser: a wheel zooms in time, hovering a
    change shows its label, moving over a chart reads every axis out, a double-click resets."""
    if CHROMIUM is None:
        if os.environ.get("CI"):
            pytest.fail("CI: chromium is required for the interactive plot test (.ci/run installs it)")
        pytest.skip("chromium is not installed (apt-get install chromium)")
    assert run_mcc("sim", "plot_xy.prg", "--profile", "mm.toml", "--plot", "run.html", cwd=plotter).returncode == 0
    url = (plotter / "run.html").as_uri() + "#selftest"
    args = [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
            "--no-first-run", f"--user-data-dir={plotter / 'profile'}", "--dump-dom", url]
    dom = subprocess.run(args, capture_output=True, text=True, timeout=120).stdout
    found = re.search(r'<pre id="selftest"[^>]*data-done="1"[^>]*>([^<]*)</pre>', dom)
    assert found, dom[-2000:]
    import html

    report = json.loads(html.unescape(found.group(1)))
    assert report["errors"] == []
    assert report["panels"] == 5  # X position, X speed, Y position, Y speed, the I/O lanes
    assert report["tooltip"] == report["svgTitle"] == "output 1 \u2192 1 at 0.000 s (line 8)"
    assert report["zoomedIn"] and report["reset"]
    assert re.match(r"t = [\d.]+ s +X [-\d.e]+ mm, [-\d.e]+ mm/s +Y ", report["readout"]), report["readout"]
    assert report["xy"] >= 1 and report["title"].startswith("plot_xy.prg")


def rows_of(path: Path) -> list[dict]:
    return list(csv.DictReader(io.StringIO(path.read_text(encoding="utf-8"), newline="")))


def test_trace_csv_is_a_wide_table(plotter: Path) -> None:
    result = run_mcc("sim", "plot_xy.prg", "--profile", "mm.toml", "--trace", "run.csv", cwd=plotter)
    assert result.returncode == 0, result.stderr
    rows = rows_of(plotter / "run.csv")
    header = list(rows[0])
    assert header[0] == "time (s)" and header[-1] == "events"
    for axis in "XYZU":
        assert f"{axis} position (steps)" in header and f"{axis} speed (steps/s)" in header
        assert f"{axis} position (mm)" in header and f"{axis} speed (mm/s)" in header
    assert header.index("X position (steps)") < header.index("Y position (steps)") < header.index("Z position (steps)")
    assert "output 1" in header
    times = [float(r["time (s)"]) for r in rows]
    assert times == sorted(times) and len(set(times)) == len(times)
    # the arc's angle is its end point's, measured from the negative x-axis (arcus-pmx-4ex-sa.txt
    # L598): 180 degrees about (2000, 2000) with radius 1000 ends at (3000, 2000)
    assert max(float(r["X position (steps)"]) for r in rows) == pytest.approx(3000)
    for r in rows:
        assert float(r["X position (mm)"]) == pytest.approx(float(r["X position (steps)"]) * 5 / 1000, abs=1e-5)
        assert float(r["Z position (steps)"]) == 0
    levels = [(float(r["time (s)"]), r["output 1"]) for r in rows]
    assert levels[0][1] == "1" and levels[-1][1] == "0"
    switched_off = next(t for t, level in levels if level == "0")
    assert any("output 1 = 0 (line 15)" in r["events"] for r in rows if float(r["time (s)"]) == switched_off)
    assert float(rows[-1]["X position (steps)"]) == 0 and float(rows[-1]["Y position (steps)"]) == 0


def test_format_csv_keeps_the_long_form(plotter: Path) -> None:
    result = run_mcc("sim", "plot_xy.prg", "--format", "csv", cwd=plotter)
    assert result.stdout.splitlines()[0] == "path,t,record,kind,line,axis,position,speed,detail"


def test_the_html_page_needs_no_matplotlib_and_images_say_what_is_missing(plotter: Path) -> None:
    """A matplotlib that cannot be imported (here a stand-in that raises ImportError) stops only
    the image formats, with the install hint and exit 2; the page is drawn without it."""
    fake = plotter / "fake"
    (fake / "matplotlib").mkdir(parents=True)
    (fake / "matplotlib" / "__init__.py").write_text("raise ImportError('no matplotlib here')\n")
    env = {**os.environ, "PYTHONPATH": str(fake), "NO_COLOR": "1"}
    exe = Path(sys.executable).parent / "mcc"
    page = subprocess.run([str(exe), "sim", "plot_xy.prg", "--plot", "run.html"], cwd=plotter, env=env,
                          capture_output=True, text=True, timeout=120)
    assert page.returncode == 0, page.stderr
    assert (plotter / "run.html").read_text(encoding="utf-8").startswith("<!DOCTYPE html>")
    image = subprocess.run([str(exe), "sim", "plot_xy.prg", "--plot", "run.png"], cwd=plotter, env=env,
                           capture_output=True, text=True, timeout=120)
    assert image.returncode == 2 and "pip install 'mcc[plot]'" in image.stderr
    assert "Traceback" not in image.stderr and not (plotter / "run.png").exists()


def test_a_plot_that_cannot_be_written_is_an_error_not_a_traceback(plotter: Path) -> None:
    result = run_mcc("sim", "plot_xy.prg", "--plot", "missing/dir/run.html", cwd=plotter)
    assert result.returncode != 0 and "Traceback" not in result.stderr
    assert "missing/dir/run.html" in result.stderr
