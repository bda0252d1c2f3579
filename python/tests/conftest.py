"""Shared fixtures of the lcprelax Python tests: the repository's test data and a small
QP with every kind of constraint (equality row, two-sided and one-sided rows, bounds)
whose solution has active rows and bounds on both sides."""
import os
import pathlib

import numpy as np
import pytest
import scipy.sparse as sp

DATA = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data"


@pytest.fixture
def data_dir():
    return DATA


@pytest.fixture
def cli_path():
    """The `lcprelax` command line tool of the build (ctest sets LCPRELAX_CLI)."""
    path = os.environ.get("LCPRELAX_CLI")
    if not path:
        import lcprelax

        guess = pathlib.Path(lcprelax.__file__).resolve().parents[2] / "apps" / "lcprelax"
        path = str(guess) if guess.exists() else None
    if not path or not os.path.exists(path):
        pytest.skip("the lcprelax CLI is not built (set LCPRELAX_CLI)")
    return path


@pytest.fixture
def small_qp():
    """n = 5: min ½xᵀPx + qᵀx s.t. Σx = 1, -0.5 ≤ x0 - x1 ≤ 0.2, x2 + 2x3 ≥ 0.9,
    0 ≤ x ≤ 0.6 (x3 ≤ 0.3). At the solution the upper side of row 0, the lower side of
    row 1 and the upper bound of x3 are active with multipliers of size 1 (strict
    complementarity); x4 is free between its bounds, so x depends on q."""
    P_full = np.array(
        [
            [4.0, 1.0, 0.0, 0.5, 0.0],
            [1.0, 3.0, 0.5, 0.0, 0.0],
            [0.0, 0.5, 2.0, 0.0, 0.3],
            [0.5, 0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.3, 0.0, 2.0],
        ]
    )
    return dict(
        P=sp.csc_matrix(np.triu(P_full)),
        q=np.array([-4.0, 1.0, 0.5, -3.0, -1.0]),
        A=sp.csc_matrix(np.ones((1, 5))),
        b=np.array([1.0]),
        G=sp.csr_matrix(np.array([[1.0, -1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 2.0, 0.0]])),
        l=np.array([-0.5, 0.9]),
        u=np.array([0.2, np.inf]),
        xl=np.zeros(5),
        xu=np.array([0.6, 0.6, 0.6, 0.3, 0.6]),
    )
