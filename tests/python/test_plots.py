"""octoreach.plots: PNG files of capability-map slices and histograms, and their input checks."""
from __future__ import annotations

import numpy as np
import pytest

import octoreach
from octoreach import plots, robots

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def cmap():
    chain = robots.test_arm().chain("base_link", "tool0")
    return octoreach.CapabilityMap.build(chain, resolution=0.25, directions=16, seed=1, progress=False)


def assert_png(path, min_size=5000):
    data = open(path, "rb").read()
    assert data.startswith(PNG_MAGIC)
    assert len(data) > min_size


def test_capability_slices(cmap, tmp_path):
    heights = plots.default_heights(cmap, 4)
    assert 1 <= len(heights) <= 4
    out = plots.capability_slices(cmap, heights, tmp_path / "slices.png")
    assert out == str(tmp_path / "slices.png")
    assert_png(out)


def test_slices_generic_with_polygon(cmap, tmp_path):
    centres, values = cmap.voxels()
    table = np.array([[0.2, -0.3, 0.5], [0.6, -0.3, 0.5], [0.6, 0.3, 0.5], [0.2, 0.3, 0.5]])
    out = plots.slices((centres, values), [0.375, 0.625], str(tmp_path / "generic.png"), polygon=table,
                       title="generic", value_label="R")
    assert_png(out)
    # a callable sampled on a grid, and a 2-D polygon
    out = plots.slices(cmap.reachability, [0.5], tmp_path / "fn.png", resolution=0.1,
                       extent=((-1, 1), (-1, 1)), polygon=table[:, :2])
    assert_png(out)
    # a height with no voxels still draws
    assert_png(plots.slices((centres, values), [25.0], tmp_path / "empty.png"), min_size=1000)


def test_reachability_histogram(cmap, tmp_path):
    assert_png(plots.reachability_histogram(cmap, tmp_path / "hist.png"))
    assert_png(plots.reachability_histogram(np.linspace(0.01, 1, 50), tmp_path / "hist2.png", bins=5))
    with pytest.raises(ValueError):
        plots.reachability_histogram(cmap, tmp_path / "bad.png", bins=0)


@pytest.mark.parametrize("heights", [[], [float("nan")], [0.1, float("inf")], [[0.1, 0.2]], "high", list(range(100))])
def test_bad_heights(cmap, tmp_path, heights):
    with pytest.raises(ValueError):
        plots.capability_slices(cmap, heights, tmp_path / "bad.png")
    assert not (tmp_path / "bad.png").exists()


def test_bad_data_and_polygon(cmap, tmp_path):
    centres, values = cmap.voxels()
    with pytest.raises(ValueError):
        plots.slices((centres[:, :2], values), [0.5], tmp_path / "x.png")
    with pytest.raises(ValueError):
        plots.slices((centres, values[:-1]), [0.5], tmp_path / "x.png")
    with pytest.raises(ValueError):
        plots.slices(cmap, [0.5], tmp_path / "x.png", polygon=np.zeros((3, 4)))
    with pytest.raises(ValueError):
        plots.slices(cmap.reachability, [0.5], tmp_path / "x.png")  # a callable needs a grid
    with pytest.raises(ValueError):
        plots.slices(cmap, [0.5], tmp_path / "x.png", vmin=1, vmax=0)
    assert not (tmp_path / "x.png").exists()


def test_surface_map_plots(tmp_path):
    import octoreach

    robot = octoreach.robots.test_arm()
    cap = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.15, directions=24,
                                        progress=False)
    table = octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55)
    sm = octoreach.SurfaceMap.build(robot, cap, table, resolution=0.15, z_range=(0, 0), progress=False)
    a = plots.surface_slices(sm, tmp_path / "surface.png")
    b = plots.sample_comparison(sm, tmp_path / "samples.png", count=60)
    for p in (a, b):
        data = open(p, "rb").read()
        assert data.startswith(b"\x89PNG") and len(data) > 10_000
    with pytest.raises(ValueError):
        plots.sample_comparison(sm, tmp_path / "x.png", count=0)
    empty = octoreach.SurfaceMap.build(robot, cap, octoreach.Surface.rectangle(0.3, 0.3, 5.0), resolution=0.15,
                                       z_range=(0, 0), progress=False)
    with pytest.raises(ValueError, match="empty"):
        plots.surface_slices(empty, tmp_path / "empty.png")
