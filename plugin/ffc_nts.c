/* ffc_nts.c: node-to-surface contact with Lagrange multipliers: slave
 * nodes, their master partners, the constraint rows of the saddle-point
 * system and the stick / slide / release transitions. */
#include "ffc.h"
#include "ffc_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* a contact node's foot outside its facet by at most this much in local
 * coordinates is still on it (1: round-off of a foot on a vertex or an
 * edge is about 1e-15 / h in them; a slide past an edge is far more) */
#define NTS_KEEP 1e-9

/* index of node v in the sorted nodes[nn] (-1 if absent) */
static long find_node(long nn, const ffc_nts_node nodes[], long v)
{
    long lo = 0, hi = nn - 1;
    while (lo <= hi) {
        const long mid = lo + (hi - lo) / 2;
        if (nodes[mid].node == v) return mid;
        if (nodes[mid].node < v) lo = mid + 1;
        else hi = mid - 1;
    }
    return -1;
}

static int law_check(const ffc_nts_law *law)
{
    if (!law) return FFC_ERR_NULL;
    if (!(law->nu_s >= 0) || !(law->nu_d >= 0) || !(law->nu_d <= law->nu_s) || isinf(law->nu_s) ||
        !(law->gtol >= 0) || !(law->ftol >= 0) || isinf(law->gtol) || law->max_flips < 1 ||
        !(law->scale > 0) || isinf(law->scale))
        return FFC_ERR_VALUE;
    return FFC_OK;
}

static int pair_check(const ffc_pair *pair)
{
    if (!pair || !pair->Fs || !pair->Fm || !pair->X || !pair->u) return FFC_ERR_NULL;
    if (pair->ns != 3 || pair->nm != 3) return FFC_ERR_NODES;
    if (pair->nfs <= 0 || pair->nfm <= 0 || pair->nv <= 0) return FFC_ERR_EMPTY;
    for (long k = 0; k < 3 * pair->nfs; k++)
        if (pair->Fs[k] < 0 || pair->Fs[k] >= pair->nv) return FFC_ERR_INDEX;
    for (long k = 0; k < 3 * pair->nfm; k++)
        if (pair->Fm[k] < 0 || pair->Fm[k] >= pair->nv) return FFC_ERR_INDEX;
    return FFC_OK;
}

long ffc_nts_nodes(const ffc_pair *pair, long cap, ffc_nts_node out[], long *need)
{
    int s = pair_check(pair);
    if (s) return s;
    if (!need || (cap > 0 && !out)) return FFC_ERR_NULL;
    const long m = 3 * pair->nfs;
    long *v = malloc((size_t)m * sizeof *v);
    if (!v) return FFC_ERR_MEMORY;
    memcpy(v, pair->Fs, (size_t)m * sizeof *v);
    qsort(v, (size_t)m, sizeof *v, ffc__cmp_long);
    long nn = 0;
    for (long k = 0; k < m; k++)
        if (k == 0 || v[k] != v[k - 1]) v[nn++] = v[k];
    *need = nn;
    if (cap < nn) {
        free(v);
        return FFC_ERR_CAPACITY;
    }
    for (long k = 0; k < nn; k++) {
        memset(&out[k], 0, sizeof out[k]);
        out[k].node = v[k];
        out[k].state = FFC_NTS_OPEN;
        out[k].mf = -1;
        out[k].mfprev = -1;
        out[k].tfix = 0;
        out[k].row = -1;
    }
    free(v);
    /* tributary areas: a third of each linear triangle to each vertex */
    for (long f = 0; f < pair->nfs; f++) {
        double X[3][3];
        for (int a = 0; a < 3; a++)
            for (int i = 0; i < 3; i++) {
                X[a][i] = pair->X[3 * pair->Fs[3 * f + a] + i];
                if (!isfinite(X[a][i])) return FFC_ERR_NONFINITE;
            }
        double e1[3], e2[3], c[3];
        for (int i = 0; i < 3; i++) {
            e1[i] = X[1][i] - X[0][i];
            e2[i] = X[2][i] - X[0][i];
        }
        ffc__cross(e1, e2, c);
        const double A = 0.5 * sqrt(ffc__dot(c, c));
        if (!(A > 0)) return FFC_ERR_DEGENERATE;
        for (int a = 0; a < 3; a++) out[find_node(nn, out, pair->Fs[3 * f + a])].area += A / 3.0;
    }
    return nn;
}

int ffc_nts_locate(const ffc_pair *pair, const ffc_nts_law *law, const ffc_search_opts *o,
                   int init, long nn, ffc_nts_node nodes[])
{
    int s = pair_check(pair);
    if (s) return s;
    if ((s = law_check(law))) return s;
    if (!nodes) return FFC_ERR_NULL;
    if (nn <= 0) return FFC_ERR_EMPTY;
    for (long k = 0; k < nn; k++)
        if (nodes[k].node < 0 || nodes[k].node >= pair->nv) return FFC_ERR_INDEX;
    const long nv = pair->nv;
    double *x = malloc((size_t)(3 * nv + 3 * nn) * sizeof *x);
    ffc_link *lk = malloc((size_t)nn * sizeof *lk);
    if (!x || !lk) {
        free(x);
        free(lk);
        return FFC_ERR_MEMORY;
    }
    double *p = x + 3 * nv;
    for (long i = 0; i < 3 * nv; i++) x[i] = pair->X[i] + pair->u[i];
    for (long k = 0; k < nn; k++)
        for (int i = 0; i < 3; i++) p[3 * k + i] = x[3 * nodes[k].node + i];
    ffc_tree *t = NULL;
    s = ffc_tree_build(3, pair->nfm, pair->Fm, nv, x, &t);
    if (s == FFC_OK) s = ffc_search_points(t, nn, p, o, lk);
    ffc_tree_free(t);
    if (s < 0) {
        free(x);
        free(lk);
        return s;
    }
    const double *up = pair->u_prev;
    for (long k = 0; k < nn; k++) {
        ffc_nts_node *d = &nodes[k];
        if (init) {
            d->mfprev = -1;
            d->frozen = 0;
        }
        const long mfold = d->mf;
        /* the node's facet kept: frozen; or a contact node the search left
         * without a partner at the rim of the master, past it in the
         * tangent plane by no more than its distance |g| to the facet's
         * plane (a node held in a symmetry plane that cuts the master: a
         * tilted facet puts its foot up to |g| past the rim, on either
         * side); or a contact node given another facet whose foot is still
         * on its own to round-off (NTS_KEEP: at a vertex or an edge the
         * facets share, which of them the search returns is round-off, and
         * their normals, the constraint's direction, differ) */
        const int rim = !init && d->state != FFC_NTS_OPEN && lk[k].mf < 0;
        const int moved = !init && d->state != FFC_NTS_OPEN && lk[k].mf >= 0 && lk[k].mf != mfold;
        if ((d->frozen || rim || moved) && mfold >= 0 && mfold < pair->nfm) {
            double Xm[3][3];
            ffc_proj pr;
            for (int a = 0; a < 3; a++)
                for (int i = 0; i < 3; i++) Xm[a][i] = x[3 * pair->Fm[3 * mfold + a] + i];
            if (ffc_project(3, (const double(*)[3])Xm, p + 3 * k, &pr) < 0) {
                free(x);
                free(lk);
                return FFC_ERR_DEGENERATE;
            }
            const double over2 = pr.dist * pr.dist - pr.gap * pr.gap;
            if (d->frozen || (rim && (!(over2 > 0) || sqrt(over2) <= fabs(pr.gap))) ||
                (moved && ffc__outside(pr.xi_free) <= NTS_KEEP)) {
                lk[k].mf = mfold;
                lk[k].xm[0] = pr.xi[0];
                lk[k].xm[1] = pr.xi[1];
                lk[k].gap = pr.gap;
                for (int i = 0; i < 3; i++) lk[k].n[i] = pr.n[i];
            } else if (moved) {
                if (lk[k].mf == d->mfprev) d->frozen = 1;   /* back to the facet before: keep it */
                d->mfprev = mfold;
            }
        }
        d->mf = lk[k].mf;
        d->gap = 0.0;
        memset(d->L, 0, sizeof d->L);
        memset(d->n, 0, sizeof d->n);
        memset(d->slip, 0, sizeof d->slip);
        if (d->mf >= 0) {
            d->L[0] = 1.0 - lk[k].xm[0] - lk[k].xm[1];
            d->L[1] = lk[k].xm[0];
            d->L[2] = lk[k].xm[1];
            d->gap = lk[k].gap;
            for (int i = 0; i < 3; i++) d->n[i] = lk[k].n[i];
            if (up) {
                /* relative motion over the master material point since u^n */
                double r[3];
                for (int i = 0; i < 3; i++) {
                    const long c = d->node;
                    r[i] = pair->u[3 * c + i] - up[3 * c + i];
                    for (int a = 0; a < 3; a++) {
                        const long m = pair->Fm[3 * d->mf + a];
                        r[i] -= d->L[a] * (pair->u[3 * m + i] - up[3 * m + i]);
                    }
                }
                const double rn = ffc__dot(r, d->n);
                for (int i = 0; i < 3; i++) d->slip[i] = r[i] - rn * d->n[i];
            }
        }
        if (init) {
            d->state = (d->mf >= 0 && d->gap <= law->gtol)
                           ? (law->nu_s > 0 ? FFC_NTS_STICK : FFC_NTS_SLIDE)
                           : FFC_NTS_OPEN;
            d->flips = 0;
            d->chatter = 0;
            d->row = -1;
            memset(d->dir, 0, sizeof d->dir);
        }
    }
    free(x);
    free(lk);
    return FFC_OK;
}

/* orthonormal tangent basis t1, t2 of the unit normal n */
static void tangent_basis(const double n[3], double t1[3], double t2[3])
{
    int k = 0;
    for (int i = 1; i < 3; i++)
        if (fabs(n[i]) < fabs(n[k])) k = i;
    double e[3] = {0, 0, 0};
    e[k] = 1.0;
    ffc__cross(e, n, t1);
    const double l = sqrt(ffc__dot(t1, t1));
    for (int i = 0; i < 3; i++) t1[i] /= l;
    ffc__cross(n, t1, t2);
}

/* Force directions w[r] of a node's rows (the columns of Bf): n, t1, t2
 * for a node in contact with friction (stick or slide), n alone without
 * friction or when both tangential directions are prescribed; with one
 * prescribed dof k (tfix = k + 1) t1 is e_k in the tangent plane (its row
 * is left out: the support carries that force) and t2 = n x t1.  Returns
 * the number of directions. */
static int force_dirs(const ffc_nts_law *law, const ffc_nts_node *d, const double n[3], double w[3][3])
{
    memcpy(w[0], n, sizeof w[0]);
    if (d->state == FFC_NTS_OPEN) return 0;
    if ((d->state == FFC_NTS_SLIDE && !(law->nu_d > 0)) || d->tfix == 4) return 1;
    if (d->tfix >= 1 && d->tfix <= 3) {
        const int k = d->tfix - 1;
        for (int i = 0; i < 3; i++) w[1][i] = (i == k) - n[k] * n[i];
        const double l = sqrt(ffc__dot(w[1], w[1]));
        for (int i = 0; i < 3; i++) w[1][i] /= l;
        ffc__cross(n, w[1], w[2]);
    } else {
        tangent_basis(n, w[1], w[2]);
    }
    return 3;
}

/* The sliding rows' point of linearization: p = m_t + s (length), the
 * tangential multiplier m_t = -F_t / scale of the last solve plus the slip
 * s since u^n, both in the tangent plane of n (along t2 alone when t1 is
 * prescribed, w the node's directions); mt = m_t, mu = max(F_n, 0) /
 * scale.  Returns |p|. */
static double slide_point(const ffc_nts_law *law, const ffc_nts_node *d, const double n[3],
                          const double w[3][3], double p[3], double mt[3], double *mu)
{
    const double fn = ffc__dot(d->f, n);
    for (int i = 0; i < 3; i++) mt[i] = -(d->f[i] - fn * n[i]) / law->scale;
    const double sn = ffc__dot(d->slip, n);
    for (int i = 0; i < 3; i++) p[i] = mt[i] + d->slip[i] - sn * n[i];
    if (d->tfix >= 1 && d->tfix <= 3) {
        const double a = ffc__dot(mt, w[2]), b = ffc__dot(p, w[2]);
        for (int i = 0; i < 3; i++) {
            mt[i] = a * w[2][i];
            p[i] = b * w[2][i];
        }
    }
    *mu = fmax(fn, 0.0) / law->scale;
    return sqrt(ffc__dot(p, p));
}

/* Formulation (sliding rows).  With multipliers m = (m_n, m_t) in the
 * basis (n, t1, t2) the force on the slave is F = -scale (m_n n + m_t),
 * and Coulomb's law in its projection form (c = scale) reads
 *   m_t = P(m_t + s),  P the projection onto the disc |m_t| <= nu_d mu,
 * mu = -m_n.  A sliding node is outside the disc: with p = m_t + s,
 *   Phi = m_t - nu_d mu p / |p| = 0.
 * Semi-smooth Newton at the last iterate (m_t, mu, s):
 *   dPhi = dm_t - nu_d ph dmu + M (dm_t + ds),
 *   M = -(nu_d mu I - mb ph^T) / |p|     (ph = p / |p|; 2 x 2 in the plane),
 * where mb, the last m_t projected onto the disc (mb = nu_d mu ph at the
 * solution, which gives M its exact value -nu_d mu (I - ph ph^T) / |p|),
 * keeps the iteration from diverging when m_t is far outside the disc
 * (the damped linearization of Hueber, Stadler and Wohlmuth).  Phi + dPhi
 * = 0 becomes the two rows
 *   M s + (I + M) m_t + nu_d ph m_n = M p - Phi = mb - nu_d mu ph,
 * with s = T (D u - D u^n): kinematic directions v_a = M^T t_a (entries of
 * B), right-hand side v_a . D u^n + t_a . (mb - nu_d mu ph), and the
 * multiplier block C_ab = delta_ab + t_a . M t_b, C_an = nu_d t_a . ph.
 * |p| below nu_d mu (a node the chattering guard kept sliding) is raised
 * to nu_d mu in M. */

/* The triplets of B and Bf (ffc_nts_rows): Bi, Bj, Bv, Fv[cap], nt of
 * them written (may exceed cap: only cap are) */
typedef struct {
    long cap, *Bi, *Bj;
    double *Bv, *Fv;
    long nt;
} trips_t;

static void put(trips_t *o, long i, long j, double bv, double fv)
{
    if (o->nt < o->cap) {
        o->Bi[o->nt] = i;
        o->Bj[o->nt] = j;
        o->Bv[o->nt] = bv;
        o->Fv[o->nt] = fv;
    }
    o->nt++;
}

/* A sliding node's rows (see the Formulation above): its direction
 * d->dir, the kinematic directions v[a], the multiplier block Cm[a] and
 * the right-hand sides' extra[a] of its tangent rows a (t1's left out
 * with skip1).  Returns 1, or 0 when p = 0 (the rows of a sticking node) */
static int slide_rows(const ffc_nts_law *law, ffc_nts_node *d, const double w[3][3], int skip1, double v[3][3],
                      double Cm[3][3], double extra[3])
{
    double p[3], mt[3], mu;
    const double pn = slide_point(law, d, d->n, w, p, mt, &mu);
    if (!(pn > 0)) return 0;
    const double bound = law->nu_d * mu, rho = fmax(pn, bound);
    const double mtn = sqrt(ffc__dot(mt, mt));
    const double shrink = mtn > bound ? bound / mtn : 1.0;
    double mb[3];
    for (int i = 0; i < 3; i++) {
        d->dir[i] = p[i] / pn;
        mb[i] = shrink * mt[i];
    }
    for (int a = 1 + skip1; a < 3; a++) {
        const double ta_mb = ffc__dot(w[a], mb);
        for (int i = 0; i < 3; i++) v[a][i] = -(bound * w[a][i] - d->dir[i] * ta_mb) / rho;
        for (int b = 1 + skip1; b < 3; b++) Cm[a][b] = (a == b) + ffc__dot(w[b], v[a]);
        Cm[a][0] = law->nu_d * ffc__dot(w[a], d->dir);
        extra[a] = ta_mb - bound * ffc__dot(w[a], d->dir);
    }
    return 1;
}

/* Row nr's entries on the dofs of a node and its master facet's nodes
 * (dofn[4], coef[4]): sc coef_a v in B, sc coef_a w in Bf; a prescribed
 * dof's moves into *rhs.  Returns how many were written. */
static long row_entries(const ffc_pair *pair, const double fixed[], double sc, const long dofn[4],
                        const double coef[4], const double v[3], const double w[3], long nr, double *rhs, trips_t *o)
{
    long used = 0;
    for (int a = 0; a < 4; a++)
        for (int i = 0; i < 3; i++) {
            const double bv = coef[a] * v[i], fv = coef[a] * w[i];
            if (bv == 0.0 && fv == 0.0) continue;
            const long j = 3 * dofn[a] + i;
            if (fixed && fixed[j] != 0) {
                *rhs -= bv * pair->u[j];
                continue;
            }
            put(o, nr, j, sc * bv, sc * fv);
            used++;
        }
    return used;
}

int ffc_nts_rows(const ffc_pair *pair, const ffc_nts_law *law, const double fixed[],
                 long nn, ffc_nts_node nodes[], long cap, long Bi[], long Bj[],
                 double Bv[], double Fv[], long ccap, double c[], long *ntrip, long *nrows)
{
    int s = pair_check(pair);
    if (s) return s;
    if ((s = law_check(law))) return s;
    if (!nodes || !ntrip || !nrows) return FFC_ERR_NULL;
    if (cap > 0 && (!Bi || !Bj || !Bv || !Fv)) return FFC_ERR_NULL;
    if (ccap > 0 && !c) return FFC_ERR_NULL;
    const double sc = law->scale;
    const long ndof = 3 * pair->nv;
    trips_t o = {cap, Bi, Bj, Bv, Fv, 0};
    long nr = 0;
    for (long k = 0; k < nn; k++) {
        ffc_nts_node *d = &nodes[k];
        d->row = -1;
        d->rmask = 0;
        if (d->state == FFC_NTS_OPEN || d->mf < 0) continue;
        if (d->node < 0 || d->node >= pair->nv || d->mf >= pair->nfm) return FFC_ERR_INDEX;
        long dofn[4];
        double coef[4];
        dofn[0] = d->node;
        coef[0] = 1.0;
        for (int a = 0; a < 3; a++) {
            dofn[a + 1] = pair->Fm[3 * d->mf + a];
            coef[a + 1] = -d->L[a];
        }
        memcpy(d->nr, d->n, sizeof d->nr);
        /* tangential dofs of the slave node held at zero (fixed > 0, |n_k|
         * < 0.9: e.g. a symmetry plane): those directions get no row (a
         * prescribed motion, fixed < 0, keeps its row: the master follows
         * it while the node sticks) */
        d->tfix = 0;
        for (int i = 0; fixed && i < 3; i++)
            if (fixed[3 * d->node + i] > 0 && fabs(d->n[i]) < 0.9) d->tfix = d->tfix ? 4 : i + 1;
        double v[3][3], w[3][3], Cm[3][3] = {{0}};
        const int nrow = force_dirs(law, d, d->n, w);
        const int skip1 = nrow == 3 && d->tfix >= 1 && d->tfix <= 3;
        memcpy(v, w, sizeof v);
        int sliding = 0;
        double extra[3] = {0, 0, 0};   /* t_a . (mb - nu_d mu ph) */
        if (nrow == 3 && d->state == FFC_NTS_SLIDE) sliding = slide_rows(law, d, w, skip1, v, Cm, extra);
        const long row0 = nr;
        const long ridx[3] = {row0, row0 + 1, row0 + 2 - skip1};   /* sliding rows' numbers */
        for (int r = 0; r < nrow; r++) {
            if (r > 0 && sliding && !(d->rmask & 1)) break;  /* no normal row: nothing to slide on */
            if (r == 1 && skip1) continue;                      /* t1 prescribed */
            /* right-hand side: the gap closes (normal row) or no tangential
             * motion since u^n (tangent rows; the sliding rows' M s^n) */
            double rhs = 0.0;
            const double *uref = (r > 0 && pair->u_prev) ? pair->u_prev : pair->u;
            for (int a = 0; a < 4; a++)
                for (int i = 0; i < 3; i++) rhs += coef[a] * v[r][i] * uref[3 * dofn[a] + i];
            if (r == 0) rhs -= d->gap;
            if (sliding) rhs += extra[r];
            long used = row_entries(pair, fixed, sc, dofn, coef, v[r], w[r], nr, &rhs, &o);
            if (sliding && r > 0) {
                /* the multiplier block: columns ndof + row of the node's
                 * normal and tangent multipliers */
                for (int b = 0; b < 3; b++) {
                    if (Cm[r][b] == 0.0 || (b == 1 && skip1)) continue;
                    put(&o, nr, ndof + ridx[b], sc * Cm[r][b], 0.0);
                }
                used++;
            }
            if (used == 0) continue;  /* wholly on Dirichlet dofs: nothing to enforce */
            if (nr < ccap) c[nr] = sc * rhs;
            if (d->row < 0) d->row = nr;
            d->rmask |= 1 << r;
            nr++;
        }
    }
    *ntrip = o.nt;
    *nrows = nr;
    return (o.nt > cap || nr > ccap) ? FFC_ERR_CAPACITY : FFC_OK;
}

/* tangential part ft = f - fn nr of a node's contact force; returns |ft| */
static double tangential_force(const ffc_nts_node *d, double ft[3])
{
    for (int i = 0; i < 3; i++) ft[i] = d->f[i] - d->fn * d->nr[i];
    return sqrt(ffc__dot(ft, ft));
}

long ffc_nts_nrows(long nn, const ffc_nts_node nodes[])
{
    if (!nodes && nn > 0) return FFC_ERR_NULL;
    long nr = 0;
    for (long k = 0; k < nn; k++) {
        if (nodes[k].row < 0) continue;
        long end = nodes[k].row;
        for (int b = 0; b < 3; b++) end += (nodes[k].rmask >> b) & 1;
        if (end > nr) nr = end;
    }
    return nr;
}

/* the nodes' forces from the multipliers m[nrows] of the rows built last;
 * *fmax_n the largest normal force, st->min_fn the smallest */
static int node_forces(const ffc_nts_law *law, long nrows, const double m[], long nn, ffc_nts_node nodes[],
                       ffc_nts_stats *st, double *fmax_n)
{
    *fmax_n = 0.0;
    int first = 1;
    for (long k = 0; k < nn; k++) {
        ffc_nts_node *d = &nodes[k];
        memset(d->f, 0, sizeof d->f);
        d->fn = 0.0;
        if (d->row < 0) continue;
        double w[3][3];
        const int nrow = force_dirs(law, d, d->nr, w);
        long r = d->row;
        for (int b = 0; b < nrow; b++) {
            if (!(d->rmask & (1 << b))) continue;
            if (r >= nrows) return FFC_ERR_SIZE;
            for (int i = 0; i < 3; i++) d->f[i] -= law->scale * m[r] * w[b][i];
            r++;
        }
        d->fn = ffc__dot(d->f, d->nr);
        *fmax_n = fmax(*fmax_n, d->fn);
        st->min_fn = first ? d->fn : fmin(st->min_fn, d->fn);
        first = 0;
    }
    return FFC_OK;
}

/* Node d's next state from its state, gap and forces (ft, ftn: its
 * tangential force; fmax_n: the largest normal force), its new sliding
 * direction into newdir (d->dir: unchanged); the largest sliding rows'
 * residual into *slide_res */
static int next_state(const ffc_nts_law *law, const ffc_nts_node *d, const double ft[3], double ftn, double fmax_n,
                      double newdir[3], ffc_nts_stats *st, double *slide_res)
{
    const int old = d->state;
    int next = old;
    if (old == FFC_NTS_OPEN) {
        /* a node that has changed state 2 max_flips times in this step
         * stays open (a release / re-contact cycle the least-index
         * rule cannot break: the geometry differs between the two
         * states); its penetration shows in min_gap_open */
        if (d->mf >= 0 && d->gap < -law->gtol && d->flips >= 2 * law->max_flips) st->locked++;
        else if (d->mf >= 0 && d->gap < -law->gtol) {
            /* a node arriving with tangential motion since u^n slides on
             * along it: sticking would pull it back to where it was at u^n */
            const double sn = sqrt(ffc__dot(d->slip, d->slip));
            next = law->nu_s > 0 && !(sn > 1e-9 * sqrt(d->area)) ? FFC_NTS_STICK : FFC_NTS_SLIDE;
            if (next == FFC_NTS_SLIDE && sn > 0)
                for (int i = 0; i < 3; i++) newdir[i] = d->slip[i] / sn;
        }
    } else if (d->mf < 0) {
        next = FFC_NTS_OPEN;       /* slid off the master surface */
    } else if (d->row >= 0 && d->fn < -law->ftol * fmax_n) {
        next = FFC_NTS_OPEN;       /* tension release */
    } else if (old == FFC_NTS_STICK && d->row >= 0) {
        /* past the cone by more than the solve's round-off: a node left
         * on the cone's edge by sliding and then held (no slip) sticks
         * with |F_t| = nu_s F_n to about 1e-11, and a test at 1e-12
         * sent it back and forth between stick and slide */
        if (ftn > law->nu_s * d->fn * (1 + 1e-9) && ftn > 0) {
            next = FFC_NTS_SLIDE;
            for (int i = 0; i < 3; i++) newdir[i] = -ft[i] / ftn;
        }
    } else if (old == FFC_NTS_SLIDE && law->nu_d > 0 && d->row >= 0) {
        /* the projection form at the new iterate: q = scale p =
         * -F_t + scale s; the node sticks when q is inside the disc
         * |q| <= nu_d F_n, else slides along q (the sliding rows'
         * residual |F_t + nu_d F_n q/|q|| measures how far the
         * Newton iterate is from Coulomb's law) */
        double p[3], mt[3], mu;
        double w[3][3];
        force_dirs(law, d, d->nr, w);
        const double pn = slide_point(law, d, d->nr, w, p, mt, &mu);
        if (!(pn > law->nu_d * mu) || pn == 0) next = FFC_NTS_STICK;
        else {
            double r[3];
            for (int i = 0; i < 3; i++) {
                newdir[i] = p[i] / pn;
                r[i] = ft[i] + law->nu_d * d->fn * newdir[i];
            }
            *slide_res = fmax(*slide_res, sqrt(ffc__dot(r, r)));
        }
    }
    return next;
}

int ffc_nts_update(const ffc_nts_law *law, long nrows, const double m[], long nn,
                   ffc_nts_node nodes[], ffc_nts_stats *st)
{
    int s = law_check(law);
    if (s) return s;
    if (!nodes || !st || (nrows > 0 && !m)) return FFC_ERR_NULL;
    for (long k = 0; k < nrows; k++)
        if (!isfinite(m[k])) return FFC_ERR_NONFINITE;
    memset(st, 0, sizeof *st);
    /* forces from the multipliers of the rows built last */
    double fmax_n;
    if ((s = node_forces(law, nrows, m, nn, nodes, st, &fmax_n))) return s;
    /* chattering guard: once a node has changed state max_flips times in
     * this step, one change per update, the first node in order (the
     * least-index rule, which ends for the P-matrix complementarity
     * problem of frictionless contact) */
    for (long k = 0; k < nn; k++) st->chatter += nodes[k].chatter;
    const int one_at_a_time = st->chatter > 0;
    int first_open = 1;
    double slide_res = 0.0;
    for (long k = 0; k < nn; k++) {
        ffc_nts_node *d = &nodes[k];
        const int old = d->state;
        double ft[3];
        const double ftn = tangential_force(d, ft);
        double newdir[3];
        memcpy(newdir, d->dir, sizeof newdir);
        int next = next_state(law, d, ft, ftn, fmax_n, newdir, st, &slide_res);
        if (next != old && one_at_a_time && st->changes > 0) {
            next = old;
            memcpy(newdir, d->dir, sizeof newdir);
        }
        if (next != old) {
            st->changes++;
            if (next == FFC_NTS_OPEN) st->released++;
            d->flips++;
            if (d->flips >= law->max_flips && !d->chatter) {
                d->chatter = 1;
                st->chatter++;
            }
        }
        if (next == FFC_NTS_SLIDE) {
            double dd[3] = {newdir[0] - d->dir[0], newdir[1] - d->dir[1], newdir[2] - d->dir[2]};
            if (old == FFC_NTS_SLIDE) st->max_ddir = fmax(st->max_ddir, sqrt(ffc__dot(dd, dd)));
            memcpy(d->dir, newdir, sizeof d->dir);
        }
        d->state = next;
        if (next == FFC_NTS_OPEN) {
            st->open++;
            if (d->mf >= 0) {
                st->min_gap_open = first_open ? d->gap : fmin(st->min_gap_open, d->gap);
                first_open = 0;
            }
        } else {
            if (next == FFC_NTS_STICK) st->stick++;
            else st->slide++;
            st->max_pen = fmax(st->max_pen, -d->gap);
            if (d->row >= 0 && d->fn > 0) st->max_ratio = fmax(st->max_ratio, ftn / d->fn);
            if (d->row >= 0) st->max_gap_err = fmax(st->max_gap_err, fabs(d->gap));
        }
        for (int i = 0; i < 3; i++) st->force[i] += d->f[i];
    }
    st->max_slide_res = fmax_n > 0 ? slide_res / fmax_n : slide_res;
    return FFC_OK;
}

int ffc_nts_points(long nv, const double X[], const double u[], long nn, const ffc_nts_node nodes[],
                   double P[], long *bad)
{
    if (!X || !u || !P || !bad || (nn > 0 && !nodes)) return FFC_ERR_NULL;
    *bad = -1;
    long active = 0;
    for (long k = 0; k < nn; k++) {
        const ffc_nts_node *d = &nodes[k];
        if (d->node < 0 || d->node >= nv) {
            *bad = k;
            return FFC_ERR_INDEX;
        }
        if (!(d->area > 0)) {
            *bad = k;
            return FFC_ERR_VALUE;
        }
        const int on = d->state != FFC_NTS_OPEN;
        double ft[3];
        tangential_force(d, ft);
        double *row = P + k * FFC_POINT_COLS;
        for (int i = 0; i < 3; i++) {
            row[FFC_PT_X + i] = X[3 * d->node + i] + u[3 * d->node + i];
            row[FFC_PT_TX + i] = ft[i] / d->area;
        }
        row[FFC_PT_GAP] = d->gap;
        row[FFC_PT_P] = on ? d->fn / d->area : 0.0;
        row[FFC_PT_ACTIVE] = on;
        row[FFC_PT_AREA] = d->area;
        row[FFC_PT_FACET] = (double)d->mf;
        row[FFC_PT_STATE] = d->state;
        row[FFC_PT_DISS] = fabs(ffc__dot(ft, d->slip)) / d->area;
        active += on;
    }
    return active <= 2147483647L ? (int)active : FFC_ERR_SIZE;
}
