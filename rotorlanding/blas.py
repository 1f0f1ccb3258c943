"""BLAS threads: one place that sets them.

The rotor's dense problems (FE assembly, the Craig-Bampton eigenproblem, the 2n x 2n state-space
eigenproblem of ``modal``) are a few hundred unknowns. OpenBLAS's threads do not pay at that size and
on a busy machine they spin against each other: a 280 x 280 ``scipy.linalg.eig`` measured 0.04 s on
one thread and 8-12 s on the default threads at load 7 on this 2-core machine
(``benchmarks/blas_threads.py``). One thread also makes the floats independent of the machine's
thread count, so the same rotor gives the same modes bit for bit everywhere."""
import contextlib
import os

BLAS_ENV = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
_BLAS_API = (("openblas_set_num_threads", "openblas_get_num_threads"),
             ("openblas_set_num_threads64_", "openblas_get_num_threads64_"),
             ("scipy_openblas_set_num_threads", "scipy_openblas_get_num_threads"),
             ("scipy_openblas_set_num_threads64_", "scipy_openblas_get_num_threads64_"),
             ("MKL_Set_Num_Threads", "MKL_Get_Max_Threads"))


def _blas_libraries() -> list:
    """(set, get) ctypes functions of every BLAS library loaded in this process (Linux)."""
    import ctypes

    try:
        with open("/proc/self/maps") as fh:
            paths = {line.split()[-1] for line in fh if ".so" in line and ("blas" in line or "mkl" in line)}
    except OSError:
        return []
    out, seen = [], set()
    for path in sorted(paths):
        try:
            dll = ctypes.CDLL(path)
        except OSError:
            continue
        for set_name, get_name in _BLAS_API:
            f, g = getattr(dll, set_name, None), getattr(dll, get_name, None)
            if f is not None and g is not None:
                key = ctypes.cast(f, ctypes.c_void_p).value
                if key not in seen:
                    seen.add(key)
                    f.argtypes, f.restype, g.argtypes, g.restype = [ctypes.c_int], None, [], ctypes.c_int
                    out.append((f, g))
                break
    return out


def limit_blas_threads(n: int = 1):
    """Set every loaded BLAS library of this process (and processes it starts) to ``n`` threads.
    Returns a function that restores the previous settings. Uses threadpoolctl when installed,
    else OpenBLAS/MKL's own setters."""
    env = {k: os.environ.get(k) for k in BLAS_ENV}
    for k in BLAS_ENV:
        os.environ[k] = str(n)
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:
        libs = _blas_libraries()
        before = [g() for f, g in libs]
        for f, g in libs:
            f(n)

        def undo_libs():
            for (f, g), m in zip(libs, before):
                f(m)
    else:
        limits = threadpool_limits(n)
        undo_libs = limits.restore_original_limits

    def restore():
        undo_libs()
        for k, v in env.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v

    return restore


@contextlib.contextmanager
def blas_threads(n: int = 1):
    """``with blas_threads(1): ...`` runs the block on ``n`` BLAS threads, then restores them."""
    restore = limit_blas_threads(n)
    try:
        yield
    finally:
        restore()
