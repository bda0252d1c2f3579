#!/usr/bin/env bash
# Installs lcprelax's build and test dependencies from Debian 12 packages (run as root or
# with sudo). Idempotent.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update
$SUDO apt-get install -y --no-install-recommends \
  build-essential cmake libeigen3-dev libsuitesparse-dev libgtest-dev libgmock-dev \
  libbenchmark-dev nlohmann-json3-dev libcli11-dev coinor-clp \
  pkg-config libcairo2-dev
# PETSc with MPI and MUMPS (LCPRELAX_WITH_PETSC): the MUMPS KKT backend, MPI learning, and
# mpiexec for the 2-rank tests.
$SUDO apt-get install -y --no-install-recommends libpetsc-real3.18-dev openmpi-bin
# clang with its sanitizer and libFuzzer runtimes: the fuzz targets' compiler
# (scripts/fuzz.sh; the sanitizer job of scripts/sanitize.sh uses GCC).
$SUDO apt-get install -y --no-install-recommends clang libclang-rt-14-dev
# Python bindings (LCPRELAX_WITH_PYTHON: python/, docs/python.md) and their pytest suite.
$SUDO apt-get install -y --no-install-recommends pybind11-dev python3-numpy python3-scipy python3-pytest python3-dev
# PyTorch for lcprelax.torch (QpLayer, LcpLayer, RelaxedLcpLoss) and its gradcheck tests.
$SUDO apt-get install -y --no-install-recommends python3-torch
