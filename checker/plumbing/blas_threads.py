"""One BLAS thread per process while checker's own processes share the cores.

NumPy's and SciPy's OpenBLAS start a thread per core for a large enough matrix product or
solve (the torsion's frequency response). In one process alone that uses an idle core; while
the remedies' helper processes and the tolerance corners' process keep every core busy, each
of those threads competes with the other processes' work and spins while it waits for the
next call. Measured on the I4 example (2 cores, remedies in two processes): 19.5 s of
processor time with the default threads, 16.9 s with one per process, the answers identical.
"""

from __future__ import annotations

from contextlib import AbstractContextManager, nullcontext


def one_per_process(active: bool = True) -> AbstractContextManager:
    """Context in which the BLAS libraries loaded in this process use one thread (and the
    processes forked inside it inherit that); the previous limits are restored at its end.
    ``active=False``: nothing changes."""
    if not active:
        return nullcontext()
    from threadpoolctl import threadpool_limits

    return threadpool_limits(limits=1, user_api="blas")
