"""study/__init__.py: the process settings made on import (one BLAS thread; numba's own choice of vector instructions)."""

import os
import subprocess
import sys


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


def test_numba_keeps_its_own_choice_of_vector_instructions():
    # docs/workers.md: the opt-in that compiled without AVX-512 (STUDY_AVX512=0) was removed once it no longer paid;
    # the variable now changes nothing and a user's NUMBA_CPU_FEATURES stands
    assert _imported({})["NUMBA_CPU_FEATURES"] is None
    assert _imported({"STUDY_AVX512": "0"})["NUMBA_CPU_FEATURES"] is None
    assert _imported({"NUMBA_CPU_FEATURES": "+sse2"})["NUMBA_CPU_FEATURES"] == "+sse2"
