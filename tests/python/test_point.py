"""Point runs from Python against ecm-point: the same history and summary bit for bit (the CSV
is written in shortest round-trip form, so its numbers parse back to the run's doubles), the
same messages for bad input, and the snap-back study's closed forms."""
import json

import numpy as np
import pytest

import ecm
from conftest import run_tool


def read_csv(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {c: data[:, i] for i, c in enumerate(header)}


@pytest.mark.parametrize("scene", ["uniaxial-tension-H10.yaml", "tension-then-shear.yaml", "cyclic.yaml"])
def test_a_point_run_gives_the_command_line_numbers_bit_for_bit(source, tmp_path, scene):
    path = source / "data/point" / scene
    status, err = run_tool("ecm-point", path, "--out", tmp_path / "cli")
    assert status == 0, err
    run = ecm.run_point(path, out=tmp_path / "py")
    cli = read_csv(tmp_path / "cli/history.csv")
    assert list(run.history) == list(cli)
    for column, values in cli.items():
        assert np.array_equal(run.history[column], values), column
    with open(tmp_path / "cli/summary.json") as f:
        assert run.summary == json.load(f)
    # and the folder written from Python is the tool's
    assert (tmp_path / "py/history.csv").read_bytes() == (tmp_path / "cli/history.csv").read_bytes()


def test_a_scene_given_as_a_dict_runs_as_its_file(source):
    scene = {"name": "uniaxial-tension-H10", "material": {"file": str(source / "data/materials/den-concrete.yaml")},
             "effective_size": 10.0, "path": {"preset": "uniaxial_tension", "strain": 5.0e-3, "increments": 1000}}
    from_dict = ecm.run_point(scene)
    from_file = ecm.run_point(source / "data/point/uniaxial-tension-H10.yaml")
    for column in from_file.history:
        assert np.array_equal(from_dict.history[column], from_file.history[column]), column


def test_bad_input_raises_the_message_the_tool_prints(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\nmaterial: {file: den-concrete.yaml}\neffective_size: -1\n"
                   "path: {preset: uniaxial_tension, strain: 1e-3, increments: 10}\n")
    status, err = run_tool("ecm-point", bad, "--out", tmp_path / "out")
    assert status == 2
    with pytest.raises(ecm.InputError) as raised:
        ecm.run_point(bad)
    assert str(raised.value) in err
    assert str(raised.value).startswith(f"{bad}:3:")
    # a dict's error names the key path, not a line of a text the user never saw
    with pytest.raises(ecm.InputError, match=r"^<dict>: key 'effective_size'"):
        ecm.run_point({"name": "x", "material": {"file": "den-concrete.yaml"}, "effective_size": -1.0,
                       "path": {"preset": "uniaxial_tension", "strain": 1e-3, "increments": 10}})
    with pytest.raises(ecm.InputError, match=r"^<dict>: key 'path.increments': expected an integer"):
        ecm.run_point({"name": "x", "material": {"file": "den-concrete.yaml"}, "effective_size": 1.0,
                       "path": {"preset": "uniaxial_tension", "strain": 1e-3, "increments": "10"}})
    with pytest.raises(ecm.InputError, match=r"^<dict>: unknown key 'bogus' in 'material'"):
        ecm.run_point({"name": "x", "material": {"file": "den-concrete.yaml", "bogus": 1}, "effective_size": 1.0,
                       "path": {"preset": "uniaxial_tension", "strain": 1e-3, "increments": 10}})


def test_the_snapback_study_finds_the_closed_form_sizes(source):
    study = ecm.snapback_study(source / "data/point/snapback-study.yaml")
    # h (E + E_p) / E_p for the paper's concrete: 0.05 (32000 + 8.184) / 8.184 = 195.55 mm
    assert study["snapback_size_1d"] == pytest.approx(0.05 * (32000 + 8.184) / 8.184, rel=1e-12)
    # H_crit = 2 E G_F / f_t'^2 = 2 x 32000 x 0.11 / 9 = 782.2 mm
    assert study["critical_size"] == pytest.approx(2 * 32000 * 0.11 / 9, rel=1e-12)
    rows = study["rows"]
    # every H dissipates G_F under opening control, and strain control snaps back beyond the size above
    np.testing.assert_allclose(rows["energy_ratio"], 1.0, atol=0.01)
    assert np.all((rows["strain_control_snapback"] == 1) == (rows["H"] > study["snapback_size"]))


def test_numpy_scalars_in_a_scene_dict_are_numbers(source):
    # Issue: path.increments = np.int64(10) gave "Object of type int64 is not JSON serializable".
    scene = {"name": "np", "material": {"file": str(source / "data/materials/den-concrete.yaml")},
             "effective_size": np.float64(10.0),
             "path": {"preset": "uniaxial_tension", "strain": np.float32(1e-3), "increments": np.int64(10)}}
    plain = dict(scene, effective_size=10.0, path={"preset": "uniaxial_tension", "strain": 1e-3, "increments": 10})
    a, b = ecm.run_point(scene), ecm.run_point(plain)
    for column in b.history:
        assert np.array_equal(a.history[column], b.history[column]), column


def test_load_scene_reads_as_the_tools_read(source, tmp_path):
    # '1e-6' is a number to the tools (YAML 1.2) and a string to PyYAML; load_scene reads as the
    # tools do, and resolves the material file next to the scene from any working directory.
    scene = ecm.load_scene(source / "data/point/uniaxial-tension-H10.yaml")
    assert isinstance(scene["effective_size"], float) and isinstance(scene["path"]["increments"], int)
    assert scene["material"]["file"] == "den-concrete.yaml"  # not next to the scene: the data folder's, as the tools find it
    (tmp_path / "m.yaml").write_text((source / "data/materials/den-concrete.yaml").read_text())
    (tmp_path / "s.yaml").write_text("name: s\nmaterial: {file: m.yaml}\neffective_size: 10.0\n"
                                     "path: {preset: uniaxial_tension, strain: 1e-3, increments: 10}\n")
    assert ecm.load_scene(tmp_path / "s.yaml")["material"]["file"] == str(tmp_path / "m.yaml")
    from_dict = ecm.run_point(scene)
    from_file = ecm.run_point(source / "data/point/uniaxial-tension-H10.yaml")
    for column in from_file.history:
        assert np.array_equal(from_dict.history[column], from_file.history[column]), column
    text = tmp_path / "t.yaml"
    text.write_text("a: 1e-6\nb: '1e-6'\nc: 10\nd: true\ne: [1, x, .inf]\nf: ~\n")
    assert ecm.load_scene(text) == {"a": 1e-6, "b": "1e-6", "c": 10, "d": True, "e": [1, "x", float("inf")], "f": None}
    with pytest.raises(FileNotFoundError, match="nope.yaml"):
        ecm.load_scene(tmp_path / "nope.yaml")
