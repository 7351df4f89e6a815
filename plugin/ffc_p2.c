/* ffc_p2.c: the nodes of quadratic (P2) tetrahedra numbered as FreeFEM
 * numbers scalar P2 degrees of freedom, their positions, and the six nodes
 * of a boundary face. */
#include "ffc.h"

#include <stdint.h>
#include <stdlib.h>

/* local edges of a tetrahedron, in FreeFEM's order */
static const int ffc__tet_edge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

int ffc_p2_number(long nt, const long T[], long nv, long node[], long *nnodes)
{
    if (!T || !node || !nnodes) return FFC_ERR_NULL;
    if (nt <= 0 || nv <= 0) return FFC_ERR_SIZE;
    for (long k = 0; k < 4 * nt; k++)
        if (T[k] < 0 || T[k] >= nv) return FFC_ERR_INDEX;
    long *vnode = malloc((size_t)nv * sizeof *vnode);
    long cap = 16;
    while (cap < 4 * nt) cap *= 2;            /* > 2x the number of edges (< 6 nt / 2 + ...) */
    while (cap < 8 * nt) cap *= 2;
    uint64_t *key = malloc((size_t)cap * sizeof *key);
    long *val = malloc((size_t)cap * sizeof *val);
    if (!vnode || !key || !val) { free(vnode); free(key); free(val); return FFC_ERR_MEMORY; }
    for (long v = 0; v < nv; v++) vnode[v] = -1;
    for (long i = 0; i < cap; i++) key[i] = UINT64_MAX;
    long n = 0;
    for (long k = 0; k < nt; k++) {
        const long *t = T + 4 * k;
        for (int a = 0; a < 4; a++) {
            if (vnode[t[a]] < 0) vnode[t[a]] = n++;
            node[10 * k + a] = vnode[t[a]];
        }
        for (int e = 0; e < 6; e++) {
            long a = t[ffc__tet_edge[e][0]], b = t[ffc__tet_edge[e][1]];
            if (a > b) { long s = a; a = b; b = s; }
            const uint64_t kk = (uint64_t)a * (uint64_t)nv + (uint64_t)b;
            uint64_t h = kk * 0x9E3779B97F4A7C15ULL;
            long i = (long)(h >> 20) & (cap - 1);
            while (key[i] != UINT64_MAX && key[i] != kk) i = (i + 1) & (cap - 1);
            if (key[i] == UINT64_MAX) { key[i] = kk; val[i] = n++; }
            node[10 * k + 4 + e] = val[i];
        }
    }
    free(vnode);
    free(key);
    free(val);
    *nnodes = n;
    return FFC_OK;
}

int ffc_p2_positions(long nt, const long T[], const long node[], const double X[],
                     long nnodes, double X2[])
{
    if (!T || !node || !X || !X2) return FFC_ERR_NULL;
    for (long k = 0; k < nt; k++)
        for (int j = 0; j < 10; j++) {
            long m = node[10 * k + j];
            if (m < 0 || m >= nnodes) return FFC_ERR_INDEX;
            for (int i = 0; i < 3; i++) {
                const long *t = T + 4 * k;
                X2[3 * m + i] = j < 4 ? X[3 * t[j] + i]
                                      : 0.5 * (X[3 * t[ffc__tet_edge[j - 4][0]] + i] +
                                               X[3 * t[ffc__tet_edge[j - 4][1]] + i]);
            }
        }
    return FFC_OK;
}

int ffc_p2_face(const long T4[4], const long node10[10], const long face[3], long out[6])
{
    if (!T4 || !node10 || !face || !out) return FFC_ERR_NULL;
    int loc[3];
    for (int a = 0; a < 3; a++) {
        loc[a] = -1;
        for (int j = 0; j < 4; j++)
            if (T4[j] == face[a]) loc[a] = j;
        if (loc[a] < 0) return FFC_ERR_INDEX;
        out[a] = node10[loc[a]];
    }
    for (int a = 0; a < 3; a++) {
        int p = loc[a], q = loc[(a + 1) % 3];
        if (p > q) { int s = p; p = q; q = s; }
        int e = 0;
        while (e < 6 && !(ffc__tet_edge[e][0] == p && ffc__tet_edge[e][1] == q)) e++;
        if (e == 6) return FFC_ERR_INDEX;
        out[3 + a] = node10[4 + e];
    }
    return FFC_OK;
}
