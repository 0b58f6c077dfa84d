"""Calibration from Python against ecm-calibrate: the same summary bit for bit, the same
messages, and the calibration's own identities (E_p for G_F and G_F for E_p are inverses; a
curve drawn from the law is fitted back to its own n and E_p)."""
import json

import numpy as np
import pytest

import ecm
from conftest import run_tool

PAPER = dict(youngs_modulus=32000, tensile_strength=3.0, fracture_energy=0.11, band_width=0.05)


def test_calibrate_gives_the_command_line_summary_bit_for_bit(tmp_path):
    status, err = run_tool("ecm-calibrate", "--E", 32000, "--ft", 3.0, "--GF", 0.11, "--h", 0.05, "--n", 0.128,
                           "--out", tmp_path / "cli")
    assert status == 0, err
    summary = ecm.calibrate(softening_exponent=0.128, out=tmp_path / "py", **PAPER)
    with open(tmp_path / "cli/summary.json") as f:
        assert summary == json.load(f)
    assert (tmp_path / "py/softening.csv").read_bytes() == (tmp_path / "cli/softening.csv").read_bytes()


def test_softening_modulus_and_fracture_energy_are_inverse():
    ep = ecm.softening_modulus(youngs_modulus=32000, tensile_strength=3.0, softening_exponent=0.128,
                               fracture_energy=0.11, band_width=0.05)
    # the paper's concrete: E_p = 8.184 MPa, which gives G_F = 0.11 N/mm to the paper's rounding (0.03 %)
    assert ep == pytest.approx(8.184, rel=1e-3)
    assert ecm.fracture_energy(youngs_modulus=32000, tensile_strength=3.0, softening_modulus=ep, softening_exponent=0.128,
                               band_width=0.05) == pytest.approx(0.11, rel=1e-9)


def test_the_identities_take_the_material_files_keys_and_the_old_names_warn():
    """One vocabulary: the keys of a material file and of calibrate(). The former short names
    give the same number with a DeprecationWarning naming the new key; a wrong or missing
    keyword is a TypeError in the module's words."""
    new = ecm.softening_modulus(youngs_modulus=32000, tensile_strength=3.0, softening_exponent=0.128,
                                fracture_energy=0.11, band_width=0.05)
    with pytest.warns(DeprecationWarning, match="now youngs_modulus"):
        old = ecm.softening_modulus(E=32000, ft=3.0, n=0.128, GF=0.11, h=0.05)
    assert old == new
    with pytest.raises(TypeError, match="needs band_width"):
        ecm.softening_modulus(youngs_modulus=32000, tensile_strength=3.0, softening_exponent=0.128, fracture_energy=0.11)
    with pytest.raises(TypeError, match="not colour"):
        ecm.fracture_energy(colour="red")


def test_a_curve_drawn_from_the_law_fits_back_to_its_parameters(tmp_path):
    # The band's own traction-opening curve (softening.csv of the calibration at n = 0.2) is fitted
    # with G_F held: the fit must find n = 0.2 and its E_p again.
    truth = ecm.calibrate(softening_exponent=0.2, out=tmp_path / "truth", **PAPER)
    data = np.loadtxt(tmp_path / "truth/softening.csv", delimiter=",", skiprows=1, ndmin=2)
    with open(tmp_path / "truth/softening.csv") as f:
        header = f.readline().strip().split(",")
    w, t = data[:, header.index("w")], data[:, header.index("sigma")]
    keep = np.concatenate(([True], np.diff(w) > 0)) & (w > 0)
    w, t = w[keep][::10], t[keep][::10]
    fit = ecm.fit_softening(w, t, **PAPER)
    assert fit["n"] == pytest.approx(0.2, rel=1e-3)
    assert fit["Ep"] == pytest.approx(truth["Ep"], rel=1e-3)
    # the same points through a CSV file and the command line give the same numbers
    csv = tmp_path / "points.csv"
    np.savetxt(csv, np.column_stack([w, t]), delimiter=",", header="w_mm,sigma_MPa", comments="", fmt="%.17g")
    status, err = run_tool("ecm-calibrate", "--E", 32000, "--ft", 3.0, "--GF", 0.11, "--h", 0.05, "--fit-csv", csv,
                           "--out", tmp_path / "cli")
    assert status == 0, err
    with open(tmp_path / "cli/summary.json") as f:
        cli = json.load(f)
    for key in ("n", "Ep", "GF", "fit_residual", "fit_points"):
        assert cli[key] == fit[key], key


def test_bad_input_raises_the_message_the_tool_prints(tmp_path):
    status, err = run_tool("ecm-calibrate", "--E", 32000, "--ft", 3.0, "--GF", 1e-6, "--h", 0.05, "--n", 0.128,
                           "--out", tmp_path / "cli")
    assert status == 2
    with pytest.raises(ValueError) as raised:
        ecm.calibrate(youngs_modulus=32000, tensile_strength=3.0, fracture_energy=1e-6, band_width=0.05,
                      softening_exponent=0.128)
    assert "below the elastic minimum" in str(raised.value)
    bad = tmp_path / "cal.yaml"
    bad.write_text("youngs_modulus: 32000\ntensile_strength: -3\nfracture_energy: 0.11\nband_width: 0.05\n"
                   "softening_exponent: 0.128\n")
    status, err = run_tool("ecm-calibrate", "--input", bad, "--out", tmp_path / "cli2")
    assert status == 2
    with pytest.raises(ecm.InputError) as raised:
        ecm.calibrate(bad)
    assert str(raised.value) in err and str(raised.value).startswith(f"{bad}:2:")


def test_numpy_scalars_are_numbers():
    # Issue: calibrate(..., softening_exponent=np.float64, youngs_modulus=np.int64) was not JSON serializable.
    plain = ecm.calibrate(softening_exponent=0.128, **PAPER)
    as_numpy = ecm.calibrate(softening_exponent=np.float64(0.128), youngs_modulus=np.int64(32000),
                             tensile_strength=np.float64(3.0), fracture_energy=0.11, band_width=0.05)
    assert as_numpy == plain


def test_calibrate_writes_the_material_and_the_umat_card_as_the_tool_does(tmp_path):
    """write_material and write_umat (with element_sizes) write what ecm-calibrate --write-material
    and --write-umat write: the material reads back with the solved E_p, and the card holds one
    *MATERIAL per element size with CONSTANTS=9 and E_p as the summary's, to the last bit."""
    summary = ecm.calibrate(youngs_modulus=32000.0, poisson_ratio=0.2, tensile_strength=3.0, fracture_energy=0.11,
                            band_width=0.05, softening_exponent=0.128, name="concrete",
                            write_material=str(tmp_path / "concrete.yaml"), write_umat=str(tmp_path / "concrete.inp"),
                            element_sizes=[2.5, 5.0])
    material = ecm.Material.from_file(tmp_path / "concrete.yaml")
    assert material.name == "concrete" and material.model == "enriched"
    line = next(l for l in (tmp_path / "concrete.yaml").read_text().splitlines() if l.startswith("softening_modulus:"))
    assert float(line.split(":")[1].split("#")[0]) == pytest.approx(summary["Ep"], rel=1e-12)
    card = (tmp_path / "concrete.inp").read_text().splitlines()
    assert [l for l in card if l.startswith("*MATERIAL")] == ["*MATERIAL, NAME=ABAQUS_CONCRETE_H2p5",
                                                              "*MATERIAL, NAME=ABAQUS_CONCRETE_H5"]
    first = card.index("*USER MATERIAL, CONSTANTS=9")
    constants = [float(v) for v in (card[first + 1] + "," + card[first + 2]).split(",")]
    assert len(constants) == 9 and constants[4] == summary["Ep"] and constants[7] == 2.5
    with pytest.raises(ValueError, match="element-size"):
        ecm.calibrate(youngs_modulus=32000.0, poisson_ratio=0.2, tensile_strength=3.0, fracture_energy=0.11,
                      band_width=0.05, softening_exponent=0.128, write_umat=str(tmp_path / "x.inp"))


def test_a_missing_file_is_file_not_found_and_the_module_shows_its_own_names_only(tmp_path):
    """A path that does not exist raises FileNotFoundError (an OSError, with the path), as open()
    does, wherever a function takes a file; dir(ecm) lists the module's API, not what it imports."""
    missing = tmp_path / "missing.yaml"
    for call in (lambda: ecm.Material.from_file(missing), lambda: ecm.run_point(missing),
                 lambda: ecm.calibrate(missing), lambda: ecm.load_scene(missing)):
        with pytest.raises(FileNotFoundError) as caught:
            call()
        assert caught.value.filename == str(missing)
    public = {name for name in dir(ecm) if not name.startswith("_")}
    assert not public & {"np", "os", "json", "tempfile", "dataclass", "field"}, public
    assert {name for name in ecm.__all__ if not name.startswith("_")} <= public
