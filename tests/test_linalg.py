"""The stacked linear algebra of ``filterwnn._linalg``: the column-by-column Cholesky factor and
forward substitution (member axis last) against NumPy's LAPACK, and the errors of ``cholesky``."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from filterwnn import NumericalError
from filterwnn._linalg import (COLUMNS_MAX_N, COLUMNS_MIN_STACK, cholesky, cholesky_columns, columns_layout,
                               not_pd_error, smallest_eigenvalue, solve_lower_columns)

TOL = 1e-12  # relative to the matrices' scale


def _pd_stack(seed, N, n, scale=1.0):
    g = np.random.default_rng(seed)
    A = g.normal(0.0, 1.0, (N, n, n + 2))
    return scale * (np.matmul(A, np.swapaxes(A, 1, 2)) / (n + 2) + 0.05 * np.eye(n))


def _columns(P):
    return np.ascontiguousarray(P.transpose(1, 2, 0))


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), N=st.integers(1, 40), n=st.integers(1, COLUMNS_MAX_N),
       log_scale=st.floats(-6.0, 6.0))
def test_cholesky_columns_equals_lapack(seed, N, n, log_scale):
    P = _pd_stack(seed, N, n, 10.0**log_scale)
    L, ok = cholesky_columns(_columns(P))
    assert ok.all() and L.shape == (n, n, N)
    ref = np.linalg.cholesky(P)
    np.testing.assert_allclose(L.transpose(2, 0, 1), ref, rtol=0, atol=TOL * np.sqrt(10.0**log_scale) * 10)
    assert np.all(np.triu(L.transpose(2, 0, 1), 1) == 0.0)


@pytest.mark.parametrize("spoil", ["negative", "singular", "nan_lower", "inf_diagonal", "nan_diagonal"])
def test_cholesky_columns_flags_the_members_lapack_rejects(spoil):
    P = _pd_stack(1, 9, 4)
    k = 6
    if spoil == "negative":
        P[k] = -np.eye(4)
    elif spoil == "singular":
        P[k] = np.ones((4, 4))
    elif spoil == "nan_lower":
        P[k, 3, 1] = P[k, 1, 3] = np.nan
    elif spoil == "inf_diagonal":
        P[k, 2, 2] = np.inf
    else:
        P[k, 0, 0] = np.nan
    _, ok = cholesky_columns(_columns(P))
    lapack_ok = []
    for Pi in P:
        try:
            lapack_ok.append(bool(np.all(np.isfinite(np.linalg.cholesky(Pi)))))
        except np.linalg.LinAlgError:
            lapack_ok.append(False)
    assert ok.tolist() == lapack_ok and not ok[k] and ok.sum() == 8


def test_cholesky_columns_reads_only_the_lower_triangle():
    P = _pd_stack(2, 5, 3)
    Pu = P.copy()
    Pu[:, 0, 2] = np.nan  # above the diagonal: not read, as LAPACK's lower factor
    L, ok = cholesky_columns(_columns(Pu))
    assert ok.all()
    np.testing.assert_array_equal(L, cholesky_columns(_columns(P))[0])


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), N=st.integers(1, 30), n=st.integers(1, COLUMNS_MAX_N), m=st.integers(1, 7))
def test_solve_lower_columns_equals_numpy_solve(seed, N, n, m):
    g = np.random.default_rng(seed)
    L = np.linalg.cholesky(_pd_stack(seed, N, n))
    Bm = g.normal(0.0, 1.0, (N, n, m))
    X = solve_lower_columns(_columns(L), np.ascontiguousarray(Bm.transpose(1, 2, 0)))
    np.testing.assert_allclose(X.transpose(2, 0, 1), np.linalg.solve(L, Bm), rtol=1e-10, atol=1e-10)


def test_cholesky_of_a_long_stack_is_by_columns_and_equals_lapack():
    N, n = COLUMNS_MIN_STACK, 6
    assert columns_layout(N, n) and not columns_layout(N - 1, n) and not columns_layout(N, COLUMNS_MAX_N + 1)
    P = _pd_stack(3, N, n)
    L = cholesky(P, "P", step=4)
    np.testing.assert_allclose(L, np.linalg.cholesky(P), rtol=0, atol=TOL)
    np.testing.assert_array_equal(L.transpose(1, 2, 0), cholesky_columns(_columns(P))[0])  # the view, no copy


@pytest.mark.parametrize("N", [8, COLUMNS_MIN_STACK + 3], ids=["lapack", "columns"])
def test_cholesky_names_the_first_member_that_is_not_pd_on_either_path(N):
    P = _pd_stack(4, N, 5)
    P[5] = np.diag([1.0, 1.0, -1e-3, 1.0, 1.0])
    P[7, 4, 1] = np.nan
    with pytest.raises(NumericalError, match=r"^S is not positive definite at step 9 \(particle 5\); check R$") as e:
        cholesky(P, "S", step=9, remedy="check R")
    assert e.value.matrix == "S" and e.value.step == 9


@pytest.mark.parametrize("spoil", ["negative", "singular", "nan_lower", "inf_diagonal", "nan_diagonal",
                                   "zero_last_pivot", "inf_last"])
def test_cholesky_on_the_column_path_rejects_the_stacks_lapack_rejects(spoil):
    """The column path decides for the whole stack from two reductions of the pivots (their
    minimum positive, their maximum finite): every spoilt member raises, naming it, as the
    per-member check does; ``zero_last_pivot`` is the one that no later pivot would catch."""
    N, n = COLUMNS_MIN_STACK + 3, 4
    P = _pd_stack(5, N, n)
    k = N - 1
    if spoil == "negative":
        P[k] = -np.eye(n)
    elif spoil == "singular":
        P[k] = np.ones((n, n))
    elif spoil == "nan_lower":
        P[k, 3, 1] = P[k, 1, 3] = np.nan
    elif spoil == "inf_diagonal":
        P[k, 2, 2] = np.inf
    elif spoil == "nan_diagonal":
        P[k, 0, 0] = np.nan
    elif spoil == "zero_last_pivot":
        P[k] = np.diag([1.0, 2.0, 3.0, 0.0])
    else:
        P[k] = np.diag([1.0, 1.0, 1.0, np.inf])  # an overflow upstream
    lapack = [bool(np.all(np.isfinite(Pi))) and np.all(np.linalg.eigvalsh(Pi) > 0) for Pi in P]
    assert not lapack[k] and all(lapack[:k])
    with pytest.raises(NumericalError, match=rf"^P is not positive definite at step 2 \(particle {k}\)"):
        cholesky(P, "P", step=2)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_not_pd_error_names_a_non_finite_entry_instead_of_an_eigenvalue(bad):
    P = np.eye(3)
    P[1, 2] = bad
    msg = str(not_pd_error("P", P, step=7, remedy="reset P"))
    assert msg == f"P is not positive definite at step 7; P[1, 2] is {bad}; reset P"
    assert smallest_eigenvalue(P) is None
