/* ffc_obstacle.c: rigid obstacles given by their shape: checks, gap, normal and its derivative, the links of a slave surface. */
#include "ffc.h"
#include "ffc_internal.h"

#include <math.h>
#include <string.h>

static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

int ffc_obstacle_check(const ffc_obstacle *ob)
{
    if (!ob) return FFC_ERR_NULL;
    if (ob->kind != FFC_OBST_PLANE && ob->kind != FFC_OBST_SPHERE && ob->kind != FFC_OBST_CYLINDER)
        return FFC_ERR_VALUE;
    if (!finite3(ob->c) || !finite3(ob->d) || !isfinite(ob->r)) return FFC_ERR_NONFINITE;
    if (ob->inside != 0 && ob->inside != 1) return FFC_ERR_VALUE;
    if (ob->kind == FFC_OBST_PLANE && ob->inside) return FFC_ERR_VALUE;
    if (ob->kind != FFC_OBST_PLANE && !(ob->r > 0)) return FFC_ERR_VALUE;
    if (ob->kind != FFC_OBST_SPHERE) {
        if (!finite3(ob->a)) return FFC_ERR_NONFINITE;
        if (fabs(ffc__dot(ob->a, ob->a) - 1.0) > 1e-12) return FFC_ERR_VALUE;
    }
    return FFC_OK;
}

int ffc_obstacle_make(int kind, const double c[3], const double a[3], double r, int inside, ffc_obstacle *ob)
{
    if (!c || !ob || (kind != FFC_OBST_SPHERE && !a)) return FFC_ERR_NULL;
    memset(ob, 0, sizeof *ob);
    ob->kind = kind;
    ob->r = kind == FFC_OBST_PLANE ? 0.0 : r;
    ob->inside = inside;
    for (int i = 0; i < 3; i++) ob->c[i] = c[i];
    if (kind != FFC_OBST_SPHERE) {
        if (!finite3(a)) return FFC_ERR_NONFINITE;
        const double L = sqrt(ffc__dot(a, a));
        if (!(L > 0)) return FFC_ERR_VALUE;
        for (int i = 0; i < 3; i++) ob->a[i] = a[i] / L;
    }
    return ffc_obstacle_check(ob);
}

/* Formulation.  phi(x) = s (|d| - r) with d = P (x - c), P = I (sphere)
 * or I - a a^T (cylinder): grad phi = s P d / |d| = s d / |d| = n (P d =
 * d, P symmetric), and
 *     dn/dx = s (P - d d^T / |d|^2) / |d| = s (P - n n^T) / |d|
 * (n n^T = d d^T / |d|^2 since s^2 = 1).  The plane's n = a is constant. */
int ffc_obstacle_gap(const ffc_obstacle *ob, const double x[3], double *g, double n[3], double H[3][3])
{
    if (!ob || !x || !g || !n) return FFC_ERR_NULL;
    if (!finite3(x)) return FFC_ERR_NONFINITE;
    double d[3] = {x[0] - ob->c[0], x[1] - ob->c[1], x[2] - ob->c[2]};
    if (ob->kind == FFC_OBST_PLANE) {
        *g = ffc__dot(ob->a, d);
        for (int i = 0; i < 3; i++) n[i] = ob->a[i];
        if (H)
            for (int i = 0; i < 3; i++) H[i][0] = H[i][1] = H[i][2] = 0.0;
        return FFC_OK;
    }
    const int cyl = ob->kind == FFC_OBST_CYLINDER;
    if (cyl) {
        const double da = ffc__dot(d, ob->a);
        for (int i = 0; i < 3; i++) d[i] -= da * ob->a[i];
    }
    const double L = sqrt(ffc__dot(d, d)), s = ob->inside ? -1.0 : 1.0;
    if (!(L > 1e-300) || !(L > 1e-12 * ob->r)) return FFC_ERR_DEGENERATE;
    *g = s * (L - ob->r);
    for (int i = 0; i < 3; i++) n[i] = s * d[i] / L;
    if (H)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                const double P = (i == j) - (cyl ? ob->a[i] * ob->a[j] : 0.0);
                H[i][j] = s * (P - n[i] * n[j]) / L;
            }
    return FFC_OK;
}

long ffc_obstacle_facing(const ffc_obstacle *ob, int nn, long nf, const long F[], long nv, const double x[])
{
    if (!ob || !F || !x) return FFC_ERR_NULL;
    int st = ffc_obstacle_check(ob);
    if (st) return st;
    if (nn != 3 && nn != 6) return FFC_ERR_NODES;
    long count = 0;
    for (long f = 0; f < nf; f++) {
        const double *p[3];
        for (int a = 0; a < 3; a++) {
            const long v = F[f * nn + a];
            if (v < 0 || v >= nv) return FFC_ERR_INDEX;
            p[a] = x + 3 * v;
        }
        double nf3[3], c[3], g, n[3];
        for (int i = 0; i < 3; i++) c[i] = (p[0][i] + p[1][i] + p[2][i]) / 3.0;
        ffc__tri_normal(p[0], p[1], p[2], nf3);
        if (ffc_obstacle_gap(ob, c, &g, n, NULL)) continue;
        count += ffc__dot(nf3, n) < 0.0;
    }
    return count;
}

int ffc_obstacle_search(const ffc_obstacle *ob, int nns, long nfs, const long Fs[], long nv, const double x[],
                        int qdeg, const ffc_search_opts *o, long cap, ffc_link links[])
{
    if (!ob || !Fs || !x || !links) return FFC_ERR_NULL;
    int st = ffc_obstacle_check(ob);
    if (st) return st;
    if (nns != 3 && nns != 6) return FFC_ERR_NODES;
    if (nfs <= 0) return FFC_ERR_EMPTY;
    ffc_search_opts def = ffc_search_defaults();
    if (!o) o = &def;
    double qxi[16][2], qw[16];
    const int nq = ffc_quad(qdeg, 16, qxi, qw);
    if (nq < 0) return nq;
    if (cap < nfs * nq) return FFC_ERR_CAPACITY;
    long found = 0;
    for (long f = 0; f < nfs; f++) {
        double P[FFC_MAXNODES][3];
        for (int a = 0; a < nns; a++) {
            const long v = Fs[f * nns + a];
            if (v < 0 || v >= nv) return FFC_ERR_INDEX;
            for (int i = 0; i < 3; i++) P[a][i] = x[3 * v + i];
        }
        const double h = sqrt(ffc__facet_size2((const double(*)[3])P));
        const double rmax = fmax(o->capture_abs, o->capture_rel * h);
        for (int q = 0; q < nq; q++) {
            ffc_link *lk = &links[f * nq + q];
            memset(lk, 0, sizeof *lk);
            lk->sf = f;
            lk->q = q;
            lk->xs[0] = qxi[q][0];
            lk->xs[1] = qxi[q][1];
            lk->mf = -1;
            double N[FFC_MAXNODES], p[3] = {0, 0, 0};
            ffc_shape(nns, qxi[q], N, NULL);
            for (int a = 0; a < nns; a++)
                for (int i = 0; i < 3; i++) p[i] += N[a] * P[a][i];
            double g, n[3];
            st = ffc_obstacle_gap(ob, p, &g, n, NULL);
            if (st == FFC_ERR_DEGENERATE) continue;   /* on the centre or the axis: far inside, no normal */
            if (st) return st;
            if (g > rmax) continue;
            lk->mf = 0;
            lk->gap = g;
            for (int i = 0; i < 3; i++) lk->n[i] = n[i];
            found++;
        }
    }
    return (int)found;
}
