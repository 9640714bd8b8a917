"""study/__init__.py: the process settings made on import (one BLAS thread; the kernels' vector instructions)."""

import os
import subprocess
import sys

import pytest


def _imported(env: dict) -> dict:
    """The environment variables study sets, read in a fresh interpreter that imports study with ``env``."""
    names = ("NUMBA_CPU_FEATURES", "OPENBLAS_NUM_THREADS")
    base = {k: v for k, v in os.environ.items() if k not in names + ("STUDY_AVX512",)}
    code = "import os, study; print(repr({n: os.environ.get(n) for n in %r}))" % (names,)
    out = subprocess.run([sys.executable, "-c", code], env={**base, **env}, capture_output=True, text=True, check=True)
    return eval(out.stdout)


def test_one_blas_thread_unless_the_user_says_otherwise():
    assert _imported({})["OPENBLAS_NUM_THREADS"] == "1"
    assert _imported({"OPENBLAS_NUM_THREADS": "4"})["OPENBLAS_NUM_THREADS"] == "4"


def test_avx512_kept_by_default_and_turned_off_on_request():
    # docs/workers.md: the default keeps the host's features (numba's own choice); STUDY_AVX512=0 drops every AVX-512
    # feature and keeps the others; a user's NUMBA_CPU_FEATURES stands either way
    assert _imported({})["NUMBA_CPU_FEATURES"] is None
    features = _imported({"STUDY_AVX512": "0"})["NUMBA_CPU_FEATURES"]
    if features is None:
        pytest.fail("STUDY_AVX512=0 set no features")
    from llvmlite import binding

    host = binding.get_host_cpu_features().flatten().split(",")
    assert features.split(",") == [("-" + f[1:]) if "avx512" in f else f for f in host]  # only AVX-512 turned off
    assert _imported({"STUDY_AVX512": "0", "NUMBA_CPU_FEATURES": "+sse2"})["NUMBA_CPU_FEATURES"] == "+sse2"
