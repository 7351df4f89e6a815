/* ffc_elastic.c: the stiffness matrix of isotropic linear elasticity on
 * linear and quadratic tetrahedra, assembled straight into its distinct
 * entries. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"
#include "ffc_internal.h"

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
/* Tetrahedron t's terms (its nodes nd[npe], gradients g, volume V) added
 * into Kv at the places of the node graph (ffc__tet_graph: rp, adj, fill) */
static void add_tet(long npe, const long nd[], const double g[4][3], double V, double lam, double mu, const long rp[],
                    const long adj[], const long fill[], double Kv[])
{
    const double qa = (5.0 + 3.0 * sqrt(5.0)) / 20.0, qb = (5.0 - sqrt(5.0)) / 20.0;
    const int nq = npe == 4 ? 1 : 4;
    for (int q = 0; q < nq; q++) {
        double G[10][3], L[4];
        for (int a = 0; a < 4; a++) L[a] = nq == 1 ? 0.25 : (a == q ? qa : qb);
        ffc__tet_shape_gradients(npe, g, L, G);
        const double w = V / nq, l = lam * w, m = mu * w;
        for (long a = 0; a < npe; a++) {
            const long i = nd[a];
            for (long b = 0; b < npe; b++) {
                const long e = ffc__find_long(adj + rp[i], fill[i], nd[b]);
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
    /* the node graph (ffc__tet_graph) */
    long *rp = calloc((size_t)nn + 1, sizeof *rp), *adj = malloc((size_t)(npe * (npe - 1) * nt + nn + 1) * sizeof *adj);
    long *fill = malloc(((size_t)nn + 1) * sizeof *fill);
    if (!rp || !adj || !fill) {
        free(rp); free(adj); free(fill);
        return FFC_ERR_MEMORY;
    }
    const long nb = ffc__tet_graph(nt, npe, nn, E, rp, adj, fill);
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
        if (ffc__tet_gradients(X, T + 4 * t, g, &V)) { *bad = t; st = FFC_ERR_DEGENERATE; break; }
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
