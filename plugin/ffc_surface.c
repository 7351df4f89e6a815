/* ffc_surface.c: selection, outward orientation, validation and area of
 * labelled boundary surfaces given as plain arrays. */
#include "ffc.h"
#include "ffc_internal.h"

#include <math.h>
#include <stdlib.h>

long ffc_labels_present(long nbe, const long belab[], long cap, long out[])
{
    if (nbe <= 0 || !belab) return 0;
    long *tmp = malloc((size_t)nbe * sizeof *tmp);
    if (!tmp) return FFC_ERR_MEMORY;
    for (long k = 0; k < nbe; k++) tmp[k] = belab[k];
    qsort(tmp, (size_t)nbe, sizeof *tmp, ffc__cmp_long);
    long nd = 0;
    for (long k = 0; k < nbe; k++) {
        if (k > 0 && tmp[k] == tmp[k - 1]) continue;
        if (nd < cap && out) out[nd] = tmp[k];
        nd++;
    }
    free(tmp);
    return nd;
}

/* Gathers facet f's node positions X + u into P. */
static void gather(int nn, const long *F, long f, const double X[],
                   const double u[], double P[][3])
{
    for (int a = 0; a < nn; a++) {
        long v = F[f * nn + a];
        for (int i = 0; i < 3; i++)
            P[a][i] = X[3 * v + i] + (u ? u[3 * v + i] : 0.0);
    }
}

static int in_set(long v, int n, const long s[])
{
    for (int i = 0; i < n; i++)
        if (s[i] == v) return 1;
    return 0;
}

int ffc_surface_select(int nn, long nbe, const long be[], const long belab[],
                       const long beopp[], long nv, const double X[],
                       int nlab, const long labs[], long cap, long F[],
                       long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (nn != 3 && nn != 6) return FFC_ERR_NODES;
    if (!be || !belab || !X || !labs) return FFC_ERR_NULL;
    if (nbe < 0 || nv <= 0 || nlab < 0) return FFC_ERR_SIZE;
    if (nlab == 0) return FFC_ERR_EMPTY;
    /* every requested label must be carried by at least one face */
    for (int l = 0; l < nlab; l++) {
        long k = 0;
        while (k < nbe && belab[k] != labs[l]) k++;
        if (k == nbe) { *bad = labs[l]; return FFC_ERR_LABEL; }
    }
    long count = 0;
    for (long k = 0; k < nbe; k++)
        if (in_set(belab[k], nlab, labs)) count++;
    if (count == 0) return FFC_ERR_EMPTY;
    if (count > cap || !F) { *bad = count; return FFC_ERR_CAPACITY; }

    long nf = 0;
    for (long k = 0; k < nbe; k++) {
        if (!in_set(belab[k], nlab, labs)) continue;
        for (int a = 0; a < nn; a++) {
            long v = be[k * nn + a];
            if (v < 0 || v >= nv) { *bad = k; return FFC_ERR_INDEX; }
            F[nf * nn + a] = v;
        }
        double P[FFC_MAXNODES][3];
        gather(nn, F, nf, X, 0, P);
        ffc_point g;
        const double c[2] = {1.0 / 3.0, 1.0 / 3.0};
        int st = ffc_facet_point(nn, (const double(*)[3])P, c, &g);
        if (st) { *bad = k; return st; }
        if (beopp) {
            long o = beopp[k];
            if (o < 0 || o >= nv) { *bad = k; return FFC_ERR_INDEX; }
            double d[3] = {X[3 * o] - g.x[0], X[3 * o + 1] - g.x[1], X[3 * o + 2] - g.x[2]};
            if (ffc__dot(d, g.n) > 0.0) {
                /* the normal points into the body: reverse the facet
                 * (swap vertices 1, 2 and the mid-edge nodes 3, 5) */
                long *f = F + nf * nn, s = f[1];
                f[1] = f[2]; f[2] = s;
                if (nn == 6) { s = f[3]; f[3] = f[5]; f[5] = s; }
            }
        }
        nf++;
    }
    return (int)nf == nf ? (int)nf : FFC_ERR_SIZE;
}

int ffc_surface_check(int nn, long nf, const long F[], long nv,
                      const double X[], const double u[], long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (nn != 3 && nn != 6) return FFC_ERR_NODES;
    if (!F || !X) return FFC_ERR_NULL;
    if (nf < 0 || nv <= 0) return FFC_ERR_SIZE;
    if (nf == 0) return FFC_ERR_EMPTY;
    for (long f = 0; f < nf; f++)
        for (int a = 0; a < nn; a++) {
            long v = F[f * nn + a];
            if (v < 0 || v >= nv) { *bad = f; return FFC_ERR_INDEX; }
            for (int i = 0; i < 3; i++)
                if (!isfinite(X[3 * v + i]) || (u && !isfinite(u[3 * v + i]))) {
                    *bad = v;
                    return FFC_ERR_NONFINITE;
                }
        }
    const double c[2] = {1.0 / 3.0, 1.0 / 3.0};
    for (long f = 0; f < nf; f++) {
        double P[FFC_MAXNODES][3];
        gather(nn, F, f, X, u, P);
        ffc_point g;
        int st = ffc_facet_point(nn, (const double(*)[3])P, c, &g);
        if (st) { *bad = f; return st; }
    }
    return FFC_OK;
}

int ffc_surface_area(int nn, long nf, const long F[], long nv,
                     const double X[], const double u[], int degree,
                     double *area)
{
    if (!area) return FFC_ERR_NULL;
    *area = 0.0;
    long bad;
    int st = ffc_surface_check(nn, nf, F, nv, X, u, &bad);
    if (st) return st;
    double xi[16][2], w[16];
    int nq = ffc_quad(degree, 16, xi, w);
    if (nq < 0) return nq;
    double A = 0.0;
    for (long f = 0; f < nf; f++) {
        double P[FFC_MAXNODES][3];
        gather(nn, F, f, X, u, P);
        for (int q = 0; q < nq; q++) {
            ffc_point g;
            st = ffc_facet_point(nn, (const double(*)[3])P, xi[q], &g);
            if (st) return st;
            A += w[q] * g.j;
        }
    }
    *area = A;
    return FFC_OK;
}

int ffc_surface_normals(int nn, long nf, const long F[], long nv,
                        const double X[], const double u[], double N[],
                        long *bad)
{
    int st = ffc_surface_check(nn, nf, F, nv, X, u, bad);
    if (st) return st;
    if (!N) return FFC_ERR_NULL;
    const double c[2] = {1.0 / 3.0, 1.0 / 3.0};
    for (long f = 0; f < nf; f++) {
        double P[FFC_MAXNODES][3];
        gather(nn, F, f, X, u, P);
        ffc_point g;
        st = ffc_facet_point(nn, (const double(*)[3])P, c, &g);
        if (st) { *bad = f; return st; }
        for (int i = 0; i < 3; i++) N[3 * f + i] = g.n[i];
    }
    return FFC_OK;
}

/* six times the signed volume of the tetrahedron with vertices v[4] */
static double tet_vol6(const long v[4], const double X[], const double u[])
{
    double e[3][3];
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 3; i++)
            e[k][i] = X[3 * v[k + 1] + i] - X[3 * v[0] + i] +
                      (u ? u[3 * v[k + 1] + i] - u[3 * v[0] + i] : 0.0);
    double c[3];
    ffc__cross(e[0], e[1], c);
    return ffc__dot(c, e[2]);
}

void ffc__tet_volumes(long nt, const long T[], const double X[], double v0[])
{
    for (long t = 0; t < nt; t++) v0[t] = tet_vol6(T + 4 * t, X, NULL);
}

/* the tetrahedron v[4] at X + u against its reference six-volume v0:
 * FFC_ERR_NONFINITE, FFC_ERR_INVERTED (turned or collapsed), or FFC_OK */
static int tet_state(const long v[4], const double X[], double v0, const double u[])
{
    const double vu = tet_vol6(v, X, u);
    if (!isfinite(vu)) return FFC_ERR_NONFINITE;
    return vu / v0 > 1e-12 ? FFC_OK : FFC_ERR_INVERTED;
}

int ffc__volume_check_ref(long nt, const long T[], const double X[], const double v0[], const double u[], long *bad)
{
    *bad = -1;
    for (long t = 0; t < nt; t++) {
        const int st = tet_state(T + 4 * t, X, v0[t], u);
        if (st) { *bad = t; return st; }
    }
    return FFC_OK;
}

int ffc_volume_check(long nt, const long T[], long nv, const double X[],
                     const double u[], long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!T || !X) return FFC_ERR_NULL;
    if (nt < 0 || nv <= 0) return FFC_ERR_SIZE;
    for (long t = 0; t < nt; t++) {
        for (int a = 0; a < 4; a++)
            if (T[4 * t + a] < 0 || T[4 * t + a] >= nv) { *bad = t; return FFC_ERR_INDEX; }
        const int st = tet_state(T + 4 * t, X, tet_vol6(T + 4 * t, X, NULL), u);
        if (st) { *bad = t; return st; }
    }
    return FFC_OK;
}

/* Formulation: the mean ratio of a tetrahedron, q = 12 (3 |V|)^(2/3) /
 * sum of its six squared edge lengths: 1 for the regular one (edge l: V =
 * l^3 / (6 sqrt 2), so 3 V = l^3 / (2 sqrt 2), (3 V)^(2/3) = l^2 / 2, and
 * 12 l^2 / 2 = 6 l^2), falling to 0 as it flattens into a sliver, a
 * needle or a cap; invariant under translation, rotation and scaling. */
int ffc_mesh_quality(long nt, const long T[], long nv, const double X[], double qbelow, double *worst,
                     long *worst_tet, long *below)
{
    if (!T || !X || !worst || !worst_tet || !below) return FFC_ERR_NULL;
    if (nt <= 0 || nv <= 0) return FFC_ERR_SIZE;
    if (!(qbelow >= 0.0)) return FFC_ERR_VALUE;
    *worst = INFINITY;
    *worst_tet = -1;
    *below = 0;
    for (long t = 0; t < nt; t++) {
        const long *v = T + 4 * t;
        for (int a = 0; a < 4; a++)
            if (v[a] < 0 || v[a] >= nv) { *worst_tet = t; return FFC_ERR_INDEX; }
        double l2 = 0.0;
        for (int a = 0; a < 4; a++)
            for (int b = a + 1; b < 4; b++)
                for (int i = 0; i < 3; i++) {
                    const double d = X[3 * v[b] + i] - X[3 * v[a] + i];
                    l2 += d * d;
                }
        const double v3 = fabs(tet_vol6(v, X, NULL)) / 2.0;   /* 3 |V| */
        if (!isfinite(l2) || !isfinite(v3)) { *worst_tet = t; return FFC_ERR_NONFINITE; }
        const double q = l2 > 0.0 ? 12.0 * cbrt(v3 * v3) / l2 : 0.0;
        if (q < *worst) { *worst = q; *worst_tet = t; }
        *below += q < qbelow;
    }
    return FFC_OK;
}
