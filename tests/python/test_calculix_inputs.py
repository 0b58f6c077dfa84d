"""The CalculiX input writers and .dat reader of scripts/calculix/, without CalculiX itself.

- CalculiX reads at most 20 characters a field (a longer *BOUNDARY value made it stop with
  rc 201): every field element_inp.py writes fits, with as many digits as fit.
- ccx_dat.py reads a set's totals (*NODE PRINT, TOTALS=ONLY), one row with no node number, in
  the format ccx 2.x prints it.
"""
import pathlib
import sys

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "calculix"))
import ccx_dat  # noqa: E402
import element_inp  # noqa: E402


def test_every_field_fits_calculix_twenty_characters(tmp_path):
    # The material and direction that wrote 22-character *BOUNDARY values before.
    inp = tmp_path / "element.inp"
    assert element_inp.main([str(inp), "--props", "1,41000,0.23,4.1,23.56529286198567,0.17,0.04,6,1",
                             "--size", "3", "--direction", "3,1,-2", "--step", "7:e=3e-4"]) == 0
    for number, line in enumerate(inp.read_text().splitlines(), 1):
        if line.startswith("*"):
            continue
        for f in line.split(","):
            assert len(f.strip()) <= 20, f"line {number}: '{f.strip()}' is {len(f.strip())} characters"


def test_a_field_keeps_as_many_digits_as_fit():
    x = -1.2345678901234567e-05
    assert len(f"{x:.17g}") > 20
    assert len(element_inp.field(x)) <= 20
    assert float(element_inp.field(x)) == pytest.approx(x, rel=1e-13)
    assert element_inp.field(0.1) == "0.10000000000000001"  # 17 digits where they fit: round-trip
    assert float(element_inp.field(0.1)) == 0.1


def test_totals_are_read_as_one_row(tmp_path):
    dat = tmp_path / "job.dat"
    dat.write_text("""
                        S T E P       1


                                INCREMENT     1


 total force (fx,fy,fz) for set LOAD and time  0.1000000E+01

        2.125470E-05  3.000881E-05  9.999992E+02

 displacements (vx,vy,vz) for set TIP and time  0.1000000E+01

         7  1.000000E-03  0.000000E+00  0.000000E+00
""")
    blocks = ccx_dat.read_dat(dat)
    (time, rows), = blocks[("total force", "LOAD")]
    assert time == 1.0
    assert rows == {(): [2.125470e-05, 3.000881e-05, 9.999992e+02]}
    assert blocks[("displacements", "TIP")][0][1] == {(7,): [1.0e-03, 0.0, 0.0]}
