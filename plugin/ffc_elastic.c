/* ffc_elastic.c: the stiffness matrix of isotropic linear elasticity on
 * linear tetrahedra, assembled straight into its distinct entries. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"

static int cmp_long(const void *a, const void *b)
{
    const long x = *(const long *)a, y = *(const long *)b;
    return (x > y) - (x < y);
}

/* the position of j in the ascending list c[n] (present by construction) */
static long find(const long c[], long n, long j)
{
    long lo = 0, hi = n - 1;
    while (lo < hi) {
        const long mid = (lo + hi) / 2;
        if (c[mid] < j) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

/* Formulation: u = sum_b N_b u_b on a tetrahedron of volume V, with the
 * constant gradients g_a = grad N_a: the rows of J^-1, J = [x1 - x0, x2 -
 * x0, x3 - x0] (columns), for a = 1, 2, 3 and g_0 = -(g_1 + g_2 + g_3).
 * The energy density lambda (div u)^2 / 2 + mu eps(u) : eps(u) gives, for
 * the test function N_a e_i and the trial function N_b e_j,
 *     div:            lambda g_a[i] g_b[j]
 *     2 mu eps : eps: mu (g_a[j] g_b[i] + delta_ij g_a . g_b)
 * (2 mu eps(N_b e_j) : eps(N_a e_i) with eps(N e_j)_kl = (delta_lj g[k] +
 * delta_kj g[l]) / 2), each times V: one quadrature point is exact. */
int ffc_elastic_p1(long nv, const double X[], long nt, const long T[], const double lam[], const double mu[],
                   long cap, long Ki[], long Kj[], double Kv[], long *nnz, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!nnz || (nv > 0 && !X) || (nt > 0 && (!T || !lam || !mu)) || (cap > 0 && (!Ki || !Kj || !Kv)))
        return FFC_ERR_NULL;
    *nnz = 0;
    if (nv < 0 || nt < 0 || cap < 0) return FFC_ERR_SIZE;
    for (long i = 0; i < 3 * nv; i++)
        if (!isfinite(X[i])) { *bad = i / 3; return FFC_ERR_NONFINITE; }
    for (long t = 0; t < nt; t++) {
        for (int a = 0; a < 4; a++)
            if (T[4 * t + a] < 0 || T[4 * t + a] >= nv) { *bad = t; return FFC_ERR_INDEX; }
        if (!isfinite(lam[t]) || !isfinite(mu[t])) { *bad = t; return FFC_ERR_NONFINITE; }
    }
    /* the vertex graph: row i lists i and the vertices that share a
     * tetrahedron with it, ascending, each once */
    long *rp = calloc((size_t)nv + 1, sizeof *rp), *adj = malloc((size_t)(12 * nt + nv + 1) * sizeof *adj);
    long *fill = malloc(((size_t)nv + 1) * sizeof *fill);
    if (!rp || !adj || !fill) {
        free(rp); free(adj); free(fill);
        return FFC_ERR_MEMORY;
    }
    for (long i = 0; i < nv; i++) rp[i + 1] = 1;
    for (long t = 0; t < nt; t++)
        for (int a = 0; a < 4; a++) rp[T[4 * t + a] + 1] += 3;
    for (long i = 0; i < nv; i++) rp[i + 1] += rp[i];
    for (long i = 0; i < nv; i++) { fill[i] = rp[i] + 1; adj[rp[i]] = i; }
    for (long t = 0; t < nt; t++)
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                if (b != a) adj[fill[T[4 * t + a]]++] = T[4 * t + b];
    long nb = 0; /* distinct blocks; rows compacted in place, fill[i] = row i's count */
    for (long i = 0; i < nv; i++) {
        long *c = adj + rp[i], k = rp[i + 1] - rp[i], u = 0;
        qsort(c, (size_t)k, sizeof *c, cmp_long);
        for (long e = 0; e < k; e++)
            if (e == 0 || c[e] != c[e - 1]) adj[nb + u++] = c[e];
        fill[i] = u;
        rp[i] = nb;
        nb += u;
    }
    rp[nv] = nb;
    *nnz = 9 * nb;
    if (cap < 9 * nb) {
        free(rp); free(adj); free(fill);
        return FFC_ERR_CAPACITY;
    }
    /* dof row 3 i + ci holds 3 fill[i] entries from 9 rp[i] + 3 ci fill[i]:
     * column 3 j + cj at 3 (position of j in row i) + cj */
    for (long i = 0; i < nv; i++)
        for (int ci = 0; ci < 3; ci++) {
            const long r0 = 9 * rp[i] + 3 * ci * fill[i];
            for (long e = 0; e < fill[i]; e++)
                for (int cj = 0; cj < 3; cj++) {
                    Ki[r0 + 3 * e + cj] = 3 * i + ci;
                    Kj[r0 + 3 * e + cj] = 3 * adj[rp[i] + e] + cj;
                    Kv[r0 + 3 * e + cj] = 0.0;
                }
        }
    int st = FFC_OK;
    for (long t = 0; t < nt && !st; t++) {
        const long *v = T + 4 * t;
        const double *x0 = X + 3 * v[0];
        double J[3][3]; /* J[r][c] = (x_{c+1} - x0)[r] */
        for (int c = 0; c < 3; c++)
            for (int r = 0; r < 3; r++) J[r][c] = X[3 * v[c + 1] + r] - x0[r];
        const double c00 = J[1][1] * J[2][2] - J[1][2] * J[2][1], c01 = J[1][2] * J[2][0] - J[1][0] * J[2][2],
                     c02 = J[1][0] * J[2][1] - J[1][1] * J[2][0];
        const double det = J[0][0] * c00 + J[0][1] * c01 + J[0][2] * c02;
        /* zero volume: |det| at round-off's level of |e1| |e2| |e3| */
        double e[3] = {0, 0, 0};
        for (int c = 0; c < 3; c++) e[c] = sqrt(J[0][c] * J[0][c] + J[1][c] * J[1][c] + J[2][c] * J[2][c]);
        if (!(fabs(det) > 1e-13 * e[0] * e[1] * e[2]) || !isfinite(det)) { *bad = t; st = FFC_ERR_DEGENERATE; break; }
        /* rows of J^-1 = cofactor columns / det */
        double g[4][3];
        g[1][0] = c00 / det; g[2][0] = c01 / det; g[3][0] = c02 / det;
        g[1][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det;
        g[2][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det;
        g[3][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det;
        g[1][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det;
        g[2][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det;
        g[3][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det;
        for (int k = 0; k < 3; k++) g[0][k] = -(g[1][k] + g[2][k] + g[3][k]);
        const double V = fabs(det) / 6.0, l = lam[t] * V, m = mu[t] * V;
        for (int a = 0; a < 4; a++) {
            const long i = v[a];
            for (int b = 0; b < 4; b++) {
                const long e = find(adj + rp[i], fill[i], v[b]);
                const double gg = g[a][0] * g[b][0] + g[a][1] * g[b][1] + g[a][2] * g[b][2];
                for (int ci = 0; ci < 3; ci++) {
                    double *row = Kv + 9 * rp[i] + 3 * ci * fill[i] + 3 * e;
                    for (int cj = 0; cj < 3; cj++)
                        row[cj] += l * g[a][ci] * g[b][cj] + m * g[a][cj] * g[b][ci] + (ci == cj ? m * gg : 0.0);
                }
            }
        }
    }
    free(rp); free(adj); free(fill);
    return st;
}
