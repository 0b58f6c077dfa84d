"""scripts/validation/check_doc_rows.py, which holds docs/validation.md to a validation run's
generated rows: a figure within half a unit of the docs' last digit plus 0.2 % passes, one past it
fails, as do a missing row, a row the docs hold twice and too few rows; commentary after a figure
and the wall-time column are not compared.
"""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "validation"))
import check_doc_rows  # noqa: E402

DOC = """# Validation
| run | peak P (kN) | / test | wall (s) |
|---|---|---|---|
| coarse (2.5 mm) | explicit, one band | 18.38 | 1.535 | 11 |
| coarse, implicit | 8.59 (a first peak of 6.7 at 0.15) | 17 % | 46* |
"""


def check(tmp_path, rows, *extra):
    (tmp_path / "doc.md").write_text(DOC)
    (tmp_path / "rows.md").write_text(rows)
    return check_doc_rows.main([str(tmp_path / "doc.md"), str(tmp_path / "rows.md"), *extra])


def test_figures_within_the_tolerance_pass(tmp_path):
    # 18.38: tolerance 0.005 + 0.2 % = 0.0418; 8.59 (commentary after it): 0.005 + 0.0172.
    assert check(tmp_path, "| coarse (2.5 mm) | explicit, one band | 18.42 | 1.537 | 15 |\n"
                           "| coarse, implicit | 8.61 | 17 % | 40 (failed) |\n", "--at-least", "2") == 0


def test_a_moved_figure_fails(tmp_path, capsys):
    assert check(tmp_path, "| coarse (2.5 mm) | explicit, one band | 18.43 | 1.535 | 15 |\n") == 1
    assert "documented 18.38, now 18.43" in capsys.readouterr().out


def test_a_row_the_docs_do_not_hold_fails(tmp_path, capsys):
    assert check(tmp_path, "| medium | explicit, one band | 18.81 | 1.570 | 200 |\n") == 1
    assert "0 rows in the docs" in capsys.readouterr().out


def test_too_few_rows_fail(tmp_path):
    assert check(tmp_path, "| coarse, implicit | 8.59 | 17 % | 46 |\n", "--at-least", "2") == 1


def test_a_figure_the_docs_leave_blank_fails(tmp_path):
    (tmp_path / "doc2.md").write_text("| coarse, implicit | | 17 % | 46 |\n")
    (tmp_path / "rows.md").write_text("| coarse, implicit | 8.59 | 17 % | 46 |\n")
    assert check_doc_rows.main([str(tmp_path / "doc2.md"), str(tmp_path / "rows.md")]) == 1
