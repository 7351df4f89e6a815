/* ffc_mass.c: mass redistribution for contact dynamics: the interpolation T
 * that moves the dofs of the contact surfaces with their neighbours off the
 * surfaces, so that M_red = T' M T carries no mass on them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"

/* the matrix's rows (duplicates kept): row i's entries ptr[i] .. ptr[i+1] */
typedef struct {
    long *ptr;   /* [n+1] row starts */
    long *col;   /* [nm] column of each entry */
    double *val; /* [nm] value of each entry */
} mass_rows;

/* a row's candidates: the dofs off the surfaces it takes, and their weights */
typedef struct {
    long *list;  /* [n] candidate dofs, cnt of them */
    double *acc; /* [n] weight of each dof (0 off the list) */
    long cnt;    /* candidates */
} mass_cand;

static void cand_add(mass_cand *c, long j, double w)
{
    if (c->acc[j] == 0) c->list[c->cnt++] = j;
    c->acc[j] += w;
}

static void cand_clear(mass_cand *c)
{
    for (long k = 0; k < c->cnt; k++) c->acc[c->list[k]] = 0;
    c->cnt = 0;
}

/* the breadth-first search's work arrays, n each */
typedef struct {
    long *stamp;    /* the search that last reached a dof (-1: none) */
    long *level;    /* the depth it was reached at */
    double *reach;  /* the share of the search's weight that reached it */
    long *front;    /* the dofs reached at the last depth */
    long *next;     /* those reached at this depth */
} mass_bfs;

/* The candidates of row i to the given depth: a breadth-first search over
 * M's graph from i (through dofs on the surfaces or not); the dofs off the
 * surfaces reached at depth d take as base weight 0.01^(d - 1) times the
 * share of the search that reached them, each step splitting a dof's share
 * as |M_jq| / sum_q |M_jq| (at depth 1: |M_iq|'s share, the neighbours'
 * own weights).  gen is this search's stamp. */
static void candidates(const mass_rows *r, const double rowabs[], const double spread[], long i, int depth, long gen,
                       mass_bfs *b, mass_cand *c)
{
    long nf = 1;
    b->front[0] = i;
    b->stamp[i] = gen;
    b->level[i] = 0;
    b->reach[i] = 1;
    double scale = 1;
    for (int d = 1; d <= depth && nf > 0; d++, scale *= 0.01) {
        long nn = 0;
        for (long f = 0; f < nf; f++) {
            long j = b->front[f];
            if (!(rowabs[j] > 0)) continue;
            for (long k = r->ptr[j]; k < r->ptr[j + 1]; k++) {
                long q = r->col[k];
                if (r->val[k] == 0 || q == i) continue;
                if (b->stamp[q] != gen) {
                    b->stamp[q] = gen;
                    b->level[q] = d;
                    b->reach[q] = 0;
                    b->next[nn++] = q;
                }
                if (b->level[q] != d) continue;
                double share = b->reach[j] * fabs(r->val[k]) / rowabs[j];
                b->reach[q] += share;
                if (spread[q] == 0) cand_add(c, q, scale * share);
            }
        }
        long *t = b->front;
        b->front = b->next;
        b->next = t;
        nf = nn;
    }
}

/* a_j = (1, (x_j - x_i) / L), with 0 for the coordinate skip (-1: none) */
static void affine_row(const double X[], long i, long j, double L, long skip, double a[4])
{
    a[0] = 1;
    for (int p = 0; p < 3; p++) a[p + 1] = p == skip ? 0 : (X[3 * j + p] - X[3 * i + p]) / L;
}

/* 1 + a . lam: the factor on a candidate's base weight (below) */
static double affine_factor(const double a[4], const double lam[4])
{
    return 1 + a[0] * lam[0] + a[1] * lam[1] + a[2] * lam[2] + a[3] * lam[3];
}

/* G = R' R (R upper, in place); 0 if a pivot is below 1e-8 of G's
 * largest diagonal */
static int factor4(double G[4][4])
{
    double gmax = 0;
    for (int p = 0; p < 4; p++)
        if (G[p][p] > gmax) gmax = G[p][p];
    for (int p = 0; p < 4; p++) {
        double d = G[p][p];
        for (int k = 0; k < p; k++) d -= G[k][p] * G[k][p];
        if (!(d > 1e-8 * gmax)) return 0;
        G[p][p] = sqrt(d);
        for (int q = p + 1; q < 4; q++) {
            double s = G[p][q];
            for (int k = 0; k < p; k++) s -= G[k][p] * G[k][q];
            G[p][q] = s / G[p][p];
        }
    }
    return 1;
}

/* R' R x = rhs, R from factor4 */
static void subst4(const double R[4][4], const double rhs[4], double x[4])
{
    for (int p = 0; p < 4; p++) {
        double s = rhs[p];
        for (int k = 0; k < p; k++) s -= R[k][p] * x[k];
        x[p] = s / R[p][p];
    }
    for (int p = 3; p >= 0; p--) {
        double s = x[p];
        for (int k = p + 1; k < 4; k++) s -= R[p][k] * x[k];
        x[p] = s / R[p][p];
    }
}

/* Formulation: the weights w closest to the base weights w0 (normalized to
 * sum 1) in sum_j (w_j - w0_j)^2 / w0_j that reproduce, at dof i, the
 * constant and the coordinates other than skip: sum_j w_j = 1 and sum_j
 * w_j (x_j - x_i)_p = 0 (p != skip).  With a_j = (1, (x_j - x_i) / L) (L
 * the candidates' largest distance, for scale; 0 in the skipped
 * coordinate), stationarity gives w_j = w0_j (1 + a_j . lam) and G lam =
 * (0, -d), G = sum_j w0_j a_j a_j' (4 x 4; the identity in the skipped row
 * and column), d = sum_j w0_j (x_j - x_i) / L.  A Cholesky pivot below
 * 1e-8 of G's largest diagonal (candidates on a plane or a line) or a
 * weight of magnitude over 8 (a nearly flat set: a wild extrapolation)
 * refuses the row.  Returns 1 with the weights in c->acc; 0 leaves the
 * normalized base weights there (X NULL: always). */
static int affine_weights(const double X[], long skip, long i, mass_cand *c)
{
    double sum = 0, L = 0;
    for (long k = 0; k < c->cnt; k++) sum += c->acc[c->list[k]];
    for (long k = 0; k < c->cnt; k++) c->acc[c->list[k]] /= sum;
    if (!X) return 0;
    for (long k = 0; k < c->cnt; k++) {
        long j = c->list[k];
        double a[4];
        affine_row(X, i, j, 1, skip, a);
        L = fmax(L, sqrt(a[1] * a[1] + a[2] * a[2] + a[3] * a[3]));
    }
    if (!(L > 0)) return 0;
    double G[4][4] = {{0}}, rhs[4] = {0}, lam[4];
    for (long k = 0; k < c->cnt; k++) {
        long j = c->list[k];
        double a[4];
        affine_row(X, i, j, L, skip, a);
        for (int p = 0; p < 4; p++) {
            for (int q = 0; q < 4; q++) G[p][q] += c->acc[j] * a[p] * a[q];
            if (p > 0) rhs[p] -= c->acc[j] * a[p];
        }
    }
    if (skip >= 0) G[skip + 1][skip + 1] = 1;   /* (its row and column are zero: lam there is 0) */
    double R[4][4], res[4] = {1, 0, 0, 0}, mu[4];
    memcpy(R, G, sizeof R);
    if (!factor4(R)) return 0;
    subst4(R, rhs, lam);
    /* one step of refinement on the weights themselves (G may be
     * ill-conditioned, and 1 + a_j . lam may cancel): the constraints'
     * residual with w_j = w0_j (1 + a_j . lam), corrected by w0_j a_j . mu */
    for (long k = 0; k < c->cnt; k++) {
        long j = c->list[k];
        double a[4];
        affine_row(X, i, j, L, skip, a);
        double wj = c->acc[j] * affine_factor(a, lam);
        for (int p = 0; p < 4; p++) res[p] -= wj * a[p];
    }
    subst4(R, res, mu);
    for (long k = 0; k < c->cnt; k++) {
        long j = c->list[k];
        double a[4];
        affine_row(X, i, j, L, skip, a);
        if (!(fabs(c->acc[j] * affine_factor(a, lam) + c->acc[j] * (affine_factor(a, mu) - 1)) <= 8)) return 0;
    }
    for (long k = 0; k < c->cnt; k++) {
        long j = c->list[k];
        double a[4];
        affine_row(X, i, j, L, skip, a);
        c->acc[j] = c->acc[j] * affine_factor(a, lam) + c->acc[j] * (affine_factor(a, mu) - 1);
    }
    return 1;
}

static int rows_make(long n, long nm, const long Mi[], const long Mj[], const double Mv[], mass_rows *r)
{
    r->ptr = calloc((size_t)n + 1, sizeof *r->ptr);
    r->col = malloc((size_t)(nm > 0 ? nm : 1) * sizeof *r->col);
    r->val = malloc((size_t)(nm > 0 ? nm : 1) * sizeof *r->val);
    if (!r->ptr || !r->col || !r->val) return FFC_ERR_MEMORY;
    for (long k = 0; k < nm; k++) r->ptr[Mi[k] + 1]++;
    for (long i = 0; i < n; i++) r->ptr[i + 1] += r->ptr[i];
    long *at = malloc((size_t)n * sizeof *at);
    if (!at) return FFC_ERR_MEMORY;
    for (long i = 0; i < n; i++) at[i] = r->ptr[i];
    for (long k = 0; k < nm; k++) {
        r->col[at[Mi[k]]] = Mj[k];
        r->val[at[Mi[k]]++] = Mv[k];
    }
    free(at);
    return FFC_OK;
}

static int check_input(long n, long nm, const long Mi[], const long Mj[], const double Mv[], const double X[],
                       const long comp[], const double spread[])
{
    if (n <= 0 || nm < 0) return FFC_ERR_SIZE;
    for (long k = 0; k < nm; k++) {
        if (Mi[k] < 0 || Mi[k] >= n || Mj[k] < 0 || Mj[k] >= n) return FFC_ERR_INDEX;
        if (!isfinite(Mv[k])) return FFC_ERR_NONFINITE;
    }
    for (long i = 0; i < n; i++)
        if (comp && (comp[i] < -1 || comp[i] > 2)) return FFC_ERR_VALUE;
    for (long i = 0; i < n; i++)
        if (!isfinite(spread[i]) || (X && (!isfinite(X[3 * i]) || !isfinite(X[3 * i + 1]) || !isfinite(X[3 * i + 2]))))
            return FFC_ERR_NONFINITE;
    return FFC_OK;
}

/* Formulation: the kinetic energy of the redistributed mass is that of the
 * interpolated velocity, 1/2 (T v)' M (T v).  Row i of T is e_i off the
 * surfaces; on them it holds weights over the dofs off the surfaces that
 * sum to 1 (a translation is kept: the total mass and the linear momentum
 * of M) and, with the dofs' positions X, reproduce the coordinates too.  A
 * rigid motion a + w x x has in component c an affine function of the two
 * other coordinates: reproducing those at a dof of component c (comp[i])
 * gives T v = v for every rigid motion, so the centre of mass and the
 * inertia tensor of M are kept; the dof's own coordinate, the normal one
 * of a flat face's normal velocity, is then left free, and the weights
 * stay the neighbours' mean where no turn asks for more.  The candidates
 * are the dofs off the surfaces that M couples to i (base weights |M_ij|:
 * the consistent P2 mass has negative entries); where they cannot
 * reproduce those fields, the dofs reached in two or three steps over M's
 * graph too (candidates()).  T only maps surface rows to identity rows, so
 * T T = T, and M_red's rows and columns of the surface dofs are zero. */
int ffc_mass_spread(long n, long nm, const long Mi[], const long Mj[], const double Mv[], const double X[],
                    const long comp[], const double spread[], long cap, long Ti[], long Tj[], double Tv[], long *nt, long *kept,
                    long *inexact)
{
    if (!spread || !nt || !kept || !inexact || (nm > 0 && (!Mi || !Mj || !Mv)) || (cap > 0 && (!Ti || !Tj || !Tv)))
        return FFC_ERR_NULL;
    if (cap < 0) return FFC_ERR_SIZE;
    int st = check_input(n, nm, Mi, Mj, Mv, X, comp, spread);
    if (st) return st;
    mass_rows r = {NULL, NULL, NULL};
    mass_cand c = {malloc((size_t)n * sizeof(long)), calloc((size_t)n, sizeof(double)), 0};
    mass_bfs b = {malloc((size_t)n * sizeof(long)), malloc((size_t)n * sizeof(long)), malloc((size_t)n * sizeof(double)),
                  malloc((size_t)n * sizeof(long)), malloc((size_t)n * sizeof(long))};
    double *rowabs = calloc((size_t)n, sizeof(double));
    st = rows_make(n, nm, Mi, Mj, Mv, &r);
    if (!st && (!c.list || !c.acc || !b.stamp || !b.level || !b.reach || !b.front || !b.next || !rowabs))
        st = FFC_ERR_MEMORY;
    if (!st)
        for (long i = 0; i < n; i++) {
            b.stamp[i] = -1;
            for (long k = r.ptr[i]; k < r.ptr[i + 1]; k++) rowabs[i] += fabs(r.val[k]);
        }
    long t = 0, keep = 0, loose = 0, gen = 0;
    for (long i = 0; i < n && !st; i++) {
        if (spread[i] != 0) {
            /* the neighbours' own, then farther dofs where they do not span space */
            int exact = 0;
            for (int depth = 1; depth <= (X ? 3 : 1) && !exact; depth++) {
                cand_clear(&c);
                candidates(&r, rowabs, spread, i, depth, gen++, &b, &c);
                exact = c.cnt > 0 && affine_weights(X, comp ? comp[i] : -1, i, &c);
            }
            if (X && !exact) {                  /* none did: the neighbours' mean, if any */
                cand_clear(&c);
                candidates(&r, rowabs, spread, i, 1, gen++, &b, &c);
                if (c.cnt == 0) candidates(&r, rowabs, spread, i, 3, gen++, &b, &c);
                if (c.cnt > 0) affine_weights(NULL, -1, i, &c);
            }
            if (c.cnt > 0) {
                loose += X && !exact;
                for (long k = 0; k < c.cnt; k++, t++)
                    if (t < cap) {
                        Ti[t] = i;
                        Tj[t] = c.list[k];
                        Tv[t] = c.acc[c.list[k]];
                    }
                cand_clear(&c);
                continue;
            }
            keep++;
        }
        if (t < cap) {
            Ti[t] = i;
            Tj[t] = i;
            Tv[t] = 1.0;
        }
        t++;
    }
    free(r.ptr);
    free(r.col);
    free(r.val);
    free(c.list);
    free(c.acc);
    free(b.stamp);
    free(b.level);
    free(b.reach);
    free(b.front);
    free(b.next);
    free(rowabs);
    if (st) return st;
    *nt = t;
    *kept = keep;
    *inexact = loose;
    return t > cap ? FFC_ERR_CAPACITY : FFC_OK;
}
