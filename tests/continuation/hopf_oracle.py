"""An independent evaluation of Kuznetsov's first Lyapunov coefficient at high precision.

Kuznetsov, *Elements of Applied Bifurcation Theory*, 3rd ed., (10.56) in §10.2 (and §3.5):

    l1 = 1/(2ω) Re[⟨p, C(q,q,q̄)⟩ − 2⟨p, B(q, A⁻¹B(q,q̄))⟩ + ⟨p, B(q̄, (2iω − A)⁻¹B(q,q))⟩],
    A q = iω q, Aᵀ p = −iω p, ⟨q, q⟩ = 1, ⟨p, q⟩ = 1, ⟨a, b⟩ = āᵀ b,

for ``u' = f(u)``: ``f`` a list of sympy expressions, its derivative tensors exact (sympy),
every number an mpmath number at ``dps`` digits, the eigenvectors from :func:`mpmath.eig`.
Nothing here shares code with :mod:`cusp.continuation`. A mass matrix ``M`` (invertible) is
handled as the book would: ``f := M⁻¹ R`` symbolically.
"""

from __future__ import annotations

import mpmath as mp
import sympy as sy


def _at(expr, subs):
    return mp.mpmathify(sy.N(expr.subs(subs), mp.mp.dps + 10))


def hopf_l1(f, xs, subs, *, mass=None, dps: int = 50):
    """``(omega, l1)`` of ``u' = f`` (or ``M u' = f``) at the Hopf point ``subs`` (exact
    sympy values of the unknowns and parameters)."""
    with mp.workdps(dps):
        f = sy.Matrix(f)
        if mass is not None:
            f = sy.Matrix(mass).inv() * f
        n = len(xs)
        jac = f.jacobian(xs)
        A = mp.matrix([[_at(jac[i, j], subs) for j in range(n)] for i in range(n)])
        w, er = mp.eig(A)
        k = max(range(n), key=lambda i: mp.im(w[i]))
        omega = mp.im(w[k])
        assert abs(mp.re(w[k])) < mp.mpf(10) ** (-dps // 2), w[k]
        q = er[:, k]
        q = q / mp.sqrt(sum(abs(q[i]) ** 2 for i in range(n)))
        wl, el = mp.eig(A.T)
        kl = min(range(n), key=lambda i: abs(wl[i] + 1j * omega))
        p = el[:, kl]
        pq = sum(mp.conj(p[i]) * q[i] for i in range(n))
        p = p / mp.conj(pq)  # ⟨p, q⟩ = 1

        second = [[[_at(sy.diff(f[i], xs[j], xs[k2]), subs) for k2 in range(n)]
                   for j in range(n)] for i in range(n)]  # fmt: skip
        third = [[[[_at(sy.diff(f[i], xs[j], xs[k2], xs[m]), subs) for m in range(n)]
                   for k2 in range(n)] for j in range(n)] for i in range(n)]  # fmt: skip

        def B(x, y):
            return mp.matrix(
                [
                    sum(second[i][j][k2] * x[j] * y[k2] for j in range(n) for k2 in range(n))
                    for i in range(n)
                ]  # fmt: skip
            )

        def C(x, y, z):
            return mp.matrix(
                [
                    sum(
                        third[i][j][k2][m] * x[j] * y[k2] * z[m]
                        for j in range(n)
                        for k2 in range(n)
                        for m in range(n)
                    )
                    for i in range(n)
                ]  # fmt: skip
            )

        def dot(a, b):
            return sum(mp.conj(a[i]) * b[i] for i in range(n))

        qb = mp.matrix([mp.conj(q[i]) for i in range(n)])
        r1 = mp.lu_solve(A, B(q, qb))
        r2 = mp.lu_solve(2j * omega * mp.eye(n) - A, B(q, q))
        total = dot(p, C(q, q, qb)) - 2 * dot(p, B(q, r1)) + dot(p, B(qb, r2))
        return omega, mp.re(total) / (2 * omega)
