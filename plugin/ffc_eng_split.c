/* ffc_eng_split.c: the CHOLMOD engine on the ranks of one machine: the
 * supernodal factor made by subtrees, each rank a set into its own copy
 * of L, and the single solves split the same way. */
#include <stdlib.h>
#include <string.h>

#include "ffc_eng_cholmod.h"
#include "ffc_internal.h"
#include "ffc_super.h"

/* BLAS */
void dgemv_(const char *trans, const int *m, const int *n, const double *alpha, const double *a, const int *lda,
            const double *x, const int *incx, const double *beta, double *y, const int *incy);
void dtrsv_(const char *uplo, const char *ta, const char *diag, const int *n, const double *a, const int *lda,
            double *x, const int *incx);

/* every rank holding the factor takes the same branch: st, or
 * FFC_ERR_MEMORY where another rank failed */
static int agree(const ffc__chol *c, int st)
{
    return ffc__chol_all(c, st == FFC_OK) ? FFC_OK : st ? st : FFC_ERR_MEMORY;
}

void ffc__chol_node_init(ffc__chol *c)
{
    c->nsize = 1;
    int nc = 0, nr = 0, ns = 1;
    if (c->rk->size > 1 && ffc__mpi_node(c->rk->comm, &nc, &nr, &ns) == FFC_OK) {
        c->ncomm = nc;
        c->nrank = nr;
        c->nsize = ns;
        if (ns < 2) ffc__mpi_comm_free(nc);
    }
}

void ffc__chol_node_free(ffc__chol *c)
{
    if (c->nsize > 1) ffc__mpi_comm_free(c->ncomm);
    c->nsize = 1;
}

void ffc__chol_split_free(ffc__chol *c)
{
    c->split = 0;
    free(c->spart); free(c->sx); free(c->scnt);
    c->spart = NULL;
    c->sx = NULL;
    c->scnt = NULL;
}

/* split_solve's work: x [n], the rows below one supernode [sbelow], the
 * values gathered [n + split * ntop: at most n, or the ranks' updates of
 * the rows above the sets], the counts [nsize] */
static int split_work(ffc__chol *c)
{
    const cholmod_factor *L = c->L;
    const long ns = (long)L->nsuper;
    const int *super = L->super, *pi = L->pi;
    c->sbelow = 1;
    c->ntop = 0;
    for (long s = 0; s < ns; s++) {
        const long ncol = super[s + 1] - super[s], below = (pi[s + 1] - pi[s]) - ncol;
        if (below > c->sbelow) c->sbelow = below;
        if (c->spart[s] < 0) c->ntop += ncol;
    }
    c->sx = malloc((size_t)(2 * c->base.n + c->sbelow + c->split * c->ntop) * sizeof(double));
    c->scnt = malloc((size_t)c->nsize * sizeof(long));
    return c->sx && c->scnt ? FFC_OK : FFC_ERR_MEMORY;
}

/* one supernode's forward solve (x_s = L_ss^-1 x_s, then the rows below
 * less L_rs x_s) and backward solve (x_s = L_ss^-T (x_s - L_rs' x_r));
 * t: [rows below] */
static void super_forward(const cholmod_factor *L, long s, double x[], double t[])
{
    const int *super = L->super, *pi = L->pi, *ls = L->s;
    const int k1 = super[s], ncol = super[s + 1] - k1, nrow = pi[s + 1] - pi[s], below = nrow - ncol, inc = 1;
    const double *Ls = (const double *)L->x + ((const int *)L->px)[s], one = 1.0, zero = 0.0;
    dtrsv_("L", "N", "N", &ncol, Ls, &nrow, x + k1, &inc);
    if (below == 0) return;
    dgemv_("N", &below, &ncol, &one, Ls + ncol, &nrow, x + k1, &inc, &zero, t, &inc);
    const int *ri = ls + pi[s] + ncol;
    for (int r = 0; r < below; r++) x[ri[r]] -= t[r];
}

static void super_backward(const cholmod_factor *L, long s, double x[], double t[])
{
    const int *super = L->super, *pi = L->pi, *ls = L->s;
    const int k1 = super[s], ncol = super[s + 1] - k1, nrow = pi[s + 1] - pi[s], below = nrow - ncol, inc = 1;
    const double *Ls = (const double *)L->x + ((const int *)L->px)[s], one = 1.0, mone = -1.0;
    if (below > 0) {
        const int *ri = ls + pi[s] + ncol;
        for (int r = 0; r < below; r++) t[r] = x[ri[r]];
        dgemv_("T", &below, &ncol, &mone, Ls + ncol, &nrow, t, &inc, &one, x + k1, &inc);
    }
    dtrsv_("L", "T", "N", &ncol, Ls, &nrow, x + k1, &inc);
}

/* Formulation: P K' P' = L L' (P = L->Perm), so y = P' L'^-T L^-1 P rhs.
 * The factor's supernodes are split into sets of whole subtrees and the
 * supernodes above them (c->spart, as the machine's ranks factorized
 * them).  A subtree's forward solve writes its own rows and its
 * ancestors' (its set's and those above the sets), and its backward
 * solve reads the same rows.  So rank k of the machine makes set k's
 * forward solve, starting from zero on the rows above the sets; the
 * ranks' updates of those rows are gathered and added to rhs there in
 * rank order (every rank the same bits); every rank makes the forward
 * and then the backward solve of the supernodes above the sets; rank k
 * makes set k's backward solve; and one all-gather gives every rank
 * every set's rows.  Each rank streams its share of L instead of all of
 * it (Hertz P1 h_c 0.0125 on two ranks, a body each: about half). */
int ffc__chol_split_solve(ffc__chol *c, const double rhs[], double y[])
{
    if (!c->sx) {
        const int st = agree(c, split_work(c));
        if (st) {
            free(c->sx); free(c->scnt);
            c->sx = NULL;
            c->scnt = NULL;
            return st;
        }
    }
    const cholmod_factor *L = c->L;
    const long n = c->base.n, ns = (long)L->nsuper, ntop = c->ntop;
    const int *super = L->super, *perm = L->Perm;
    const signed char *part = c->spart;
    const int parts = c->split, me = c->nrank < parts ? c->nrank : -2;
    double *x = c->sx, *t = x + n, *g = t + c->sbelow;
    long *cnt = c->scnt;
    for (long k = 0; k < n; k++) x[k] = rhs[perm[k]];
    for (long s = 0; s < ns; s++)
        if (part[s] < 0) memset(x + super[s], 0, (size_t)(super[s + 1] - super[s]) * sizeof(double));
    for (long s = 0; s < ns; s++)
        if (part[s] == me) super_forward(L, s, x, t);
    int st = FFC_OK;
    if (ntop > 0) {
        for (int r = 0; r < c->nsize; r++) cnt[r] = r < parts ? ntop : 0;
        if (me >= 0)
            for (long s = 0, i = me * ntop; s < ns; s++)
                for (int c = super[s]; c < super[s + 1] && part[s] < 0; c++) g[i++] = x[c];
        st = ffc__mpi_allgather(c->ncomm, g, cnt);
        if (st) return st;
        for (long s = 0, i = 0; s < ns; s++)
            for (int c = super[s]; c < super[s + 1] && part[s] < 0; c++, i++) {
                double v = rhs[perm[c]];
                for (int r = 0; r < parts; r++) v += g[r * ntop + i];
                x[c] = v;
            }
        for (long s = 0; s < ns; s++)
            if (part[s] < 0) super_forward(L, s, x, t);
        for (long s = ns - 1; s >= 0; s--)
            if (part[s] < 0) super_backward(L, s, x, t);
    }
    for (long s = ns - 1; s >= 0; s--)
        if (part[s] == me) super_backward(L, s, x, t);
    /* every set's rows: rank k's after those of the ranks before it */
    for (int r = 0; r < c->nsize; r++) cnt[r] = 0;
    for (long s = 0; s < ns; s++)
        if (part[s] >= 0) cnt[part[s]] += super[s + 1] - super[s];
    long off = 0;
    for (int r = 0; r < me; r++) off += cnt[r];
    for (long s = 0; s < ns && me >= 0; s++)
        for (int c = super[s]; c < super[s + 1] && part[s] == me; c++) g[off++] = x[c];
    st = ffc__mpi_allgather(c->ncomm, g, cnt);
    if (st) return st;
    off = 0;
    for (int r = 0; r < parts; r++)
        for (long s = 0; s < ns; s++)
            for (int c = super[s]; c < super[s + 1] && part[s] == r; c++) x[c] = g[off++];
    for (long k = 0; k < n; k++) y[perm[k]] = x[k];
    return FFC_OK;
}

/* the values of the runs of consecutive supernodes of set `part` of the
 * split (-1: those above the sets), broadcast from the machine's rank
 * `root` into every rank's L */
static int bcast_part(ffc__chol *c, const signed char spart[], int part, int root)
{
    const cholmod_factor *L = c->L;
    const long ns = (long)L->nsuper;
    const int *px = L->px;
    double *x = L->x;
    for (long s = 0; s < ns;) {
        if (spart[s] != part) { s++; continue; }
        long e = s;
        while (e < ns && spart[e] == part) e++;
        const int st = ffc__mpi_bcast_from(c->ncomm, root, x + px[s], (long)px[e] - px[s]);
        if (st) return st;
        s = e;
    }
    return FFC_OK;
}

/* The same on the ranks of each machine (replicated bulk, a supernodal L,
 * every rank with a machine-mate; called on every rank): the supernodal
 * tree's subtrees are shared out among the machine's ranks (ffc_super.c),
 * as many sets as the fewest ranks of any machine has (every machine the
 * same split, the same bits); rank k factorizes set k into its own L on
 * one core, and the machine's ranks broadcast their sets' values to each
 * other (a set is a few runs of consecutive supernodes: whole subtrees,
 * in the tree's postorder); rank 0 then makes the supernodes above the
 * sets with as many BLAS threads as the sets, while the others wait
 * without spinning, and broadcasts them.  So every rank holds the whole
 * factor, the same bits, in memory of its own, and solves with it.
 * (An earlier build kept one L per machine in memory the ranks shared:
 * on this project's 2-core machines, virtual, that memory came in 4 KB
 * pages and the solves read it several times slower than private
 * memory, and erratically: Hertz P1 h_c 0.008 on 2 ranks, the single
 * back-solves 5 to 10 s against 0.7 to 0.9 s.)  L's structure, from the
 * same analysis of the same matrix, is the same on every rank: checked
 * first; where it is not on some machine, or no split applies, every
 * rank factorizes for itself.  The decisions are every rank's. */
int ffc__chol_numeric_on_node(ffc__chol *c, cholmod_sparse *A)
{
    const cholmod_factor *L = c->L;
    double sig[4] = {(double)L->xsize, (double)L->nsuper, (double)L->ssize, 0.0}, s0[4];
    const int *perm = L->Perm;
    for (size_t k = 0; k < L->n; k++) sig[3] += (double)perm[k] * (double)((k % 1021) + 1);
    memcpy(s0, sig, sizeof sig);
    int st = ffc__mpi_bcast_idle(c->ncomm, s0, 4);
    if (st) return st;
    const int same = ffc__mpi_min(c->ncomm, memcmp(s0, sig, sizeof sig) == 0);   /* (alike on the machine) */
    const int threads = ffc__mpi_min(c->rk->comm, c->nsize);
    /* L made numeric (its values not yet touched) */
    cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, c->L, &c->cc);
    st = c->cc.status < CHOLMOD_OK || !c->L->x ? FFC_ERR_MEMORY : FFC_OK;
    int sst = FFC_OK;
    ffc__super *sp = same && !st ? ffc__super_create(c->L, A, threads, &sst) : NULL;
    if (!ffc__chol_all(c, sp != NULL)) {
        ffc__super_free(sp);
        return ffc__chol_numeric(c, A);
    }
    c->spart = malloc((size_t)c->L->nsuper);
    if (!ffc__chol_all(c, c->spart != NULL)) {
        ffc__super_free(sp);
        return FFC_ERR_MEMORY;
    }
    memcpy(c->spart, ffc__super_parts(sp), (size_t)c->L->nsuper);
    c->split = threads;
    double *x = c->L->x, head[2] = {0.0, 0.0};   /* rank 0's status and rcond */
    int mine = 1;
    if (c->nrank < threads) {
        const int old = ffc__blas_threads(1);
        mine = ffc__super_numeric(sp, c->L, x, c->nrank) == FFC_OK;
        ffc__blas_threads(old);
    }
    const int all = ffc__mpi_min(c->ncomm, mine);
    for (int p = 0; p < threads && all && !st; p++) st = bcast_part(c, c->spart, p, p);
    if (st) {
        ffc__super_free(sp);
        return st;
    }
    if (c->nrank == 0) {
        head[0] = all ? FFC_OK : FFC_ERR_SINGULAR;
        if (all) {
            const int old = ffc__blas_threads(threads);
            head[0] = ffc__super_numeric(sp, c->L, x, -1);
            ffc__blas_threads(old);
        }
        if (head[0] == FFC_OK) head[0] = ffc__chol_conditioned(c);
        head[1] = c->base.info->rcond;
    }
    ffc__super_free(sp);
    if ((st = ffc__mpi_bcast_idle(c->ncomm, head, 2))) return st;
    if (head[0] == FFC_OK && (st = bcast_part(c, c->spart, -1, 0))) return st;
    c->base.info->rcond = head[1];
    return (int)head[0];
}

