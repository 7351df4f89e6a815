/* ffc_tet.c: what the bulk assemblies share on straight-sided tetrahedra: the node graph, the barycentric gradients, the shape gradients of P1 and P2 at a point, the quadrature rules. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"
#include "ffc_internal.h"

const int ffc__tet_edge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

long ffc__find_long(const long c[], long n, long j)
{
    long lo = 0, hi = n - 1;
    while (lo < hi) {
        const long mid = (lo + hi) / 2;
        if (c[mid] < j) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

long ffc__tet_graph(long nt, long npe, long nn, const long E[], long rp[], long adj[], long fill[])
{
    for (long i = 0; i < nn; i++) rp[i + 1] = 1;
    for (long t = 0; t < nt; t++)
        for (long a = 0; a < npe; a++) rp[E[npe * t + a] + 1] += npe - 1;
    rp[0] = 0;
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

int ffc__tet_gradients(const double X[], const long v[4], double g[4][3], double *V)
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

void ffc__tet_shape_gradients(long npe, const double g[4][3], const double L[4], double G[10][3])
{
    if (npe == 4) {
        memcpy(G, g, 4 * sizeof g[0]);
        return;
    }
    for (int a = 0; a < 4; a++)
        for (int k = 0; k < 3; k++) G[a][k] = (4.0 * L[a] - 1.0) * g[a][k];
    for (int e = 0; e < 6; e++) {
        const int p = ffc__tet_edge[e][0], r = ffc__tet_edge[e][1];
        for (int k = 0; k < 3; k++) G[4 + e][k] = 4.0 * (L[p] * g[r][k] + L[r] * g[p][k]);
    }
}

/* The 14-point rule of degree 5 (Walkington's; FreeFEM's qfV5): the
 * barycentric points of three orbits, (a, a, a, 1 - 3a) and (b, b, b, 1 -
 * 3b) with their 4 permutations each, (c, c, 1/2 - c, 1/2 - c) with its
 * 6, and their weights as fractions of the volume. */
int ffc__tet_rule5(double L[14][4], double w[14])
{
    const double a = 0.0927352503108912264023239137370306, wa = 6 * 0.0122488405193936582572850342477212;
    const double b = 0.310885919263300609797345733763457, wb = 6 * 0.0187813209530026417998642753888810;
    const double c = 0.454496295874350350508119473720660, wc = 6 * 7.09100346284691107301157135337624E-3;
    int q = 0;
    for (int k = 0; k < 4; k++, q++) {
        for (int m = 0; m < 4; m++) L[q][m] = m == k ? 1.0 - 3.0 * a : a;
        w[q] = wa;
    }
    for (int k = 0; k < 4; k++, q++) {
        for (int m = 0; m < 4; m++) L[q][m] = m == k ? 1.0 - 3.0 * b : b;
        w[q] = wb;
    }
    for (int e = 0; e < 6; e++, q++) {
        for (int m = 0; m < 4; m++) L[q][m] = 0.5 - c;
        L[q][ffc__tet_edge[e][0]] = c;
        L[q][ffc__tet_edge[e][1]] = c;
        w[q] = wc;
    }
    return q;
}
