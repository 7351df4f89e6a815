/* ffc_tree.c: the bounding-volume tree over the master facets (Morton order, implicit binary heap). */
#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_tree.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------ helpers */
/* the facet's size: its longest edge (ffc__facet_size2) */
static double facet_h(int nn, const double *X)
{
    (void)nn;
    return sqrt(ffc__facet_size2((const double(*)[3])X));
}

/* (ffc_tree.h) */
void ffc__facet_box(int nn, const double *X, double b[6])
{
    for (int i = 0; i < 3; i++) { b[i] = INFINITY; b[3 + i] = -INFINITY; }
    for (int a = 0; a < nn; a++)
        for (int i = 0; i < 3; i++) {
            double v = X[3 * a + i];
            if (v < b[i]) b[i] = v;
            if (v > b[3 + i]) b[3 + i] = v;
        }
    if (nn == 6) {
        /* the quadratic patch lies in the convex hull of its Bezier control
         * points: the vertices and, per edge (a, b) with mid-node m,
         * 2 m - (a + b) / 2 */
        static const int ed[3][3] = {{0, 1, 3}, {1, 2, 4}, {2, 0, 5}};
        for (int e = 0; e < 3; e++)
            for (int i = 0; i < 3; i++) {
                double v = 2.0 * X[3 * ed[e][2] + i] - 0.5 * (X[3 * ed[e][0] + i] + X[3 * ed[e][1] + i]);
                if (v < b[i]) b[i] = v;
                if (v > b[3 + i]) b[3 + i] = v;
            }
    }
}

static uint64_t spread3(uint64_t v)
{
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
}

/* LSD radix sort of (key, idx) pairs on 8-bit digits */
static int radix_sort(long n, uint64_t *key, long *idx)
{
    uint64_t *k2 = malloc((size_t)n * sizeof *k2);
    long *i2 = malloc((size_t)n * sizeof *i2);
    if (!k2 || !i2) { free(k2); free(i2); return FFC_ERR_MEMORY; }
    for (int pass = 0; pass < 8; pass++) {
        const int sh = 8 * pass;
        long cnt[257] = {0};
        for (long i = 0; i < n; i++) cnt[((key[i] >> sh) & 255) + 1]++;
        if (cnt[1] == n) continue; /* every key has this digit 0 */
        for (int d = 0; d < 256; d++) cnt[d + 1] += cnt[d];
        for (long i = 0; i < n; i++) {
            long o = cnt[(key[i] >> sh) & 255]++;
            k2[o] = key[i];
            i2[o] = idx[i];
        }
        memcpy(key, k2, (size_t)n * sizeof *key);
        memcpy(idx, i2, (size_t)n * sizeof *idx);
    }
    free(k2);
    free(i2);
    return FFC_OK;
}

/* The traversal's boxes (qb) from the double ones, relative to the root
 * box's centre qo in units of its half-width qscale (values of order 1,
 * whatever the model's units: no float overflow or underflow), widened by
 * 8 FLT_EPSILON and rounded to float: for a query point with |p_i - qo_i|
 * <= 2 qscale the float distance (the box and (p - qo) / qscale rounded,
 * their differences rounded: each error below 4 FLT_EPSILON) is then below
 * the exact distance to the double box, so that the float test, scaled
 * back by qscale^2 (see lower_bound), never prunes a facet the double test
 * keeps. */
static void fill_quad_boxes(ffc_tree *t)
{
    const double *r = t->box + 6;
    double sc = 0.0;
    for (int k = 0; k < 3; k++) {
        t->qo[k] = 0.5 * (r[k] + r[3 + k]);
        sc = fmax(sc, 0.5 * (r[3 + k] - r[k]));
    }
    if (!isfinite(sc)) sc = 0.0;
    t->qscale = sc;
    t->qfast = t->qb && sc >= 1e-30 && sc <= 1e30;
    if (!t->qfast) return;
    const double pad = 8.0 * FLT_EPSILON, inv = 1.0 / sc;
    for (long i = 1; i < t->P / 2; i++) {
        float *g = t->qb + 24 * i;
        for (int j = 0; j < 4; j++) {
            const double *b = t->box + 6 * (4 * i + j);
            for (int k = 0; k < 3; k++) {
                g[4 * k + j] = (float)((b[k] - t->qo[k]) * inv - pad);
                g[12 + 4 * k + j] = (float)((b[3 + k] - t->qo[k]) * inv + pad);
            }
        }
    }
}

/* Facet coordinates into tree order and all boxes from the leaves up. */
static int fill_geometry(ffc_tree *t, const double x[])
{
    const int nn = t->nn;
    t->hmax = 0.0;
    for (long s = 0; s < t->nf; s++) {
        const long f = t->slot2f[s];
        double *X = t->fx + s * nn * 3;
        for (int a = 0; a < nn; a++)
            for (int i = 0; i < 3; i++) {
                double v = x[3 * t->F[f * nn + a] + i];
                if (!isfinite(v)) return FFC_ERR_NONFINITE;
                X[3 * a + i] = v;
            }
        double h = facet_h(nn, X);
        t->hf[f] = h;
        if (nn == 3) { /* ffc_project's test of a linear facet's area */
            double e1[3], e2[3], c[3];
            for (int i = 0; i < 3; i++) { e1[i] = X[3 + i] - X[i]; e2[i] = X[6 + i] - X[i]; }
            ffc__cross(e1, e2, c);
            t->degen[s] = ffc__degenerate(ffc__dot(c, c), ffc__facet_size2((const double(*)[3])X));
        } else
            t->degen[s] = 0;
        if (h > t->hmax) t->hmax = h;
    }
    const long P = t->P;
    for (long j = 0; j < P; j++) {
        double *b = t->box + 6 * (P + j);
        for (int i = 0; i < 3; i++) { b[i] = INFINITY; b[3 + i] = -INFINITY; }
        for (long s = j * FFC__LEAF; s < (j + 1) * FFC__LEAF && s < t->nf; s++) {
            double fb[6];
            ffc__facet_box(nn, t->fx + s * nn * 3, fb);
            for (int i = 0; i < 3; i++) {
                b[i] = fmin(b[i], fb[i]);
                b[3 + i] = fmax(b[3 + i], fb[3 + i]);
            }
        }
    }
    for (long i = P - 1; i >= 1; i--) {
        double *b = t->box + 6 * i, *l = t->box + 12 * i, *r = l + 6;
        for (int k = 0; k < 3; k++) {
            b[k] = fmin(l[k], r[k]);
            b[3 + k] = fmax(l[3 + k], r[3 + k]);
        }
    }
    fill_quad_boxes(t);
    return FFC_OK;
}

/* Edge neighbours through the node -> facet incidence (linear time). */
static int build_adjacency(ffc_tree *t)
{
    const int nn = t->nn;
    const long nf = t->nf, nv = t->nv;
    long *start = calloc((size_t)nv + 1, sizeof *start);
    long *inc = malloc((size_t)nf * 3 * sizeof *inc);
    if (!start || !inc) { free(start); free(inc); return FFC_ERR_MEMORY; }
    for (long f = 0; f < nf; f++)
        for (int a = 0; a < 3; a++) start[t->F[f * nn + a] + 1]++;
    for (long v = 0; v < nv; v++) start[v + 1] += start[v];
    for (long f = 0; f < nf; f++)
        for (int a = 0; a < 3; a++) inc[start[t->F[f * nn + a]]++] = f;
    for (long v = nv; v > 0; v--) start[v] = start[v - 1];
    start[0] = 0;
    memset(t->vrim, 0, (size_t)nf * 3);
    for (long f = 0; f < nf; f++)
        for (int e = 0; e < 3; e++) {
            const long a = t->F[f * nn + e], b = t->F[f * nn + (e + 1) % 3];
            long g = -1;
            for (long k = start[a]; k < start[a + 1] && g < 0; k++) {
                long h = inc[k];
                if (h == f) continue;
                for (int c = 0; c < 3; c++)
                    if (t->F[h * nn + c] == b) { g = h; break; }
            }
            t->nbr[f * 3 + e] = g;
        }
    /* rim vertices: on an edge without a neighbour, seen from every facet */
    unsigned char *rim = calloc((size_t)nv, 1);
    if (!rim) { free(start); free(inc); return FFC_ERR_MEMORY; }
    for (long f = 0; f < nf; f++)
        for (int e = 0; e < 3; e++)
            if (t->nbr[f * 3 + e] < 0) {
                rim[t->F[f * nn + e]] = 1;
                rim[t->F[f * nn + (e + 1) % 3]] = 1;
            }
    for (long f = 0; f < nf; f++)
        for (int a = 0; a < 3; a++) t->vrim[f * 3 + a] = rim[t->F[f * nn + a]];
    free(rim);
    free(start);
    free(inc);
    return FFC_OK;
}

void ffc_tree_free(ffc_tree *t)
{
    if (!t) return;
    free(t->F);
    free(t->slot2f);
    free(t->f2slot);
    free(t->hf);
    free(t->degen);
    free(t->fx);
    free(t->box);
    free(t->qb);
    free(t->nbr);
    free(t->vrim);
    free(t);
}

long ffc_tree_bytes(const ffc_tree *t)
{
    if (!t) return 0;
    return (long)sizeof *t + t->nf * (long)(t->nn * sizeof(long) + 2 * sizeof(long) + sizeof(double) +
                                            t->nn * 3 * sizeof(double) + 3 * sizeof(long) + 4) +
           2 * t->P * 6 * (long)sizeof(double) + (t->P >= 4 ? t->P / 2 * 24 * (long)sizeof(float) : 0);
}

int ffc_tree_build(int nn, long nf, const long F[], long nv, const double x[],
                   ffc_tree **out)
{
    if (!out) return FFC_ERR_NULL;
    *out = NULL;
    if (nn != 3 && nn != 6) return FFC_ERR_NODES;
    if (!F || !x) return FFC_ERR_NULL;
    if (nf <= 0) return FFC_ERR_EMPTY;
    if (nv <= 0) return FFC_ERR_SIZE;
    for (long k = 0; k < nf * nn; k++)
        if (F[k] < 0 || F[k] >= nv) return FFC_ERR_INDEX;

    ffc_tree *t = calloc(1, sizeof *t);
    if (!t) return FFC_ERR_MEMORY;
    t->nn = nn;
    t->nf = nf;
    t->nv = nv;
    long L = (nf + FFC__LEAF - 1) / FFC__LEAF, P = 1;
    while (P < L) P *= 2;
    t->P = P;
    while ((1L << t->depth) < P) t->depth++;
    t->F = malloc((size_t)nf * nn * sizeof *t->F);
    t->slot2f = malloc((size_t)nf * sizeof *t->slot2f);
    t->hf = malloc((size_t)nf * sizeof *t->hf);
    t->degen = malloc((size_t)nf);
    t->f2slot = malloc((size_t)nf * sizeof *t->f2slot);
    t->fx = malloc((size_t)nf * nn * 3 * sizeof *t->fx);
    t->box = malloc((size_t)2 * P * 6 * sizeof *t->box);
    t->qb = P >= 4 ? malloc((size_t)P / 2 * 24 * sizeof *t->qb) : NULL;
    t->nbr = malloc((size_t)nf * 3 * sizeof *t->nbr);
    t->vrim = malloc((size_t)nf * 3);
    uint64_t *key = malloc((size_t)nf * sizeof *key);
    int st = FFC_ERR_MEMORY;
    if (!t->F || !t->slot2f || !t->hf || !t->degen || !t->f2slot || !t->fx || !t->box || (P >= 4 && !t->qb) || !t->nbr || !t->vrim || !key) goto fail;
    memcpy(t->F, F, (size_t)nf * nn * sizeof *F);

    /* Morton keys of the facet centroids */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (long f = 0; f < nf; f++)
        for (int i = 0; i < 3; i++) {
            double c = (x[3 * F[f * nn] + i] + x[3 * F[f * nn + 1] + i] + x[3 * F[f * nn + 2] + i]) / 3.0;
            if (!isfinite(c)) { st = FFC_ERR_NONFINITE; goto fail; }
            lo[i] = fmin(lo[i], c);
            hi[i] = fmax(hi[i], c);
        }
    double span = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    double sc = span > 0 ? 2097151.0 / span : 0.0;
    for (long f = 0; f < nf; f++) {
        uint64_t k = 0;
        for (int i = 0; i < 3; i++) {
            double c = (x[3 * F[f * nn] + i] + x[3 * F[f * nn + 1] + i] + x[3 * F[f * nn + 2] + i]) / 3.0;
            k |= spread3((uint64_t)((c - lo[i]) * sc)) << i;
        }
        key[f] = k;
        t->slot2f[f] = f;
    }
    if ((st = radix_sort(nf, key, t->slot2f))) goto fail;
    for (long k = 0; k < nf; k++) t->f2slot[t->slot2f[k]] = k;
    free(key);
    key = NULL;
    if ((st = fill_geometry(t, x))) goto fail;
    if ((st = build_adjacency(t))) goto fail;
    *out = t;
    return FFC_OK;
fail:
    free(key);
    ffc_tree_free(t);
    return st;
}

int ffc_tree_refit(ffc_tree *t, const double x[])
{
    if (!t || !x) return FFC_ERR_NULL;
    return fill_geometry(t, x);
}
