"""Readers: read_qps returns the problem in QpSolver.setup's keywords (P upper triangle,
every constraint row in G), parse_qps reads text, Siconos fc2d files, and malformed input
raises lcprelax.InputError naming the file and line."""
import numpy as np
import pytest
import scipy.sparse as sp

import lcprelax
from helpers import full_p


def test_read_qps_quadobj(data_dir):
    model = lcprelax.read_qps(str(data_dir / "qps" / "quadobj.qps"))
    p = model["problem"]
    assert model["name"] == "QUAD" and model["variable_names"] == ["x1", "x2", "x3"]
    assert model["row_names"] == ["c1"] and model["objective_name"] == "obj"
    # The file's header: P = [4 1 -0.5; 1 3 0; -0.5 0 2], q = (1, -2, 0.5), r = -2.
    assert sp.tril(p["P"], k=-1).nnz == 0
    assert np.array_equal(full_p(p["P"]), [[4, 1, -0.5], [1, 3, 0], [-0.5, 0, 2]])
    assert np.array_equal(p["q"], [1, -2, 0.5]) and p["r"] == -2.0
    assert p["A"].shape == (0, 3) and p["G"].shape == (1, 3)
    assert np.array_equal(p["l"], [1.0]) and np.array_equal(p["u"], [1.0])
    assert np.all(np.isneginf(p["xl"])) and np.all(np.isposinf(p["xu"]))
    solver = lcprelax.QpSolver()
    solver.setup(**p)
    r = solver.solve()
    assert r.status == "solved" and r.objective == pytest.approx(-2.67032967032967, abs=1e-12)


def test_parse_qps_error_names_line():
    text = "NAME T\nROWS\n N obj\nCOLUMNS\n x obj abc\nENDATA\n"
    with pytest.raises(lcprelax.InputError, match="mem.qps:5"):
        lcprelax.parse_qps(text, "mem.qps")


def test_read_missing_file_is_input_error(tmp_path):
    with pytest.raises(lcprelax.InputError, match="nothere.qps"):
        lcprelax.read_qps(tmp_path / "nothere.qps")


def test_read_siconos_fc2d(data_dir):
    data = lcprelax.read_siconos_fc2d(data_dir / "siconos" / "handmade" / "fc2d_sparse_block.dat")
    nc = data["contacts"]
    assert nc > 0
    assert data["W"].shape == (2 * nc, 2 * nc) and data["q"].shape == (2 * nc,)
    assert data["mu"].shape == (nc,) and np.all(data["mu"] >= 0)
