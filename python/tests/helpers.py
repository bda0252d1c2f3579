"""Small NumPy helpers shared by the tests."""
import numpy as np
import scipy.sparse as sp


def full_p(P_upper):
    """The symmetric P from its stored upper triangle."""
    P = sp.csc_matrix(P_upper).toarray()
    return P + P.T - np.diag(np.diag(P))
