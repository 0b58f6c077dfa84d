"""3D point runs from Python (ecm.run_point_3d) against ecm-point with hypothesis:
three_dimensional: the same history bit for bit, and the rotated-axis scene's band normal."""
import numpy as np

import ecm
from conftest import run_tool
from test_point import read_csv


def test_a_3d_point_run_gives_the_command_line_numbers_and_the_normal_follows_the_axis(source, tmp_path):
    path = source / "data/point/3d-rotated-axis.yaml"
    status, err = run_tool("ecm-point", path, "--out", tmp_path / "cli")
    assert status == 0, err
    run = ecm.run_point_3d(path, out=tmp_path / "py")
    cli = read_csv(tmp_path / "cli/history.csv")
    for column, values in cli.items():
        assert np.array_equal(run.history[column], values), column
    # the scene pulls along d = (1, 2, 2) / 3: the band's normal at onset (docs/model.md)
    normal = [run.history[c][-1] for c in ("normal_x", "normal_y", "normal_z")]
    assert np.allclose(normal, np.array([1.0, 2.0, 2.0]) / 3.0, atol=1e-12)
    assert run.summary["completed"]
