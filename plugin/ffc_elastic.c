/* ffc_elastic.c: the stiffness matrix of isotropic linear elasticity on
 * linear and quadratic tetrahedra, assembled straight into its distinct
 * entries. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"
#include "ffc_internal.h"

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

/* Formulation: u = sum_b N_b u_b on a straight-sided tetrahedron of
 * volume V, J = [x1 - x0, x2 - x0, x3 - x0] (columns), g_a = grad L_a the
 * gradients of its barycentric coordinates L: the rows of J^-1 for a = 1,
 * 2, 3 and g_0 = -(g_1 + g_2 + g_3).  The energy density lambda (div u)^2
 * / 2 + mu eps(u) : eps(u) gives, for the test function N_a e_i and the
 * trial function N_b e_j, with G_a = grad N_a at a point,
 *     div:            lambda G_a[i] G_b[j]
 *     2 mu eps : eps: mu (G_a[j] G_b[i] + delta_ij G_a . G_b)
 * (2 mu eps(N_b e_j) : eps(N_a e_i) with eps(N e_j)_kl = (delta_lj G[k] +
 * delta_kj G[l]) / 2), integrated over the tetrahedron.  Linear (4 nodes):
 * N_a = L_a, G_a = g_a constant, one point (V) is exact.  Quadratic (10
 * nodes, FreeFEM's order: the vertices, then the edges 01 02 03 12 13
 * 23): N_a = L_a (2 L_a - 1), G_a = (4 L_a - 1) g_a at a vertex, N = 4 L_p
 * L_q, G = 4 (L_p g_q + L_q g_p) on edge pq; G_a[i] G_b[j] is quadratic,
 * and the 4-point rule of degree 2 (L = (a, b, b, b) and its
 * permutations, a = (5 + 3 sqrt 5) / 20, b = (5 - sqrt 5) / 20, weights
 * V / 4) is exact. */
static const int tet_edge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

/* The node graph of the tetrahedra's nodes E[nt*npe] (nn nodes): row i
 * lists i and the nodes that share a tetrahedron with it, ascending, each
 * once, in adj[rp[i] .. rp[i] + fill[i]) (rp[nn]: their count, returned) */
static long node_graph(long nt, long npe, long nn, const long E[], long rp[], long adj[], long fill[])
{
    for (long i = 0; i < nn; i++) rp[i + 1] = 1;
    for (long t = 0; t < nt; t++)
        for (long a = 0; a < npe; a++) rp[E[npe * t + a] + 1] += npe - 1;
    for (long i = 0; i < nn; i++) rp[i + 1] += rp[i];
    for (long i = 0; i < nn; i++) { fill[i] = rp[i] + 1; adj[rp[i]] = i; }
    for (long t = 0; t < nt; t++)
        for (long a = 0; a < npe; a++)
            for (long b = 0; b < npe; b++)
                if (b != a) adj[fill[E[npe * t + a]]++] = E[npe * t + b];
    long nb = 0; /* distinct blocks; rows compacted in place, fill[i] = row i's count */
    for (long i = 0; i < nn; i++) {
        long *c = adj + rp[i], k = rp[i + 1] - rp[i], u = 0;
        qsort(c, (size_t)k, sizeof *c, ffc__cmp_long);
        for (long e = 0; e < k; e++)
            if (e == 0 || c[e] != c[e - 1]) adj[nb + u++] = c[e];
        fill[i] = u;
        rp[i] = nb;
        nb += u;
    }
    rp[nn] = nb;
    return nb;
}

/* Tetrahedron v[4]'s barycentric gradients g (g[0] = -(g[1] + g[2] +
 * g[3])) and volume *V; FFC_ERR_DEGENERATE for a zero volume */
static int tet_gradients(const double X[], const long v[4], double g[4][3], double *V)
{
    const double *x0 = X + 3 * v[0];
    double J[3][3]; /* J[r][c] = (x_{c+1} - x0)[r] */
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++) J[r][c] = X[3 * v[c + 1] + r] - x0[r];
    const double c00 = J[1][1] * J[2][2] - J[1][2] * J[2][1], c01 = J[1][2] * J[2][0] - J[1][0] * J[2][2],
                 c02 = J[1][0] * J[2][1] - J[1][1] * J[2][0];
    const double det = J[0][0] * c00 + J[0][1] * c01 + J[0][2] * c02;
    /* zero volume: |det| at round-off's level of |e1| |e2| |e3| */
    double el[3];
    for (int c = 0; c < 3; c++) el[c] = sqrt(J[0][c] * J[0][c] + J[1][c] * J[1][c] + J[2][c] * J[2][c]);
    if (!(fabs(det) > 1e-13 * el[0] * el[1] * el[2]) || !isfinite(det)) return FFC_ERR_DEGENERATE;
    /* rows of J^-1 = cofactor columns / det */
    g[1][0] = c00 / det; g[2][0] = c01 / det; g[3][0] = c02 / det;
    g[1][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det;
    g[2][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det;
    g[3][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det;
    g[1][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det;
    g[2][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det;
    g[3][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det;
    for (int k = 0; k < 3; k++) g[0][k] = -(g[1][k] + g[2][k] + g[3][k]);
    *V = fabs(det) / 6.0;
    return FFC_OK;
}

/* Tetrahedron t's terms (its nodes nd[npe], gradients g, volume V) added
 * into Kv at the places of the node graph (node_graph: rp, adj, fill) */
static void add_tet(long npe, const long nd[], const double g[4][3], double V, double lam, double mu, const long rp[],
                    const long adj[], const long fill[], double Kv[])
{
    const double qa = (5.0 + 3.0 * sqrt(5.0)) / 20.0, qb = (5.0 - sqrt(5.0)) / 20.0;
    const int nq = npe == 4 ? 1 : 4;
    for (int q = 0; q < nq; q++) {
        double G[10][3], L[4];
        for (int a = 0; a < 4; a++) L[a] = nq == 1 ? 0.25 : (a == q ? qa : qb);
        if (npe == 4)
            memcpy(G, g, 4 * sizeof g[0]);
        else {
            for (int a = 0; a < 4; a++)
                for (int k = 0; k < 3; k++) G[a][k] = (4.0 * L[a] - 1.0) * g[a][k];
            for (int e = 0; e < 6; e++) {
                const int p = tet_edge[e][0], r = tet_edge[e][1];
                for (int k = 0; k < 3; k++) G[4 + e][k] = 4.0 * (L[p] * g[r][k] + L[r] * g[p][k]);
            }
        }
        const double w = V / nq, l = lam * w, m = mu * w;
        for (long a = 0; a < npe; a++) {
            const long i = nd[a];
            for (long b = 0; b < npe; b++) {
                const long e = find(adj + rp[i], fill[i], nd[b]);
                const double gg = G[a][0] * G[b][0] + G[a][1] * G[b][1] + G[a][2] * G[b][2];
                for (int ci = 0; ci < 3; ci++) {
                    double *row = Kv + 9 * rp[i] + 3 * ci * fill[i] + 3 * e;
                    for (int cj = 0; cj < 3; cj++)
                        row[cj] += l * G[a][ci] * G[b][cj] + m * G[a][cj] * G[b][ci] + (ci == cj ? m * gg : 0.0);
                }
            }
        }
    }
}

static int assemble(long nv, const double X[], long nt, const long T[], long npe, long nn, const long E[],
                    const double lam[], const double mu[], long cap, long Ki[], long Kj[], double Kv[], long *nnz,
                    long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!nnz || (nv > 0 && !X) || (nt > 0 && (!T || !E || !lam || !mu)) || (cap > 0 && (!Ki || !Kj || !Kv)))
        return FFC_ERR_NULL;
    *nnz = 0;
    if (nv < 0 || nt < 0 || nn < 0 || cap < 0) return FFC_ERR_SIZE;
    for (long i = 0; i < 3 * nv; i++)
        if (!isfinite(X[i])) { *bad = i / 3; return FFC_ERR_NONFINITE; }
    for (long t = 0; t < nt; t++) {
        for (int a = 0; a < 4; a++)
            if (T[4 * t + a] < 0 || T[4 * t + a] >= nv) { *bad = t; return FFC_ERR_INDEX; }
        for (long a = 0; a < npe; a++)
            if (E[npe * t + a] < 0 || E[npe * t + a] >= nn) { *bad = t; return FFC_ERR_INDEX; }
        if (!isfinite(lam[t]) || !isfinite(mu[t])) { *bad = t; return FFC_ERR_NONFINITE; }
    }
    /* the node graph (node_graph) */
    long *rp = calloc((size_t)nn + 1, sizeof *rp), *adj = malloc((size_t)(npe * (npe - 1) * nt + nn + 1) * sizeof *adj);
    long *fill = malloc(((size_t)nn + 1) * sizeof *fill);
    if (!rp || !adj || !fill) {
        free(rp); free(adj); free(fill);
        return FFC_ERR_MEMORY;
    }
    const long nb = node_graph(nt, npe, nn, E, rp, adj, fill);
    *nnz = 9 * nb;
    if (cap < 9 * nb) {
        free(rp); free(adj); free(fill);
        return FFC_ERR_CAPACITY;
    }
    /* dof row 3 i + ci holds 3 fill[i] entries from 9 rp[i] + 3 ci fill[i]:
     * column 3 j + cj at 3 (position of j in row i) + cj */
    for (long i = 0; i < nn; i++)
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
        double g[4][3], V;
        if (tet_gradients(X, T + 4 * t, g, &V)) { *bad = t; st = FFC_ERR_DEGENERATE; break; }
        add_tet(npe, E + npe * t, (const double(*)[3])g, V, lam[t], mu[t], rp, adj, fill, Kv);
    }
    free(rp); free(adj); free(fill);
    return st;
}

int ffc_elastic_p1(long nv, const double X[], long nt, const long T[], const double lam[], const double mu[],
                   long cap, long Ki[], long Kj[], double Kv[], long *nnz, long *bad)
{
    return assemble(nv, X, nt, T, 4, nv, T, lam, mu, cap, Ki, Kj, Kv, nnz, bad);
}

int ffc_elastic_p2(long nv, const double X[], long nt, const long T[], long nn, const long node[],
                   const double lam[], const double mu[], long cap, long Ki[], long Kj[], double Kv[], long *nnz,
                   long *bad)
{
    return assemble(nv, X, nt, T, 10, nn, node, lam, mu, cap, Ki, Kj, Kv, nnz, bad);
}
