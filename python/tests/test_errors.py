"""Bad input raises a clear exception, never crashes: wrong shapes (lcprelax.InputError, a
ValueError, naming the dimension), NaN (InputError), wrong types (TypeError; a dense
ndarray where a sparse matrix is required is rejected), calls out of order (UsageError)."""
import numpy as np
import pytest
import scipy.sparse as sp

import lcprelax


def test_exception_classes():
    assert issubclass(lcprelax.InputError, ValueError)
    assert issubclass(lcprelax.UsageError, RuntimeError)


def test_wrong_shape_names_the_dimension(small_qp):
    solver = lcprelax.QpSolver()
    with pytest.raises(ValueError, match="expected 5x5"):
        solver.setup(**dict(small_qp, P=sp.identity(4, format="csc")))
    with pytest.raises(lcprelax.InputError, match="xl has length 3, expected 5"):
        solver.setup(**dict(small_qp, xl=np.zeros(3)))
    with pytest.raises(lcprelax.InputError, match="l has length 1, expected 2"):
        solver.setup(**dict(small_qp, l=np.zeros(1)))
    with pytest.raises(lcprelax.InputError, match=r"G is 2x4, expected 2x5"):
        solver.setup(**dict(small_qp, G=sp.csc_matrix((2, 4))))
    with pytest.raises(lcprelax.InputError, match=r"shape \(5, 1\)"):
        solver.setup(**dict(small_qp, q=np.ones((5, 1))))
    lemke = lcprelax.LemkeSolver()
    with pytest.raises(lcprelax.InputError, match="q has length 2, expected 3"):
        lemke.setup(sp.identity(3, format="csc"), np.ones(2))
    with pytest.raises(lcprelax.InputError, match="2x3"):
        lemke.setup(sp.csc_matrix((2, 3)), np.ones(2))


def test_nan_raises_input_error(small_qp):
    q = small_qp["q"].copy()
    q[2] = np.nan
    with pytest.raises(lcprelax.InputError, match=r"q\(2\)"):
        lcprelax.QpSolver().setup(**dict(small_qp, q=q))
    P = small_qp["P"].copy()
    P.data[0] = np.inf
    with pytest.raises(lcprelax.InputError, match="P has a NaN or infinite entry"):
        lcprelax.QpSolver().setup(**dict(small_qp, P=P))
    with pytest.raises(lcprelax.InputError, match="NaN"):
        lcprelax.LemkeSolver().setup(sp.identity(2, format="csc"), np.array([1.0, np.nan]))


def test_dense_matrix_is_rejected_with_type_error(small_qp):
    with pytest.raises(TypeError, match=r"P must be a scipy.sparse matrix.*csc_matrix"):
        lcprelax.QpSolver().setup(**dict(small_qp, P=small_qp["P"].toarray()))
    with pytest.raises(TypeError, match="M must be a scipy.sparse"):
        lcprelax.LemkeSolver().setup(np.eye(2), np.ones(2))


def test_wrong_types(small_qp):
    with pytest.raises(TypeError, match="q must be"):
        lcprelax.QpSolver().setup(**dict(small_qp, q="12345"))
    with pytest.raises(TypeError, match="complex"):
        lcprelax.QpSolver().setup(**dict(small_qp, q=np.ones(5, dtype=complex)))
    with pytest.raises(TypeError, match="complex"):
        lcprelax.QpSolver().setup(**dict(small_qp, G=small_qp["G"].astype(complex)))
    with pytest.raises(TypeError, match="sparse"):
        lcprelax.QpSolver().setup(**dict(small_qp, A=[[1, 1, 1, 1, 1]]))
    with pytest.raises(TypeError):
        lcprelax.read_qps(42)


def test_any_sparse_format_and_int_vectors(small_qp):
    reference = lcprelax.QpSolver()
    reference.setup(**small_qp)
    x = reference.solve().x
    for fmt in ("coo", "csr", "lil", "dok"):
        solver = lcprelax.QpSolver()
        solver.setup(**dict(small_qp, P=small_qp["P"].asformat(fmt), G=small_qp["G"].asformat(fmt)))
        assert np.array_equal(solver.solve().x, x)
    solver = lcprelax.QpSolver()
    solver.setup(**dict(small_qp, b=[1]))  # a list of ints is converted to float64
    assert np.array_equal(solver.solve().x, x)


def test_lower_triangle_of_p_is_rejected(small_qp):
    P = small_qp["P"].toarray()
    with pytest.raises(lcprelax.InputError, match="upper triangle"):
        lcprelax.QpSolver().setup(**dict(small_qp, P=sp.csc_matrix(P + P.T - np.diag(np.diag(P)))))


def test_calls_out_of_order():
    with pytest.raises(lcprelax.UsageError, match="before setup"):
        lcprelax.QpSolver().solve()
    with pytest.raises(lcprelax.UsageError, match="before setup"):
        lcprelax.QpSolver().update(q=np.ones(2))
    with pytest.raises(lcprelax.UsageError, match="before setup"):
        lcprelax.LemkeSolver().solve()
    with pytest.raises(lcprelax.UsageError):
        lcprelax.LemkeSolver().backward(np.ones(2))


def test_a_and_b_go_together(small_qp):
    args = dict(small_qp)
    del args["b"]
    with pytest.raises(lcprelax.InputError, match="A and b"):
        lcprelax.QpSolver().setup(**args)
