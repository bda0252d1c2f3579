# The installed Python package imports and solves: installs the build into PREFIX, then runs
# PYTHON with PYTHONPATH=PREFIX/INSTALL_DIR (the documented step for a prefix that is not the
# interpreter's own) and checks that `lcprelax` comes from there, solves a QP, and that
# `lcprelax.torch` imports when torch does. Run by the ctest `python_install`.
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${PREFIX} RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "install failed: ${rc}")
endif()
set(check [=[
import importlib.util, os, sys
import numpy as np, scipy.sparse as sp
import lcprelax
where = os.path.realpath(lcprelax.__file__)
assert where.startswith(os.path.realpath(sys.argv[1])), f"lcprelax imported from {where}"
s = lcprelax.QpSolver()
s.setup(sp.csc_matrix(np.array([[2.0]])), np.array([-2.0]), xu=np.array([0.5]))
r = s.solve()
assert r.status == "solved" and abs(r.x[0] - 0.5) < 1e-8, (r.status, r.x)
if importlib.util.find_spec("torch"):
    import lcprelax.torch
    print("lcprelax.torch:", lcprelax.torch.QpLayer.__name__)
print("installed lcprelax OK:", where)
]=])
# From the prefix, not from the build tree (python -c puts the working directory first on sys.path).
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${PREFIX}/${INSTALL_DIR} ${PYTHON} -c "${check}" ${PREFIX}
  WORKING_DIRECTORY ${PREFIX}
  RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "the installed package failed: ${rc}")
endif()
