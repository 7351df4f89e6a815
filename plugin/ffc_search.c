/* ffc_search.c: contact search: a bounding-volume tree over the master
 * facets (Morton order, implicit binary heap), exact closest-facet queries
 * by branch and bound, edge adjacency, and slave-point links. */
#include "ffc.h"
#include "ffc_internal.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define LEAF 2          /* facets per leaf (2 measured fastest of 2, 4, 8) */
#define STACK 256

typedef float v4f __attribute__((vector_size(16))); /* four boxes at once (GCC, Clang) */
typedef int v4i __attribute__((vector_size(16)));       /* traversal stack (depth <= 64 levels, 2 per level) */

struct ffc_tree {
    int nn;            /* nodes per facet: 3 or 6 */
    long nf;           /* facets */
    long nv;           /* node positions expected by refit */
    long P;            /* leaves rounded up to a power of two */
    long *F;           /* [nf*nn] connectivity (original facet order) */
    long *slot2f;      /* [nf] tree slot -> facet */
    long *f2slot;      /* [nf] facet -> tree slot */
    double *hf;        /* [nf] longest edge of each facet, by facet (length) */
    unsigned char *degen; /* [nf] by slot: 1 for a linear facet ffc_project refuses (no area), which no
                             query takes */
    double *fx;        /* [nf*nn*3] facet node positions, tree order (length) */
    double *box;       /* [2P*6] node boxes lo[3], hi[3] (length) */
    float *qb;         /* [P/2*24] the traversal's boxes: at 24 i those of node i's four grandchildren
                          4i..4i+3, lo x, y, z then hi x, y, z, four values each, relative to qo in
                          units of qscale, widened (see fill_quad_boxes; NULL when P < 4) */
    int depth;         /* log2 P: the leaves' level (the root's is 0) */
    double qo[3];      /* qb's origin: the root box's centre (length) */
    double qscale;     /* the root box's largest half-width (length) */
    int qfast;         /* 1: qb usable (qscale between 1e-30 and 1e30) */
    long *nbr;         /* [nf*3] facet across edge e (vertices e, e+1), -1 on the rim */
    unsigned char *vrim; /* [nf*3] 1 when vertex a lies on the rim of the surface */
    double hmax;       /* longest facet edge (length) */
};

/* ------------------------------------------------------------ helpers */
static double facet_h(int nn, const double *X)
{
    (void)nn;
    return sqrt(ffc__facet_size2((const double(*)[3])X));
}

static void facet_box(int nn, const double *X, double b[6])
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

static double box_d2(const double b[6], const double p[3])
{
    double d2 = 0.0;
    for (int i = 0; i < 3; i++) {
        double d = p[i] < b[i] ? b[i] - p[i] : (p[i] > b[3 + i] ? p[i] - b[3 + i] : 0.0);
        d2 += d * d;
    }
    return d2;
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

/* A lower bound of the squared distance (length^2) from the float one d
 * (units of qscale^2): the float sums carry a relative error below 1e-6,
 * hence 1 - 1e-5, and near float underflow an absolute one below 1e-44,
 * hence 1e-38 */
static inline double lower_bound(const ffc_tree *t, float d)
{
    return ((double)d * (1.0 - 1e-5) - 1e-38) * t->qscale * t->qscale;
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
        for (long s = j * LEAF; s < (j + 1) * LEAF && s < t->nf; s++) {
            double fb[6];
            facet_box(nn, t->fx + s * nn * 3, fb);
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
    long L = (nf + LEAF - 1) / LEAF, P = 1;
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

/* ------------------------------------------------------------- queries */
/* Squared distance from p to the flat triangle (a, b, c) by its Voronoi
 * regions; *inside is 1 when the closest point is interior. */
static double tri_d2(const double *a, const double *b, const double *c, const double p[3],
                     int *inside)
{
    double ab[3], ac[3], ap[3], q[3];
    for (int i = 0; i < 3; i++) { ab[i] = b[i] - a[i]; ac[i] = c[i] - a[i]; ap[i] = p[i] - a[i]; }
    double d1 = ffc__dot(ab, ap), d2 = ffc__dot(ac, ap);
    *inside = 0;
    if (d1 <= 0 && d2 <= 0) { for (int i = 0; i < 3; i++) q[i] = a[i]; goto done; }
    double bp[3] = {p[0] - b[0], p[1] - b[1], p[2] - b[2]};
    double d3 = ffc__dot(ab, bp), d4 = ffc__dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) { for (int i = 0; i < 3; i++) q[i] = b[i]; goto done; }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        double v = d1 / (d1 - d3);
        for (int i = 0; i < 3; i++) q[i] = a[i] + v * ab[i];
        goto done;
    }
    double cp[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
    double d5 = ffc__dot(ab, cp), d6 = ffc__dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) { for (int i = 0; i < 3; i++) q[i] = c[i]; goto done; }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        double w = d2 / (d2 - d6);
        for (int i = 0; i < 3; i++) q[i] = a[i] + w * ac[i];
        goto done;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (int i = 0; i < 3; i++) q[i] = b[i] + w * (c[i] - b[i]);
        goto done;
    }
    {
        double den = 1.0 / (va + vb + vc), v = vb * den, w = vc * den;
        for (int i = 0; i < 3; i++) q[i] = a[i] + v * ab[i] + w * ac[i];
        *inside = 1;
    }
done:
    for (int i = 0; i < 3; i++) q[i] = p[i] - q[i];
    return ffc__dot(q, q);
}

/* Candidates and the rule that picks a partner among them: of the facets
 * within rmax, those whose squared distance is within the tie tolerance of
 * the smallest one (ties at shared edges and vertices, to round-off) form
 * the window; the answer is the window's facet with an interior foot, then
 * with the lower index.  The rule depends on the set of facets alone, not
 * on the order they are met in (a pairwise "closer, or as close and
 * better" is not transitive), so the traversal, the batches, the warm
 * start and brute force give the same answer.  The window keeps its TIES
 * smallest facets by (distance, index) (more facets tied to round-off at
 * one point than that: the TIES closest compete). */
enum { TIES = 16 };
typedef struct {
    long f, slot;    /* the answer (after cand_pick): facet and its tree slot, f = -1 for none */
    double d2;       /* its squared distance (length^2) */
    int inside;      /* its foot is interior */
    double rmax2;    /* squared search radius (length^2) */
    double dmin;     /* smallest squared distance met (length^2; INFINITY: none yet) */
    double lim2;     /* squared pruning radius: dmin plus the tie tolerance, at most rmax2 */
    int n;           /* facets in the window */
    struct { long f, slot; double d2; int inside; } w[TIES]; /* the window */
} cand_t;

static void cand_init(cand_t *c, double rmax)
{
    c->f = c->slot = -1;
    c->d2 = 0.0;
    c->inside = 0;
    c->rmax2 = rmax * rmax;
    c->dmin = INFINITY;
    c->lim2 = c->rmax2;
    c->n = 0;
}

/* tolerance of ties on squared distances: distances equal within
 * 1e-12 d + 1e-13 hmax (round-off of coordinates of size ~hmax) */
static double tie_tol2(const ffc_tree *t, double d2)
{
    double d = sqrt(d2), tol = 1e-12 * d + 1e-13 * t->hmax;
    return 2.0 * d * tol + tol * tol;
}

/* facet f (slot s) at squared distance d2 <= c->lim2 joins the window */
static void cand_add(const ffc_tree *t, cand_t *c, long f, long s, double d2, int inside)
{
    if (d2 < c->dmin) {
        c->dmin = d2;
        c->lim2 = fmin(c->rmax2, d2 + tie_tol2(t, d2));
        int k = 0;
        for (int j = 0; j < c->n; j++)
            if (c->w[j].d2 <= c->lim2) c->w[k++] = c->w[j];
        c->n = k;
    }
    int j = c->n;
    if (j == TIES) { /* full: the largest (distance, index) leaves, if larger than f's */
        j = 0;
        for (int k = 1; k < TIES; k++)
            if (c->w[k].d2 > c->w[j].d2 || (c->w[k].d2 == c->w[j].d2 && c->w[k].f > c->w[j].f)) j = k;
        if (c->w[j].d2 < d2 || (c->w[j].d2 == d2 && c->w[j].f < f)) return;
    } else
        c->n++;
    c->w[j].f = f;
    c->w[j].slot = s;
    c->w[j].d2 = d2;
    c->w[j].inside = inside;
}

/* the answer: the window's facet with an interior foot, then the lowest index */
static void cand_pick(cand_t *c)
{
    c->f = c->slot = -1;
    for (int j = 0; j < c->n; j++)
        if (c->f < 0 || (c->w[j].inside && !c->inside) || (c->w[j].inside == c->inside && c->w[j].f < c->f)) {
            c->f = c->w[j].f;
            c->slot = c->w[j].slot;
            c->d2 = c->w[j].d2;
            c->inside = c->w[j].inside;
        }
}

static void consider(const ffc_tree *t, long s, const double p[3], cand_t *best)
{
    double d2;
    int inside;
    const double *X = t->fx + s * t->nn * 3;
    if (t->nn == 3) {
        if (t->degen[s]) return;
        d2 = tri_d2(X, X + 3, X + 6, p, &inside);
    } else {
        ffc_proj pr;
        if (ffc_project(6, (const double(*)[3])X, p, &pr) < 0) return;
        d2 = pr.dist * pr.dist;
        inside = pr.where == FFC_FOOT_INSIDE;
    }
    if (!(d2 <= best->lim2)) return; /* (and NaN) */
    cand_add(t, best, t->slot2f[s], s, d2, inside);
}

/* the level of tree node i (the root, 1, is at 0) */
static int level(long i) { return 63 - __builtin_clzll((unsigned long long)i); }

/* Closest facet within rmax.  A warm start (a facet near the previous
 * query's partner, or -1) and its edge neighbours tighten the bound before
 * the traversal; the result does not depend on it. */
static void warm_start(const ffc_tree *t, const double p[3], double rmax, long warm, cand_t *best, long seen[4])
{
    cand_init(best, rmax);
    seen[0] = seen[1] = seen[2] = seen[3] = -1;
    if (warm >= 0) {
        seen[0] = t->f2slot[warm];
        for (int e = 0; e < 3; e++) {
            long g = t->nbr[warm * 3 + e];
            if (g >= 0) seen[e + 1] = t->f2slot[g];
        }
        for (int e = 0; e < 4; e++)
            if (seen[e] >= 0) consider(t, seen[e], p, best);
    }
}

/* the facets of leaf j but the warm start's */
static void consider_leaf(const ffc_tree *t, long j, const double p[3], cand_t *best, const long seen[4])
{
    for (long s = j * LEAF; s < (j + 1) * LEAF && s < t->nf; s++)
        if (s != seen[0] && s != seen[1] && s != seen[2] && s != seen[3]) consider(t, s, p, best);
}

/* the float distances (squared) of pf to four boxes lo[k][0..3], hi[k][0..3] */
static v4f dist4(const float *lo, const float *hi, long stride, const float pf[3])
{
    v4f d = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int k = 0; k < 3; k++) {
        v4f l, h;
        memcpy(&l, lo + k * stride, sizeof l);
        memcpy(&h, hi + k * stride, sizeof h);
        const v4f a = l - pf[k], c = pf[k] - h;
        const v4i ge = a > c;
        const v4f m = (v4f)(((v4i)a & ge) | ((v4i)c & ~ge)), e = (v4f)((v4i)m & (m > 0.0f));
        d += e * e;
    }
    return d;
}

/* p within the float boxes' range (see fill_quad_boxes), and p - qo in float */
static int quad_point(const ffc_tree *t, const double p[3], float pf[3])
{
    const double inv = t->qscale > 0.0 ? 1.0 / t->qscale : 0.0;
    for (int k = 0; k < 3; k++) pf[k] = (float)((p[k] - t->qo[k]) * inv);
    return t->qfast && fabs(p[0] - t->qo[0]) <= 2.0 * t->qscale && fabs(p[1] - t->qo[1]) <= 2.0 * t->qscale &&
           fabs(p[2] - t->qo[2]) <= 2.0 * t->qscale;
}

static void nearest(const ffc_tree *t, const double p[3], double rmax, long warm, cand_t *best)
{
    long seen[4]; /* the slots considered by the warm start */
    warm_start(t, p, rmax, warm, best, seen);
    /* stack of (node, squared box distance, a lower bound): each box is
     * measured once.  A node at an even number of levels above the leaves
     * tests its four grandchildren's float boxes at once (qb) when p is
     * within their range; the root, when that number is odd, tests its two
     * children's double boxes (so do all nodes when qb is not usable) */
    long stack[STACK];
    double sd2[STACK];
    int sp = 0;
    stack[sp] = 1;
    sd2[sp++] = box_d2(t->box + 6, p);
    float pf[3];
    const int quad = quad_point(t, p, pf);
    while (sp > 0) {
        --sp;
        const long i = stack[sp];
        const double lim = best->lim2;
        if (sd2[sp] > lim) continue;
        if (i >= t->P) {
            consider_leaf(t, i - t->P, p, best, seen);
            continue;
        }
        if (quad && i < t->P / 2 && !((t->depth - level(i)) & 1)) {
            const float *g = t->qb + 24 * i;
            const v4f d = dist4(g, g + 12, 4, pf);
            /* (lower_bound: back in length^2, below the exact distance) */
            long ord[4];
            double od[4];
            int no = 0;
            for (int j = 0; j < 4; j++) {
                const double dj = lower_bound(t, d[j]);
                if (dj > lim) continue;
                int k = no++;
                for (; k > 0 && od[k - 1] < dj; k--) { ord[k] = ord[k - 1]; od[k] = od[k - 1]; }
                ord[k] = 4 * i + j;
                od[k] = dj;
            }
            /* farthest pushed first: the nearest is visited first */
            for (int k = 0; k < no; k++) { stack[sp] = ord[k]; sd2[sp++] = od[k]; }
            continue;
        }
        const long l = 2 * i, r = l + 1;
        const double dl = box_d2(t->box + 6 * l, p), dr = box_d2(t->box + 6 * r, p);
        /* push the farther child first so that the nearer one is visited first */
        if (dl <= dr) {
            if (dr <= lim) { stack[sp] = r; sd2[sp++] = dr; }
            if (dl <= lim) { stack[sp] = l; sd2[sp++] = dl; }
        } else {
            if (dl <= lim) { stack[sp] = l; sd2[sp++] = dl; }
            if (dr <= lim) { stack[sp] = r; sd2[sp++] = dr; }
        }
    }
    cand_pick(best);
}

/* A batch of nearby query points shares one traversal: the leaves whose
 * boxes meet the points' bounding box widened by r0 are collected once, and
 * each point then tests only those (four float boxes at once).  A point
 * whose final pruning radius (sqrt lim2) is within r0 has every facet that
 * could beat its answer in a collected leaf, so its answer is the one the
 * traversal gives; any other point is searched alone. */
enum { BATCH = 16, BATCH_LEAVES = 512 };

typedef struct {
    long n;                          /* leaves collected (a multiple of 4, the rest empty boxes) */
    long leaf[BATCH_LEAVES];         /* leaf j (tree node P + j), -1 for an empty box */
    float lo[3][BATCH_LEAVES];       /* their float boxes (see fill_quad_boxes) */
    float hi[3][BATCH_LEAVES];
} batch_t;

/* The leaves whose boxes meet [rlo, rhi] into b: 1, or 0 when the region is
 * beyond the float boxes' range or meets more than BATCH_LEAVES leaves */
static int collect(const ffc_tree *t, const double rlo[3], const double rhi[3], batch_t *b)
{
    b->n = 0;
    if (!t->qfast) return 0;
    float flo[3], fhi[3];
    const double pad = 8.0 * FLT_EPSILON, inv = 1.0 / t->qscale;
    for (int k = 0; k < 3; k++) {
        if (!(fabs(rlo[k] - t->qo[k]) <= 2.0 * t->qscale && fabs(rhi[k] - t->qo[k]) <= 2.0 * t->qscale)) return 0;
        flo[k] = (float)((rlo[k] - t->qo[k]) * inv - pad);
        fhi[k] = (float)((rhi[k] - t->qo[k]) * inv + pad);
    }
    long stack[STACK];
    int sp = 0;
    const double *r = t->box + 6;
    if (r[0] <= rhi[0] && r[1] <= rhi[1] && r[2] <= rhi[2] && r[3] >= rlo[0] && r[4] >= rlo[1] && r[5] >= rlo[2])
        stack[sp++] = 1;
    while (sp > 0) {
        const long i = stack[--sp];
        if (i >= t->P) {
            if (b->n == BATCH_LEAVES) return 0;
            const float *g = t->qb + 24 * (i / 4);
            const long c = b->n++;
            b->leaf[c] = i - t->P;
            for (int k = 0; k < 3; k++) {
                b->lo[k][c] = g[4 * k + i % 4];
                b->hi[k][c] = g[12 + 4 * k + i % 4];
            }
            continue;
        }
        if (i < t->P / 2 && !((t->depth - level(i)) & 1)) {
            const float *g = t->qb + 24 * i;
            v4i in = {-1, -1, -1, -1};
            for (int k = 0; k < 3; k++) {
                v4f l, h;
                memcpy(&l, g + 4 * k, sizeof l);
                memcpy(&h, g + 12 + 4 * k, sizeof h);
                in &= (l <= fhi[k]) & (h >= flo[k]);
            }
            for (int j = 3; j >= 0; j--)
                if (in[j]) stack[sp++] = 4 * i + j;
            continue;
        }
        for (long c = 2 * i + 1; c >= 2 * i; c--) {
            const double *q = t->box + 6 * c;
            if (q[0] <= rhi[0] && q[1] <= rhi[1] && q[2] <= rhi[2] && q[3] >= rlo[0] && q[4] >= rlo[1] &&
                q[5] >= rlo[2])
                stack[sp++] = c;
        }
    }
    while (b->n % 4) { /* empty boxes up to a multiple of 4 */
        const long c = b->n++;
        b->leaf[c] = -1;
        for (int k = 0; k < 3; k++) { b->lo[k][c] = INFINITY; b->hi[k][c] = -INFINITY; }
    }
    return 1;
}

/* The closest facet of p among the collected leaves, after the warm
 * start: 1 when its pruning radius is within r0 (the answer), else 0 */
static int nearest_in(const ffc_tree *t, const batch_t *b, double r0, const double p[3], double rmax, long warm,
                      cand_t *best)
{
    long seen[4];
    warm_start(t, p, rmax, warm, best, seen);
    float pf[3];
    if (!quad_point(t, p, pf) || !(best->lim2 <= r0 * r0)) return 0;
    for (long c = 0; c < b->n; c += 4) {
        const v4f d = dist4(&b->lo[0][c], &b->hi[0][c], BATCH_LEAVES, pf);
        for (int j = 0; j < 4; j++)
            if (lower_bound(t, d[j]) <= best->lim2 && b->leaf[c + j] >= 0)
                consider_leaf(t, b->leaf[c + j], p, best, seen);
    }
    if (!(best->lim2 <= r0 * r0)) return 0;
    cand_pick(best);
    return 1;
}

/* full projection onto the chosen facet */
static int finish(const ffc_tree *t, const cand_t *c, const double p[3], ffc_proj *pr)
{
    return ffc_project(t->nn, (const double(*)[3])(t->fx + c->slot * t->nn * 3), p, pr);
}

int ffc_tree_nearest(const ffc_tree *t, const double p[3], double rmax,
                     long *facet, ffc_proj *pr)
{
    if (!t || !p || !facet || !pr) return FFC_ERR_NULL;
    if (!(rmax >= 0)) return FFC_ERR_VALUE;
    for (int i = 0; i < 3; i++)
        if (!isfinite(p[i])) return FFC_ERR_NONFINITE;
    cand_t best;
    nearest(t, p, rmax, -1, &best);
    *facet = best.f;
    if (best.f >= 0) {
        int st = finish(t, &best, p, pr);
        if (st < 0) return st;
    }
    return FFC_OK;
}

ffc_search_opts ffc_search_defaults(void)
{
    ffc_search_opts o = {2.0, 0.0, 1e-9};
    return o;
}

/* Turns the closest candidate into a link (or none): feet clamped onto
 * the rim of the master surface are outside its footprint, and points
 * farther than the capture distance of their partner get no link. */
static void make_link(const ffc_tree *t, const cand_t *c, const double p[3],
                      const ffc_search_opts *o, ffc_link *lk)
{
    lk->mf = -1;
    lk->where = FFC_FOOT_INSIDE;
    lk->xm[0] = lk->xm[1] = 0.0;
    lk->gap = 0.0;
    lk->n[0] = lk->n[1] = lk->n[2] = 0.0;
    if (c->f < 0) return;
    ffc_proj prv;
    if (finish(t, c, p, &prv) < 0) return;
    const ffc_proj *pr = &prv;
    lk->where = pr->where;
    if (pr->where != FFC_FOOT_INSIDE && ffc__outside(pr->xi_free) > o->edge_tol) {
        int rim = pr->where <= FFC_FOOT_EDGE2 ? t->nbr[c->f * 3 + pr->where - FFC_FOOT_EDGE0] < 0
                                              : t->vrim[c->f * 3 + pr->where - FFC_FOOT_VERTEX0];
        /* how far beyond the rim, in the facet's tangent plane: a point
         * that overshoots by less than its distance to the facet's plane
         * (depth or height) is at the rim, not past it (a node in a
         * symmetry plane, or on a slave surface flush with the master's
         * rim, projects slightly beyond the rim of a facet that the
         * deformation tilted; open points too: a cylinder's end flush
         * with a block's side, as slave, had its rim facets' points come
         * and go with each augmentation's search, 1,490 Newton iterations
         * against 220) */
        const double over2 = pr->dist * pr->dist - pr->gap * pr->gap;
        const double over = over2 > 0 ? sqrt(over2) : 0.0;
        if (rim && over > o->edge_tol * t->hf[c->f] + fabs(pr->gap)) return;
    }
    if (pr->dist > fmax(o->capture_abs, o->capture_rel * t->hf[c->f])) return;
    lk->mf = c->f;
    lk->xm[0] = pr->xi[0];
    lk->xm[1] = pr->xi[1];
    lk->gap = pr->gap;
    for (int i = 0; i < 3; i++) lk->n[i] = pr->n[i];
}

/* The links of a batch of nb points bp (links[bl[k]]), searched together
 * when *r0 > 0 (see collect); *warm and *r0 carried to the next batch.
 * Returns how many have a partner. */
static long query_batch(const ffc_tree *t, batch_t *B, long nb, const double bp[][3], const long bl[],
                        double rmax, const ffc_search_opts *o, ffc_link links[], long *warm, double *r0)
{
    int shared = 0;
    if (*r0 > 0.0 && B) {
        double rlo[3], rhi[3];
        for (int i = 0; i < 3; i++) {
            rlo[i] = rhi[i] = bp[0][i];
            for (long k = 1; k < nb; k++) {
                rlo[i] = fmin(rlo[i], bp[k][i]);
                rhi[i] = fmax(rhi[i], bp[k][i]);
            }
            rlo[i] -= *r0;
            rhi[i] += *r0;
        }
        shared = collect(t, rlo, rhi, B);
    }
    long found = 0;
    double rnext = 0.0;
    for (long k = 0; k < nb; k++) {
        cand_t best;
        if (!shared || !nearest_in(t, B, *r0, bp[k], rmax, *warm, &best)) nearest(t, bp[k], rmax, *warm, &best);
        if (best.f >= 0) {
            *warm = best.f;
            rnext = fmax(rnext, sqrt(best.lim2));
        }
        make_link(t, &best, bp[k], o, links + bl[k]);
        found += links[bl[k]].mf >= 0;
    }
    /* twice the largest pruning radius of this batch (measured fastest
     * of 1.5, 2 and 3, with 8, 16 and 32 points a batch) */
    *r0 = 2.0 * rnext;
    return found;
}

static int search_common(const ffc_tree *t, int nns, long nfs, const long Fs[], long nvs,
                         const double xs[], int qdeg, const ffc_search_opts *o, long cap,
                         ffc_link links[], int brute)
{
    if (!t || !Fs || !xs || !links) return FFC_ERR_NULL;
    if (nns != 3 && nns != 6) return FFC_ERR_NODES;
    if (nfs <= 0) return FFC_ERR_EMPTY;
    ffc_search_opts def = ffc_search_defaults();
    if (!o) o = &def;
    if (!(o->capture_rel >= 0) || !(o->capture_abs >= 0) || !(o->edge_tol >= 0) ||
        isinf(o->capture_rel) || isinf(o->capture_abs))
        return FFC_ERR_VALUE;
    double qxi[16][2], qw[16];
    int nq = ffc_quad(qdeg, 16, qxi, qw);
    if (nq < 0) return nq;
    if (cap < nfs * nq) return FFC_ERR_CAPACITY;
    for (long k = 0; k < nfs * nns; k++)
        if (Fs[k] < 0 || Fs[k] >= nvs) return FFC_ERR_INDEX;
    const double rmax = fmax(o->capture_abs, o->capture_rel * t->hmax);
    long found = 0, warm = -1, nb = 0;
    double bp[BATCH][3]; /* the batch's points, */
    long bl[BATCH];      /* and their links */
    double r0 = 0.0;     /* the batch radius (0: none yet) */
    batch_t *B = brute ? NULL : malloc(sizeof *B); /* (without it, one traversal per point) */
    for (long f = 0; f < nfs; f++) {
        double X[FFC_MAXNODES][3];
        for (int a = 0; a < nns; a++)
            for (int i = 0; i < 3; i++) {
                X[a][i] = xs[3 * Fs[f * nns + a] + i];
                if (!isfinite(X[a][i])) { free(B); return FFC_ERR_NONFINITE; }
            }
        for (int q = 0; q < nq; q++) {
            double N[FFC_MAXNODES], p[3] = {0, 0, 0};
            ffc_shape(nns, qxi[q], N, NULL);
            for (int a = 0; a < nns; a++)
                for (int i = 0; i < 3; i++) p[i] += N[a] * X[a][i];
            ffc_link *lk = links + f * nq + q;
            lk->sf = f;
            lk->q = q;
            lk->xs[0] = qxi[q][0];
            lk->xs[1] = qxi[q][1];
            if (brute) {
                cand_t best;
                cand_init(&best, rmax);
                /* every facet, no pruning */
                for (long s = 0; s < t->nf; s++) consider(t, s, p, &best);
                cand_pick(&best);
                make_link(t, &best, p, o, lk);
                found += lk->mf >= 0;
                continue;
            }
            memcpy(bp[nb], p, sizeof p);
            bl[nb++] = f * nq + q;
            if (nb < BATCH && !(f == nfs - 1 && q == nq - 1)) continue;
            found += query_batch(t, B, nb, (const double(*)[3])bp, bl, rmax, o, links, &warm, &r0);
            nb = 0;
        }
    }
    free(B);
    return found <= 2147483647L ? (int)found : FFC_ERR_SIZE;
}

int ffc_search_points(const ffc_tree *t, long np, const double p[],
                      const ffc_search_opts *o, ffc_link links[])
{
    if (!t || !p || !links) return FFC_ERR_NULL;
    if (np <= 0) return FFC_ERR_EMPTY;
    ffc_search_opts def = ffc_search_defaults();
    if (!o) o = &def;
    if (!(o->capture_rel >= 0) || !(o->capture_abs >= 0) || !(o->edge_tol >= 0) ||
        isinf(o->capture_rel) || isinf(o->capture_abs))
        return FFC_ERR_VALUE;
    const double rmax = fmax(o->capture_abs, o->capture_rel * t->hmax);
    for (long k = 0; k < 3 * np; k++)
        if (!isfinite(p[k])) return FFC_ERR_NONFINITE;
    long found = 0, warm = -1;
    long bl[BATCH];
    double r0 = 0.0;
    batch_t *B = malloc(sizeof *B); /* (without it, one traversal per point) */
    for (long k0 = 0; k0 < np; k0 += BATCH) {
        const long nb = np - k0 < BATCH ? np - k0 : BATCH;
        for (long k = 0; k < nb; k++) {
            ffc_link *lk = links + k0 + k;
            lk->sf = k0 + k;
            lk->q = 0;
            lk->xs[0] = lk->xs[1] = 0.0;
            bl[k] = k0 + k;
        }
        found += query_batch(t, B, nb, (const double(*)[3])(p + 3 * k0), bl, rmax, o, links, &warm, &r0);
    }
    free(B);
    return found <= 2147483647L ? (int)found : FFC_ERR_SIZE;
}

int ffc_search(const ffc_tree *t, int nns, long nfs, const long Fs[],
               long nvs, const double xs_nodes[], int qdeg,
               const ffc_search_opts *o, long cap, ffc_link links[])
{
    return search_common(t, nns, nfs, Fs, nvs, xs_nodes, qdeg, o, cap, links, 0);
}

int ffc_search_brute(const ffc_tree *t, int nns, long nfs, const long Fs[],
                     long nvs, const double xs_nodes[], int qdeg,
                     const ffc_search_opts *o, long cap, ffc_link links[])
{
    return search_common(t, nns, nfs, Fs, nvs, xs_nodes, qdeg, o, cap, links, 1);
}

/* Facets (tree slots) whose boxes overlap b[6], into out[cap]; returns
 * their count (may exceed cap: only cap are written). */
static long tree_overlap(const ffc_tree *t, const double b[6], long cap, long out[])
{
    long stack[STACK], n = 0;
    int sp = 0;
    stack[sp++] = 1;
    while (sp > 0) {
        const long i = stack[--sp];
        const double *c = t->box + 6 * i;
        if (c[0] > b[3] || c[1] > b[4] || c[2] > b[5] || c[3] < b[0] || c[4] < b[1] || c[5] < b[2]) continue;
        if (i >= t->P) {
            const long j = i - t->P;
            for (long s = j * LEAF; s < (j + 1) * LEAF && s < t->nf; s++) {
                const double *X = t->fx + s * t->nn * 3;
                double fb[6];
                facet_box(t->nn, X, fb);
                if (fb[0] > b[3] || fb[1] > b[4] || fb[2] > b[5] || fb[3] < b[0] || fb[4] < b[1] || fb[5] < b[2])
                    continue;
                if (n < cap) out[n] = s;
                n++;
            }
            continue;
        }
        stack[sp++] = 2 * i;
        stack[sp++] = 2 * i + 1;
    }
    return n;
}

static void facet_normal(const double X[3][3], double n[3])
{
    const double a[3] = {X[1][0] - X[0][0], X[1][1] - X[0][1], X[1][2] - X[0][2]};
    const double b[3] = {X[2][0] - X[0][0], X[2][1] - X[0][1], X[2][2] - X[0][2]};
    ffc__cross(a, b, n);
}

#define MORTAR_PTS 96   /* points of one segment: <= 4 triangles x 12 (degree 6) */
#define MORTAR_CAND 4096 /* master facets overlapping one slave facet's box */

int ffc_mortar_pairs(const ffc_tree *t, long nfs, const long Fs[], long nvs, const double x[],
                     const ffc_search_opts *o, long cap, long pairs[], long *need)
{
    long dummy;
    if (!need) need = &dummy;
    *need = 0;
    if (!t || !Fs || !x || (cap > 0 && !pairs)) return FFC_ERR_NULL;
    const int nn = t->nn; /* (3 or 6: ffc_tree_build) */
    if (nfs <= 0) return FFC_ERR_EMPTY;
    if (cap < 0 || t->nv > nvs) return FFC_ERR_SIZE;
    ffc_search_opts def = ffc_search_defaults();
    if (!o) o = &def;
    if (!(o->capture_rel >= 0) || !(o->capture_abs >= 0) || !(o->edge_tol >= 0) || isinf(o->capture_rel) ||
        isinf(o->capture_abs))
        return FFC_ERR_VALUE;
    for (long k = 0; k < nn * nfs; k++)
        if (Fs[k] < 0 || Fs[k] >= nvs) return FFC_ERR_INDEX;
    for (long k = 0; k < nn * t->nf; k++)
        if (t->F[k] < 0 || t->F[k] >= nvs) return FFC_ERR_INDEX;
    const double rmax = fmax(o->capture_abs, o->capture_rel * t->hmax);
    long n = 0, cand[MORTAR_CAND];
    double xi[MORTAR_PTS][2], w[MORTAR_PTS];
    for (long f = 0; f < nfs; f++) {
        double Xs[FFC_MAXNODES][3], ns[3], box[6]; /* (the segments: the vertex triangles) */
        for (int a = 0; a < nn; a++)
            for (int i = 0; i < 3; i++) {
                Xs[a][i] = x[3 * Fs[nn * f + a] + i];
                if (!isfinite(Xs[a][i])) return FFC_ERR_NONFINITE;
            }
        facet_normal(Xs, ns);
        facet_box(nn, &Xs[0][0], box);
        for (int i = 0; i < 3; i++) { box[i] -= rmax; box[3 + i] += rmax; }
        const long nc = tree_overlap(t, box, MORTAR_CAND, cand);
        if (nc > MORTAR_CAND) return FFC_ERR_SIZE;
        long nf = 0;
        int captured = 0;
        for (long c = 0; c < nc; c++) {
            const long mf = t->slot2f[cand[c]];
            double Xm[FFC_MAXNODES][3], nm[3];
            for (int a = 0; a < nn; a++)
                for (int i = 0; i < 3; i++) {
                    Xm[a][i] = x[3 * t->F[nn * mf + a] + i];
                    if (!isfinite(Xm[a][i])) return FFC_ERR_NONFINITE;
                }
            facet_normal(Xm, nm);
            if (!(ffc__dot(ns, nm) < 0)) continue; /* not facing */
            double cov;
            /* (degree 1: one point per segment triangle, enough for its centre) */
            const int np = ffc_mortar_segment(1, (const double(*)[3])Xs, (const double(*)[3])Xm, MORTAR_PTS, xi, w, 0,
                                              NULL, NULL, NULL, &cov);
            if (np < 0) return np;
            if (np == 0) continue;
            /* capture: the distance from the segment's centre to the master plane */
            double xc[2] = {0, 0}, ws = 0;
            for (int q = 0; q < np; q++) {
                xc[0] += w[q] * xi[q][0];
                xc[1] += w[q] * xi[q][1];
                ws += w[q];
            }
            xc[0] /= ws;
            xc[1] /= ws;
            double pc[3];
            for (int i = 0; i < 3; i++)
                pc[i] = Xs[0][i] + xc[0] * (Xs[1][i] - Xs[0][i]) + xc[1] * (Xs[2][i] - Xs[0][i]);
            ffc_proj pr;
            /* (the vertex triangle's plane: a capture decision, in closed form for 6-node facets too) */
            int st = ffc__project_free(3, (const double(*)[3])Xm, pc, &pr);
            if (st < 0) return st;
            /* a facet within the capture distance of one master facet takes all those it faces and
               overlaps: no facet is cut by the edge of the capture band (its dual basis would be
               that of a part, and move with it) */
            if (fabs(pr.gap) <= fmax(o->capture_abs, o->capture_rel * t->hf[mf])) captured = 1;
            if (n + nf < cap) {
                pairs[2 * (n + nf)] = f;
                pairs[2 * (n + nf) + 1] = mf;
            }
            nf++;
        }
        if (captured) n += nf;
    }
    *need = n;
    return n > cap ? FFC_ERR_CAPACITY : (n <= 2147483647L ? (int)n : FFC_ERR_SIZE);
}

int ffc_mortar_search(const ffc_tree *t, long nfs, const long Fs[], long nvs, const double x[], int qdeg,
                      const ffc_search_opts *o, long cap, ffc_link links[], long *need)
{
    long dummy;
    if (!need) need = &dummy;
    *need = 0;
    if (!t || !Fs || !x || (cap > 0 && !links)) return FFC_ERR_NULL;
    if (ffc_quad_size(qdeg) < 0) return FFC_ERR_QUAD;
    long np = 0;
    int st = ffc_mortar_pairs(t, nfs, Fs, nvs, x, o, 0, NULL, &np);
    if (st < 0 && st != FFC_ERR_CAPACITY) return st;
    long *pairs = malloc((size_t)(2 * np + 2) * sizeof *pairs);
    if (!pairs) return FFC_ERR_MEMORY;
    st = ffc_mortar_pairs(t, nfs, Fs, nvs, x, o, np, pairs, &np);
    if (st >= 0) st = ffc_mortar_links(t->nn, nfs, Fs, t->nf, t->F, nvs, x, qdeg, np, pairs, cap, links, need, 0, NULL, NULL);
    free(pairs);
    return st;
}
