#!/usr/bin/env python3
"""pyamg's smoothed aggregation on the HPM elastic stiffness, for a
side-by-side iteration count with dismech's own multigrid.

Write the matrix first (Matrix Market, from the same model as the bench):

    cargo bench --bench hpm_elastic -- 100 5 mtx=/tmp/hpm100
    python3 benches/hpm_pyamg.py /tmp/hpm100 [tol]

It reads K.mtx (12 unknowns an element), b.mtx (the loads) and B.mtx (the
six rigid motions of each element), builds pyamg's
smoothed_aggregation_solver with B as near-null space and blocks of 12
(symmetric strength, standard aggregation, Jacobi-smoothed prolongator,
symmetric block Gauss-Seidel sweeps before and after the coarse
correction: pyamg's defaults but theta = 0, max_coarse = 2000 and a sparse
LU on the coarsest level), and solves
K x = b by PCG with one V-cycle per iteration to the relative residual tol
(1e-8 by default). Requires `pip install pyamg scipy`.
"""

import sys
import time

import numpy as np
import pyamg
import scipy.io
import scipy.sparse


def main():
    folder = sys.argv[1]
    tol = float(sys.argv[2]) if len(sys.argv) > 2 else 1e-8
    t0 = time.perf_counter()
    K = scipy.sparse.csr_matrix(scipy.io.mmread(f"{folder}/K.mtx"))
    b = np.asarray(scipy.io.mmread(f"{folder}/b.mtx")).ravel()
    B = np.asarray(scipy.io.mmread(f"{folder}/B.mtx"))
    K = K.tobsr(blocksize=(12, 12))
    t1 = time.perf_counter()
    ml = pyamg.smoothed_aggregation_solver(
        K,
        B=B,
        strength=("symmetric", {"theta": 0.0}),
        smooth=("jacobi", {"omega": 4.0 / 3.0}),
        presmoother=("block_gauss_seidel", {"sweep": "symmetric"}),
        postsmoother=("block_gauss_seidel", {"sweep": "symmetric"}),
        max_coarse=2000 // 12,  # counted in block rows here
        coarse_solver="splu",
    )
    t2 = time.perf_counter()
    residuals = []
    x = ml.solve(b, tol=tol, accel="cg", maxiter=2000, residuals=residuals)
    t3 = time.perf_counter()
    relative = np.linalg.norm(b - K @ x) / np.linalg.norm(b)
    print(ml)
    print(
        f"pyamg {pyamg.__version__}: {K.shape[0]} unknowns; read {t1 - t0:.2f} s; "
        f"setup {t2 - t1:.2f} s; PCG {t3 - t2:.2f} s ({len(residuals) - 1} iterations, "
        f"relative residual {relative:.3e}); setup + PCG {t3 - t1:.2f} s"
    )


if __name__ == "__main__":
    main()
