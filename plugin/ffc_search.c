/* ffc_search.c: exact closest-facet queries on the tree by branch and bound, and slave-point links. */
#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_tree.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef float v4f __attribute__((vector_size(16))); /* four boxes at once (GCC, Clang) */
typedef int v4i __attribute__((vector_size(16)));   /* their comparisons' masks */

/* squared distance from p to the box b = lo[3], hi[3] */
static double box_d2(const double b[6], const double p[3])
{
    double d2 = 0.0;
    for (int i = 0; i < 3; i++) {
        double d = p[i] < b[i] ? b[i] - p[i] : (p[i] > b[3 + i] ? p[i] - b[3 + i] : 0.0);
        d2 += d * d;
    }
    return d2;
}

/* A lower bound of the squared distance (length^2) from the float one d
 * (units of qscale^2): the float sums carry a relative error below 1e-6,
 * hence 1 - 1e-5, and near float underflow an absolute one below 1e-44,
 * hence 1e-38 */
static inline double lower_bound(const ffc_tree *t, float d)
{
    return ((double)d * (1.0 - 1e-5) - 1e-38) * t->qscale * t->qscale;
}

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
/* Self-contact: the querying point's facet */
typedef struct {
    double X[9];     /* its corners (length) */
    double n[3];     /* its unit normal (1) */
    long f;          /* its index in the facet list */
} self_ex;
typedef struct {
    long f, slot;    /* the answer (after cand_pick): facet and its tree slot, f = -1 for none */
    double d2;       /* its squared distance (length^2) */
    int inside;      /* its foot is interior */
    double rmax2;    /* squared search radius (length^2) */
    double dmin;     /* smallest squared distance met (length^2; INFINITY: none yet) */
    double lim2;     /* squared pruning radius: dmin plus the tie tolerance, at most rmax2 */
    const self_ex *ex; /* self-contact: the querying point's facet (NULL: no exclusion; not reset by cand_init) */
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

/* Self-contact: facet slot s is no partner of the querying point when its
 * index is not above the point's facet's (each two facing facets are
 * linked once, from the one of lower index: one pass, as a pair of two
 * surfaces; two passes over-constrain the fold and their multipliers
 * never settle), when it shares a corner with the point's facet (the
 * same node: the same coordinates, as both come from one array), or when
 * its normal does not oppose the point's facet's (n . n_s >= 0: the
 * surface merely curves there). */
static int excluded(const ffc_tree *t, long s, const self_ex *ex)
{
    if (t->slot2f[s] <= ex->f) return 1;
    const double *X = t->fx + s * t->nn * 3, *E = ex->X;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            if (X[3 * a] == E[3 * b] && X[3 * a + 1] == E[3 * b + 1] && X[3 * a + 2] == E[3 * b + 2]) return 1;
    double n[3];
    ffc__tri_normal(X, X + 3, X + 6, n);
    return !(ffc__dot(n, ex->n) < 0);
}

static void consider(const ffc_tree *t, long s, const double p[3], cand_t *best)
{
    double d2;
    int inside;
    if (best->ex && excluded(t, s, best->ex)) return;
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
    for (long s = j * FFC__LEAF; s < (j + 1) * FFC__LEAF && s < t->nf; s++)
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
    long stack[FFC__STACK];
    double sd2[FFC__STACK];
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
    long stack[FFC__STACK];
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
    best.ex = NULL;
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
    ffc_search_opts o = {2.0, 0.0, 1e-9, 0};
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
                        const self_ex *bx, double rmax, const ffc_search_opts *o, ffc_link links[], long *warm,
                        double *r0)
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
        best.ex = bx ? &bx[k] : NULL;
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
    self_ex bx[BATCH];   /* self-contact: each point's facet */
    double r0 = 0.0;     /* the batch radius (0: none yet) */
    batch_t *B = brute ? NULL : malloc(sizeof *B); /* (without it, one traversal per point) */
    for (long f = 0; f < nfs; f++) {
        double X[FFC_MAXNODES][3];
        for (int a = 0; a < nns; a++)
            for (int i = 0; i < 3; i++) {
                X[a][i] = xs[3 * Fs[f * nns + a] + i];
                if (!isfinite(X[a][i])) { free(B); return FFC_ERR_NONFINITE; }
            }
        self_ex ex;      /* self-contact: facet f */
        if (o->self) {
            memcpy(ex.X, X, sizeof ex.X);  /* (its corners: the first three rows of X) */
            ffc__tri_normal(ex.X, ex.X + 3, ex.X + 6, ex.n);
            const double nn = sqrt(ffc__dot(ex.n, ex.n));
            for (int i = 0; i < 3; i++) ex.n[i] = nn > 0 ? ex.n[i] / nn : 0.0;
            ex.f = f;
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
                best.ex = o->self ? &ex : NULL;
                /* every facet, no pruning */
                for (long s = 0; s < t->nf; s++) consider(t, s, p, &best);
                cand_pick(&best);
                make_link(t, &best, p, o, lk);
                found += lk->mf >= 0;
                continue;
            }
            memcpy(bp[nb], p, sizeof p);
            if (o->self) bx[nb] = ex;
            bl[nb++] = f * nq + q;
            if (nb < BATCH && !(f == nfs - 1 && q == nq - 1)) continue;
            found += query_batch(t, B, nb, (const double(*)[3])bp, bl, o->self ? bx : NULL, rmax, o,
                                 links, &warm, &r0);
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
        found += query_batch(t, B, nb, (const double(*)[3])(p + 3 * k0), bl, NULL, rmax, o, links, &warm, &r0);
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
