/* ffc_nts.c: node-to-surface contact with Lagrange multipliers: slave
 * nodes, their master partners, the constraint rows of the saddle-point
 * system and the stick / slide / release transitions. */
#include "ffc.h"
#include "ffc_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_long(const void *a, const void *b)
{
    const long x = *(const long *)a, y = *(const long *)b;
    return (x > y) - (x < y);
}

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
    qsort(v, (size_t)m, sizeof *v, cmp_long);
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

/* Directions of a node's rows: v[r] the constraint direction, w[r] the
 * force direction; returns the number of rows: 3 stick (n, t1, t2);
 * slide with friction 2: n with the force direction n - nu_d d (the
 * friction nu_d F_n against the sliding direction d), and the lateral
 * direction e = n x d (no motion across d: its multiplier is the lateral
 * friction the update turns d with); frictionless slide 1 (n). */
static int row_dirs(const ffc_nts_law *law, const ffc_nts_node *d, const double n[3],
                    double v[3][3], double w[3][3])
{
    memcpy(v[0], n, sizeof v[0]);
    memcpy(w[0], n, sizeof w[0]);
    if (d->state == FFC_NTS_STICK) {
        tangent_basis(n, v[1], v[2]);
        memcpy(w[1], v[1], sizeof w[1]);
        memcpy(w[2], v[2], sizeof w[2]);
        return 3;
    }
    if (d->state != FFC_NTS_SLIDE || !(law->nu_d > 0)) return 1;
    /* the sliding direction in the tangent plane of n */
    double t[3];
    const double dn = ffc__dot(d->dir, n);
    for (int i = 0; i < 3; i++) t[i] = d->dir[i] - dn * n[i];
    const double l = sqrt(ffc__dot(t, t));
    if (!(l > 1e-8)) return 1;
    for (int i = 0; i < 3; i++) {
        t[i] /= l;
        w[0][i] -= law->nu_d * t[i];
    }
    ffc__cross(n, t, v[1]);
    memcpy(w[1], v[1], sizeof w[1]);
    return 2;
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
    long nt = 0, nr = 0;
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
        double v[3][3], w[3][3];
        const int nrow = row_dirs(law, d, d->n, v, w);
        for (int r = 0; r < nrow; r++) {
            /* right-hand side: the gap closes (normal row) or no tangential
             * motion since u^n (tangent rows) */
            double rhs = 0.0;
            const double *uref = (r > 0 && pair->u_prev) ? pair->u_prev : pair->u;
            for (int a = 0; a < 4; a++)
                for (int i = 0; i < 3; i++) rhs += coef[a] * v[r][i] * uref[3 * dofn[a] + i];
            if (r == 0) rhs -= d->gap;
            long used = 0;
            for (int a = 0; a < 4; a++)
                for (int i = 0; i < 3; i++) {
                    const double bv = coef[a] * v[r][i], fv = coef[a] * w[r][i];
                    if (bv == 0.0 && fv == 0.0) continue;
                    const long j = 3 * dofn[a] + i;
                    if (fixed && fixed[j] != 0) {
                        rhs -= bv * pair->u[j];
                        continue;
                    }
                    if (nt < cap) {
                        Bi[nt] = nr;
                        Bj[nt] = j;
                        Bv[nt] = sc * bv;
                        Fv[nt] = sc * fv;
                    }
                    nt++;
                    used++;
                }
            if (used == 0) continue;  /* wholly on Dirichlet dofs: nothing to enforce */
            if (nr < ccap) c[nr] = sc * rhs;
            if (d->row < 0) d->row = nr;
            d->rmask |= 1 << r;
            nr++;
        }
    }
    *ntrip = nt;
    *nrows = nr;
    return (nt > cap || nr > ccap) ? FFC_ERR_CAPACITY : FFC_OK;
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
    double fmax_n = 0.0;
    int first = 1;
    for (long k = 0; k < nn; k++) {
        ffc_nts_node *d = &nodes[k];
        memset(d->f, 0, sizeof d->f);
        d->fn = 0.0;
        if (d->row < 0) continue;
        double v[3][3], w[3][3];
        const int nrow = row_dirs(law, d, d->nr, v, w);
        long r = d->row;
        for (int b = 0; b < nrow; b++) {
            if (!(d->rmask & (1 << b))) continue;
            if (r >= nrows) return FFC_ERR_SIZE;
            for (int i = 0; i < 3; i++) d->f[i] -= law->scale * m[r] * w[b][i];
            r++;
        }
        d->fn = ffc__dot(d->f, d->nr);
        fmax_n = fmax(fmax_n, d->fn);
        st->min_fn = first ? d->fn : fmin(st->min_fn, d->fn);
        first = 0;
    }
    /* chattering guard: once a node has changed state max_flips times in
     * this step, one change per update, the first node in order (the
     * least-index rule, which ends for the P-matrix complementarity
     * problem of frictionless contact) */
    for (long k = 0; k < nn; k++) st->chatter += nodes[k].chatter;
    const int one_at_a_time = st->chatter > 0;
    int first_open = 1;
    for (long k = 0; k < nn; k++) {
        ffc_nts_node *d = &nodes[k];
        const int old = d->state;
        double ft[3];
        const double ftn = tangential_force(d, ft);
        int next = old;
        double newdir[3];
        memcpy(newdir, d->dir, sizeof newdir);
        if (old == FFC_NTS_OPEN) {
            if (d->mf >= 0 && d->gap < -law->gtol) {
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
            if (ftn > law->nu_s * d->fn * (1 + 1e-12) && ftn > 0) {
                next = FFC_NTS_SLIDE;
                for (int i = 0; i < 3; i++) newdir[i] = -ft[i] / ftn;
            }
        } else if (old == FFC_NTS_SLIDE && law->nu_s > 0 && d->row >= 0) {
            /* q = nu_d F_n d - f_lat e + c s: the sliding traction pushed on
             * by the slip s along d and turned by the lateral reaction; the
             * node sticks when |q| falls to the bound (a slip reversed by up
             * to 2 nu_d F_n / c) or q turns against d (the stick force then
             * gives the new direction), else slides along q */
            double q[3];
            for (int i = 0; i < 3; i++) q[i] = -ft[i] + law->scale * d->slip[i];
            const double qn = sqrt(ffc__dot(q, q));
            if (!(qn > law->nu_d * d->fn) || qn == 0 || ffc__dot(q, d->dir) <= 0) next = FFC_NTS_STICK;
            else
                for (int i = 0; i < 3; i++) newdir[i] = q[i] / qn;
        }
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
            row[i] = X[3 * d->node + i] + u[3 * d->node + i];
            row[8 + i] = ft[i] / d->area;
        }
        row[3] = d->gap;
        row[4] = on ? d->fn / d->area : 0.0;
        row[5] = on;
        row[6] = d->area;
        row[7] = (double)d->mf;
        row[11] = d->state;
        row[12] = fabs(ffc__dot(ft, d->slip)) / d->area;
        active += on;
    }
    return active <= 2147483647L ? (int)active : FFC_ERR_SIZE;
}
