/* ffc_bulk.c: the bulk stiffness K of a small-strain scene, its
 * Dirichlet rows, and the factorization of K' + S on a linear engine
 * (CHOLMOD, or parallel MUMPS) with the single back-solves. */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ffc_bulk_state.h"
#include "ffc_internal.h"

int ffc__bulk_all(const ffc__bulk *b, int ok)
{
    return b->eng->op->agree(b->eng, ok);
}

int ffc__bulk_agree(const ffc__bulk *b, int st)
{
    return ffc__bulk_all(b, st == FFC_OK) ? FFC_OK : st ? st : FFC_ERR_MEMORY;
}

double ffc__seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* the factor and the compliance dropped */
static void bulk_free_factor(ffc__bulk *b)
{
    if (b->eng) b->eng->op->release(b->eng);
    b->prev = 0;
    b->factored = 0;
    b->m = 0;
}

void ffc__bulk_free(ffc__bulk *b)
{
    if (!b) return;
    bulk_free_factor(b);
    if (b->eng) b->eng->op->free(b->eng);
    ffc__pdense_free(b->pd);
    free(b->Ti); free(b->Tj); free(b->Tv); free(b->diag); free(b->big); free(b->sh); free(b->lift);
    free(b->dof); free(b->G); free(b->pos); free(b->nd); free(b->A); free(b->piv);
    free(b->rv); free(b->ri);
    free(b->xc); free(b->w); free(b->r); free(b->dx); free(b->t); free(b->kv);
    free(b->Gc); free(b->ti); free(b->tj); free(b->tv); free(b->Mw); free(b->Gw);
    free(b->rows); free(b->rpos); free(b->H); free(b->bprev); free(b->xprev);
    free(b->kdof); free(b->klu); free(b->kpiv); free(b->gv); free(b->rk.count);
    free(b);
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int ffc__bulk_create(long n, long nt, const long Ti[], const long Tj[], const double Tv[], long mmax,
                     ffc__bulk **out, long *bad)
{
    if (!out) return FFC_ERR_NULL;
    *out = NULL;
    if (nt > 0 && (!Ti || !Tj || !Tv)) return FFC_ERR_NULL;
    if (n <= 0 || nt < 0 || mmax < 0 || n > 2147483647L) return FFC_ERR_SIZE;
    const int st = ffc__check_triplets(n, nt, Ti, Tj, Tv, bad);
    if (st) return st;
    ffc__bulk *b = calloc(1, sizeof *b);
    if (!b) return FFC_ERR_MEMORY;
    b->n = n;
    b->nt = nt;
    b->mmax = mmax;
    b->rk.size = 1;
    const size_t nn = (size_t)n, nz = (size_t)(nt > 0 ? nt : 1);
    b->Ti = malloc(nz * sizeof(long));
    b->Tj = malloc(nz * sizeof(long));
    b->Tv = malloc(nz * sizeof(double));
    b->diag = calloc(nn, sizeof(double));
    b->big = calloc(nn, 1);
    b->sh = calloc(nn, sizeof(double));
    b->pos = malloc(nn * sizeof(long));
    b->nd = malloc(nn * sizeof(long));
    b->w = malloc(nn * sizeof(double));
    b->r = malloc(nn * sizeof(double));
    b->dx = malloc(nn * sizeof(double));
    b->t = malloc(nn * sizeof(double));
    b->rk.count = malloc(sizeof(long));
    double *d = malloc(nn * sizeof(double));
    if (!b->Ti || !b->Tj || !b->Tv || !b->diag || !b->big || !b->sh || !b->pos || !b->nd || !b->w || !b->r ||
        !b->dx || !b->t || !b->rk.count || !d || ffc__cholmod_create(&b->info, &b->rk, &b->eng)) {
        free(d);
        ffc__bulk_free(b);
        return FFC_ERR_MEMORY;
    }
    if (nt > 0) {
        memcpy(b->Ti, Ti, (size_t)nt * sizeof(long));
        memcpy(b->Tj, Tj, (size_t)nt * sizeof(long));
        memcpy(b->Tv, Tv, (size_t)nt * sizeof(double));
    }
    for (long t = 0; t < nt; t++)
        if (Ti[t] == Tj[t]) b->diag[Ti[t]] += Tv[t];
    for (long i = 0; i < n; i++) {
        b->pos[i] = -1;
        if (!(b->diag[i] > 0)) { /* not positive definite: no Cholesky */
            if (bad) *bad = i;
            free(d);
            ffc__bulk_free(b);
            return FFC_ERR_SINGULAR;
        }
    }
    /* Dirichlet rows: FreeFEM's tgv puts 1e30 on their diagonal. They are
     * the rows above the first gap of 1e12 or more in the sorted diagonal
     * (not a multiple of the median: a scene may hold more Dirichlet rows
     * than free ones); the shift is the mean diagonal of the others */
    memcpy(d, b->diag, nn * sizeof(double));
    qsort(d, nn, sizeof(double), cmp_double);
    const double med = d[nn / 2];
    double cut = HUGE_VAL;
    for (size_t i = 0; i + 1 < nn; i++)
        if (d[i + 1] >= 1e12 * d[i]) {
            cut = d[i + 1];
            break;
        }
    free(d);
    double sum = 0.0;
    long cnt = 0;
    for (long i = 0; i < n; i++) {
        b->big[i] = b->diag[i] >= cut;
        if (!b->big[i]) { sum += b->diag[i]; cnt++; }
    }
    b->kfree = cnt ? sum / cnt : med;
    long nl = 0;
    for (long t = 0; t < nt; t++) nl += b->big[Tj[t]] && !b->big[Ti[t]];
    b->lift = malloc((size_t)(nl ? nl : 1) * sizeof(long));
    if (!b->lift) {
        ffc__bulk_free(b);
        return FFC_ERR_MEMORY;
    }
    for (long t = 0; t < nt; t++)
        if (b->big[Tj[t]] && !b->big[Ti[t]]) b->lift[b->nlift++] = t;
    *out = b;
    return FFC_OK;
}

/* the condensed Newton's dense LU shared over the ranks of fcomm when make
 * is 1 (ScaLAPACK), or on no rank when any failed to make it (without it,
 * dense LUs on every rank); the kept LU dropped */
static void shared_lu(ffc__bulk *b, int fcomm, int make)
{
    ffc__pdense_free(b->pd);
    b->pd = NULL;
    b->kdist = 0;
    b->ka = 0;
    if (!make) return;
    if (ffc__pdense_create(fcomm, &b->pd)) b->pd = NULL;
    if (!ffc__mpi_min(fcomm, b->pd != NULL)) { ffc__pdense_free(b->pd); b->pd = NULL; }
}

int ffc__bulk_set_mumps(ffc__bulk *b, int fcomm)
{
    if (!b) return FFC_ERR_NULL;
    ffc__engine *e = NULL;
    const int st = ffc__mumps_create(&b->info, fcomm, 1, &e);
    if (st) return st;
    bulk_free_factor(b);
    b->eng->op->free(b->eng);
    b->eng = e;
    b->rk.size = 1;
    b->rk.rank = 0;
    shared_lu(b, fcomm, 1);
    return FFC_OK;
}

int ffc__bulk_set_replicated(ffc__bulk *b, int fcomm)
{
    if (!b) return FFC_ERR_NULL;
    if (!ffc_has_mpi()) return FFC_ERR_UNAVAILABLE;
    int rank = 0, size = 1;
    ffc__mpi_ranks(fcomm, &rank, &size);
    long *count = malloc((size_t)size * sizeof *count);
    if (!count) return FFC_ERR_MEMORY;
    bulk_free_factor(b);
    b->eng->op->free(b->eng);
    b->eng = NULL;
    free(b->rk.count);
    b->rk = (ffc__ranks){fcomm, rank, size, count};
    const int st = ffc__cholmod_create(&b->info, &b->rk, &b->eng);
    if (st) return st;
    shared_lu(b, fcomm, size > 1);
    return FFC_OK;
}

/* y = (K + S)^-1 rhs, one back-solve */
static int backsolve_timed(ffc__bulk *b, const double rhs[], double y[])
{
    const int st = b->eng->op->solve(b->eng, rhs, y);
    if (st) return st;
    b->info.backsolves++;
    for (long i = 0; i < b->n; i++)
        if (!isfinite(y[i])) return FFC_ERR_NONFINITE;
    return FFC_OK;
}

int ffc__bulk_backsolve(ffc__bulk *b, const double rhs[], double y[])
{
    const double t0 = ffc__seconds();
    const int st = backsolve_timed(b, rhs, y);
    b->info.t_backsolves += ffc__seconds() - t0;
    return st;
}

/* the factorization of K' + S, S = diag(sh) on the dofs nd[nnew], K' = K
 * with each Dirichlet row and column replaced by kfree on the diagonal (the
 * values of those dofs are moved to the right-hand side: the same solution
 * as the tgv rows' to within 1/tgv, and a factor whose pivots show a
 * singular K: the engine refuses one) */
static int factorize_timed(ffc__bulk *b, long nnew, const long nd[])
{
    for (long k = 0; k < nnew; k++) b->sh[nd[k]] = b->kfree;
    long nlow = 0;
    for (long t = 0; t < b->nt; t++) nlow += b->Ti[t] >= b->Tj[t] && !b->big[b->Ti[t]] && !b->big[b->Tj[t]];
    const size_t cap = (size_t)(nlow + b->n);
    int *ti = malloc(cap * sizeof *ti), *tj = malloc(cap * sizeof *tj);
    double *tv = malloc(cap * sizeof *tv);
    int st = ffc__bulk_agree(b, ti && tj && tv ? FFC_OK : FFC_ERR_MEMORY);   /* (a shared factorization: every
                                                                              rank enters it, or none) */
    long c = 0;
    if (!st) {
        for (long t = 0; t < b->nt; t++)
            if (b->Ti[t] >= b->Tj[t] && !b->big[b->Ti[t]] && !b->big[b->Tj[t]]) {
                ti[c] = (int)b->Ti[t]; tj[c] = (int)b->Tj[t]; tv[c] = b->Tv[t]; c++;
            }
        for (long i = 0; i < b->n; i++)
            if (b->sh[i] != 0.0 || b->big[i]) { ti[c] = tj[c] = (int)i; tv[c] = b->big[i] ? b->kfree : b->sh[i]; c++; }
        const ffc__tri A = {b->n, c, ti, tj, tv, 1};
        st = b->eng->op->analyze(b->eng, &A);
        if (!st) st = b->eng->op->factorize(b->eng, &A);
    }
    free(ti); free(tj); free(tv);
    st = ffc__bulk_agree(b, st);
    if (st) {
        bulk_free_factor(b);
        for (long k = 0; k < nnew; k++) b->sh[nd[k]] = 0.0;
        return st;
    }
    b->factored = 1;
    b->info.factorizations++;
    b->info.shift = nnew ? b->kfree : 0.0;
    b->info.shifted = nnew;
    return FFC_OK;
}

int ffc__bulk_factorize(ffc__bulk *b, long nnew, const long nd[])
{
    b->prev = 0;
    const double t0 = ffc__seconds();
    const int st = factorize_timed(b, nnew, nd);
    b->info.t_factor += ffc__seconds() - t0;
    return st;
}

/* BFS over the node graph (xadj, adj) from s: dist[] (-1 where not yet
 * reached) set on s's part; the nodes in the order reached into q, their
 * count returned (the last one is a farthest from s) */
static long node_bfs(const int xadj[], const int adj[], long s, int dist[], int q[])
{
    long h = 0, t = 0;
    dist[s] = 0;
    q[t++] = (int)s;
    while (h < t) {
        const int v = q[h++];
        for (int e = xadj[v]; e < xadj[v + 1]; e++)
            if (dist[adj[e]] < 0) { dist[adj[e]] = dist[v] + 1; q[t++] = adj[e]; }
    }
    return t;
}

/* 1 when K's triplet t couples two free dofs of different nodes: an edge
 * of the node graph (spread_dofs) */
static int node_edge(const ffc__bulk *b, long t)
{
    return !b->big[b->Ti[t]] && !b->big[b->Tj[t]] && b->Ti[t] / 3 != b->Tj[t] / 3;
}

/* The shift of a singular K on few dofs: in each part of K's graph (a
 * body) that holds one of the dofs seed[nseed], the free dofs of three
 * nodes far apart (a, the farthest from a seed; b, the farthest from a;
 * c, the one farthest from both), into b->nd[*nset].  A rigid motion that
 * is zero at three points not on one line is zero, so K + S is regular
 * on every body the contact touches (each shifted dof joins C and adds
 * one term to the condensed Newton's dense systems; a shift on the
 * contact dofs themselves put every linked point's dofs there: a
 * hemisphere pushed by a force onto a block, 538 shifted dofs and dense
 * systems of 552, against 18 and 23).  Nodes are dofs / 3 (node-major
 * dofs); distances count the graph's edges.  seed must not be b->nd. */
int ffc__bulk_spread_dofs(ffc__bulk *b, long nseed, const long seed[], long *nset)
{
    const long n = b->n, nn = (n + 2) / 3;
    *nset = 0;
    if (nn > 2147483647L / 4) return FFC_ERR_SIZE;
    int *xadj = calloc((size_t)nn + 1, sizeof(int)), *lab = malloc((size_t)nn * 4 * sizeof(int));
    long ne = 0;
    for (long t = 0; t < b->nt; t++)
        if (node_edge(b, t)) { ne++; if (xadj) xadj[b->Ti[t] / 3 + 1]++; }
    int *adj = ne < 2147483647L ? malloc((size_t)(ne + 1) * sizeof(int)) : NULL;
    if (!xadj || !lab || !adj) { free(xadj); free(lab); free(adj); return FFC_ERR_MEMORY; }
    for (long v = 0; v < nn; v++) xadj[v + 1] += xadj[v];
    int *fill = lab + nn;   /* (the fill pointers, then da) */
    memcpy(fill, xadj, (size_t)nn * sizeof(int));
    for (long t = 0; t < b->nt; t++)
        if (node_edge(b, t)) adj[fill[b->Ti[t] / 3]++] = (int)(b->Tj[t] / 3);
    int *da = lab + nn, *db = lab + 2 * nn, *q = lab + 3 * nn;
    for (long v = 0; v < 3 * nn; v++) lab[v] = -1;
    long c = 0;
    for (long k = 0; k < nseed; k++) {
        if (seed[k] < 0 || seed[k] >= n || b->big[seed[k]] || lab[seed[k] / 3] >= 0) continue;
        long cnt = node_bfs(xadj, adj, seed[k] / 3, lab, q);
        const long a = q[cnt - 1];
        cnt = node_bfs(xadj, adj, a, da, q);
        const long bb = q[cnt - 1];
        node_bfs(xadj, adj, bb, db, q);
        long cc = a;
        for (long i = 0, best = -1; i < cnt; i++) {
            const int v = q[i], d = da[v] < db[v] ? da[v] : db[v];
            if (d > best) { best = d; cc = v; }
        }
        const long pick[3] = {a, bb, cc};
        for (int p = 0; p < 3; p++) {
            if ((p == 1 && pick[1] == pick[0]) || (p == 2 && (pick[2] == pick[0] || pick[2] == pick[1]))) continue;
            for (long d = 3 * pick[p]; d < 3 * pick[p] + 3 && d < n; d++)
                if (!b->big[d]) b->nd[c++] = d;
        }
    }
    free(xadj); free(lab); free(adj);
    *nset = c;
    return FFC_OK;
}

/* The first factorization: K alone; when K is singular (a body that only
 * contact holds), K + S with the shift on the contact dofs nd[nnew] of the
 * first solve (in C anyway: the dense systems of these solves are over all
 * of C). */
int ffc__bulk_factorize_first(ffc__bulk *b, long nnew, const long nd[])
{
    int st = ffc__bulk_factorize(b, 0, NULL);
    if (st == FFC_ERR_SINGULAR && nnew > 0) st = ffc__bulk_factorize(b, nnew, nd);
    return st;
}

/* r = b - (K + Kc) x */
void ffc__bulk_residual(const ffc__bulk *b, long nt, const long Ti[], const long Tj[], const double Tv[],
                        const double rhs[], const double x[], double r[])
{
    memcpy(r, rhs, (size_t)b->n * sizeof(double));
    for (long t = 0; t < b->nt; t++) r[b->Ti[t]] -= b->Tv[t] * x[b->Tj[t]];
    for (long t = 0; t < nt; t++) r[Ti[t]] -= Tv[t] * x[Tj[t]];
}

/* t = rhs with the Dirichlet values g = rhs / diag on their rows (times
 * the factor's kfree) and the columns of K and Kc (Ti, Tj, Tv)[nt] at
 * those dofs, times g, moved to the right-hand side */
void ffc__bulk_lift(const ffc__bulk *b, long nt, const long Ti[], const long Tj[], const double Tv[],
                    const double rhs[], double t[])
{
    memcpy(t, rhs, (size_t)b->n * sizeof(double));
    for (long i = 0; i < b->n; i++)
        if (b->big[i]) t[i] = b->kfree * (rhs[i] / b->diag[i]);
    for (long e = 0; e < b->nlift; e++) {
        const long k = b->lift[e];
        t[b->Ti[k]] -= b->Tv[k] * (rhs[b->Tj[k]] / b->diag[b->Tj[k]]);
    }
    for (long k = 0; k < nt; k++)
        if (b->big[Tj[k]] && !b->big[Ti[k]]) t[Ti[k]] -= Tv[k] * (rhs[Tj[k]] / b->diag[Tj[k]]);
}

void ffc__bulk_info(const ffc__bulk *b, ffc_solve_info *info)
{
    if (b) *info = b->info;
    else {
        memset(info, 0, sizeof *info);
        info->ranks = 1;
    }
}

long ffc__bulk_n(const ffc__bulk *b) { return b ? b->n : 0; }

double ffc__bulk_kfree(const ffc__bulk *b) { return b ? b->kfree : 0.0; }

const ffc_error *ffc__bulk_error(const ffc__bulk *b) { return b && b->eng ? &b->eng->err : NULL; }

int ffc__bulk_note(ffc__bulk *b, int st)
{
    if (st == FFC_OK) ffc__bulk_clear_error(b);   /* (a failure on the way, mended: no reason left) */
    if (st != FFC_ERR_MEMORY || !b || !b->eng || b->eng->err.status) return st;
    const double mb = 8.0 * (double)b->ld * (double)b->ld * 3.0 / 1048576.0;
    return ffc__engine_fail(b->eng, st, FFC_AT_COUNT, b->m, "out of memory with %ld dofs and %ld contact dofs "
                            "(the dense compliance and its work: about %.0f MB)", b->n, b->m, mb);
}

void ffc__bulk_clear_error(ffc__bulk *b)
{
    if (b && b->eng) b->eng->err = (ffc_error){0, FFC_AT_NONE, -1, ""};
}
