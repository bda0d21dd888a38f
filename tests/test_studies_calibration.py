"""Calibration (sources: CSV parsing against hand-written files)."""

import numpy as np
import pytest

from betvdesign.errors import UsageError
from betvdesign.studies.calibration import read_measurements


def test_reads_units_from_the_header(tmp_path):
    f = tmp_path / "s.csv"
    f.write_text("# measured 2026-11\nvoltage [V],speed [um/s],sigma [um/s]\n6,10,1\n8,20.5,2\n")
    m = read_measurements(f, "speed")
    assert np.allclose(m.x, [6, 8]) and np.allclose(m.y, [10e-6, 20.5e-6])
    assert np.allclose(m.sigma, [1e-6, 2e-6])
    f.write_text("time [ms],displacement [nm]\n0.5,100\n1.0,250\n")
    m = read_measurements(f, "displacement")
    assert np.allclose(m.x, [5e-4, 1e-3]) and np.allclose(m.y, [1e-7, 2.5e-7])
    assert m.sigma is None


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("voltage,speed\n1,2\n", ":1: column 1: header 'voltage' must read 'name [unit]'"),
        ("voltage [V],speed [um/s]\n", "needs a header and at least one data row"),
        ("voltage [V],speed [wibble]\n1,2\n", "unknown unit"),
        ("voltage [V],speed [um]\n1,2\n", "speed: unit micrometer is not a um/s unit"),
        ("voltage [V],velocity [um/s]\n1,2\n", "needs columns voltage [V], speed [um/s]"),
        ("voltage [V],speed [um/s]\n1,2\n3\n", ":3: expected 2 fields, got 1"),
        ("voltage [V],speed [um/s]\n1,fast\n", ":2: speed: 'fast' is not a number"),
        ("voltage [V],speed [um/s],sigma [um/s]\n1,2,0\n", "sigma must be > 0"),
    ],
)
def test_bad_csv_names_file_line_and_column(tmp_path, text, fragment):
    f = tmp_path / "bad.csv"
    f.write_text(text)
    with pytest.raises(UsageError) as exc:
        read_measurements(f, "speed")
    assert str(exc.value).startswith(str(f))
    assert fragment in str(exc.value)
