/* ffc_eng_cholmod.c: the CHOLMOD engine: a symmetric positive definite
 * matrix factorized (LL^T, supernodal or simplicial, CHOLMOD's choice),
 * solved, and the entries of its inverse by block solves pruned to the
 * paths of the rows asked for; on several ranks each holds the factor. */
#include <stdlib.h>
#include <string.h>

#include <suitesparse/cholmod.h>

#include "ffc_engine.h"
#include "ffc_internal.h"

/* BLAS */
void dtrsm_(const char *side, const char *uplo, const char *ta, const char *diag, const int *m, const int *n,
            const double *alpha, const double *a, const int *lda, double *b, const int *ldb);
void dgemm_(const char *ta, const char *tb, const int *m, const int *n, const int *k, const double *alpha,
            const double *a, const int *lda, const double *b, const int *ldb, const double *beta, double *c,
            const int *ldc);

enum { FFC__BLOCK = 128 };  /* inverse columns per block back-solve (128 against 64: the same at 44k dofs,
                               about 10 % less at 141k) */

typedef struct {
    ffc__engine base;
    ffc__ranks *rk;            /* the ranks holding the factor, each all of it (size 1: one process) */
    int started;               /* cholmod_start called */
    cholmod_common cc;
    cholmod_factor *L;         /* NULL until the first analysis */
    cholmod_dense *B, *X, *Y, *E;       /* one right-hand side and solve2's work */
    cholmod_dense *Bb, *Xb, *Yb, *Eb;   /* a block of FFC__BLOCK right-hand sides (Bb zero between uses) */
    /* the pruned solves of a supernodal factor (made with the factor) */
    int prune;                 /* 1: the inverse by pruned solves when L is supernodal (default) */
    int force_super;           /* 1: a supernodal L whatever its size (test hook; 0: CHOLMOD chooses) */
    int *ipm;                  /* [n] position of each dof in L's order (the inverse of L->Perm) */
    int *sn;                   /* [n] the supernode of each of L's columns */
    int *spar;                 /* [nsuper] each supernode's parent in the supernodal elimination tree, or -1 */
    int *sroot;                /* [nsuper] the root of each supernode's tree (one tree per part of the matrix
                                  that nothing couples: each body, before contact) */
    unsigned char *smark;      /* [nsuper] work: 1 on the supernodes a solve visits */
    unsigned char *tmark;      /* [nsuper] work: 1 on the roots of the trees a block of columns lies in */
    double *sw;                /* [swcap] work: a supernode's rows below its diagonal block x FFC__BLOCK */
    long swcap;
    double pshare;             /* the share of L's entries the last pruned backward solves visited */
    double min_rcond;          /* a factor of estimated reciprocal condition below it is singular (1e-12;
                                  0: only a failed factorization is, for matrices with tgv rows) */
} ffc__chol;

enum { INV_ENTRIES = 1 << 21 };   /* inverse values per piece (fewer columns per solve lost the pruning's gain) */

/* ok on every rank holding the factor (a collective call; ok itself alone) */
static int chol_all(const ffc__chol *c, int ok)
{
    return c->rk->size > 1 ? ffc__mpi_min(c->rk->comm, ok) : ok;
}

/* every rank holding the factor takes the same branch: st, or
 * FFC_ERR_MEMORY where another rank failed */
static int agree(const ffc__chol *c, int st)
{
    return chol_all(c, st == FFC_OK) ? FFC_OK : st ? st : FFC_ERR_MEMORY;
}

static int chol_agree(const ffc__engine *e, int ok) { return chol_all((const ffc__chol *)e, ok); }

/* drops the pruned solves' tree and work (made again with the next factor) */
static void prune_free(ffc__chol *c)
{
    free(c->ipm); free(c->sn); free(c->spar); free(c->sroot); free(c->smark); free(c->tmark); free(c->sw);
    c->ipm = c->sn = c->spar = c->sroot = NULL;
    c->smark = c->tmark = NULL;
    c->sw = NULL;
    c->swcap = 0;
}

/* the numeric factor's work dropped (the analysis kept) */
static void numeric_free(ffc__chol *c)
{
    if (!c->started) return;
    cholmod_dense **d[] = {&c->B, &c->X, &c->Y, &c->E, &c->Bb, &c->Xb, &c->Yb, &c->Eb};
    for (size_t k = 0; k < sizeof d / sizeof *d; k++)
        if (*d[k]) cholmod_free_dense(d[k], &c->cc);
    prune_free(c);
    c->base.factored = 0;
}

static void chol_release(ffc__engine *e)
{
    ffc__chol *c = (ffc__chol *)e;
    numeric_free(c);
    if (c->started && c->L) cholmod_free_factor(&c->L, &c->cc);
}

static void chol_free(ffc__engine *e)
{
    ffc__chol *c = (ffc__chol *)e;
    chol_release(e);
    if (c->started) cholmod_finish(&c->cc);
    free(c);
}

/* A as CHOLMOD's packed sparse matrix (NULL when out of memory) */
static cholmod_sparse *to_sparse(ffc__chol *c, const ffc__tri *A)
{
    cholmod_triplet T = {0};
    T.nrow = T.ncol = (size_t)A->n;
    T.nzmax = T.nnz = (size_t)A->nz;
    T.i = (void *)A->i;
    T.j = (void *)A->j;
    T.x = (void *)A->v;
    T.stype = -1;
    T.itype = CHOLMOD_INT;
    T.xtype = CHOLMOD_REAL;
    T.dtype = CHOLMOD_DOUBLE;
    return cholmod_triplet_to_sparse(&T, (size_t)A->nz, &c->cc);
}

static int chol_analyze(ffc__engine *e, const ffc__tri *A)
{
    ffc__chol *c = (ffc__chol *)e;
    if (!A->sym) return ffc__engine_fail(e, FFC_ERR_VALUE, FFC_AT_NONE, -1, "CHOLMOD: the matrix is not symmetric");
    chol_release(e);
    if (!c->started) {
        cholmod_start(&c->cc);
        c->cc.print = 0;              /* kernels never print */
        c->cc.error_handler = NULL;
        c->started = 1;
    }
    c->cc.supernodal = c->force_super ? CHOLMOD_SUPERNODAL : CHOLMOD_AUTO;
    e->n = A->n;
    cholmod_sparse *S = to_sparse(c, A);
    if (S) c->L = cholmod_analyze(S, &c->cc);
    if (S) cholmod_free_sparse(&S, &c->cc);
    const int st = agree(c, c->L ? FFC_OK : FFC_ERR_MEMORY);   /* (every rank analysed A, or none goes on) */
    if (st) return ffc__engine_fail(e, st, FFC_AT_COUNT, A->n, "CHOLMOD: out of memory analysing a matrix of "
                                    "order %ld with %ld entries", A->n, A->nz);
    return FFC_OK;
}

/* the numeric factorization of A (lower, packed) into the analysed c->L,
 * and its condition estimate (FFC_ERR_SINGULAR below c->min_rcond) */
static int chol_numeric(ffc__chol *c, cholmod_sparse *A)
{
    cholmod_factorize(A, c->L, &c->cc);
    if (c->cc.status == CHOLMOD_NOT_POSDEF || c->L->minor < c->L->n) return FFC_ERR_SINGULAR;
    if (c->cc.status < CHOLMOD_OK) return FFC_ERR_MEMORY;
    c->base.info->rcond = cholmod_rcond(c->L, &c->cc);
    return c->base.info->rcond >= c->min_rcond ? FFC_OK : FFC_ERR_SINGULAR;
}

static int chol_factorize(ffc__engine *e, const ffc__tri *A)
{
    ffc__chol *c = (ffc__chol *)e;
    if (!c->L || A->n != e->n) return ffc__engine_fail(e, FFC_ERR_EMPTY, FFC_AT_NONE, -1, "CHOLMOD: not analysed");
    numeric_free(c);
    cholmod_sparse *S = to_sparse(c, A);
    int st = agree(c, S ? FFC_OK : FFC_ERR_MEMORY);
    if (!st) st = chol_numeric(c, S);
    if (S) cholmod_free_sparse(&S, &c->cc);
    if (!st) {
        c->B = cholmod_zeros((size_t)A->n, 1, CHOLMOD_REAL, &c->cc);
        c->Bb = cholmod_zeros((size_t)A->n, FFC__BLOCK, CHOLMOD_REAL, &c->cc);
        if (!c->B || !c->Bb) st = FFC_ERR_MEMORY;
    }
    st = agree(c, st);   /* (a shared factor: one rank short of memory is every rank's failure) */
    if (st == FFC_ERR_SINGULAR)
        return ffc__engine_fail(e, st, FFC_AT_NONE, -1, "CHOLMOD: the matrix is not positive definite or its "
                                "estimated reciprocal condition %.3g is below %.3g", e->info->rcond, c->min_rcond);
    if (st)
        return ffc__engine_fail(e, st, FFC_AT_COUNT, A->n, "CHOLMOD: out of memory factorizing a matrix of order "
                                "%ld with %ld entries", A->n, A->nz);
    e->factored = 1;
    return FFC_OK;
}

static int chol_solve(ffc__engine *e, const double rhs[], double y[])
{
    ffc__chol *c = (ffc__chol *)e;
    if (!e->factored) return ffc__engine_fail(e, FFC_ERR_EMPTY, FFC_AT_NONE, -1, "CHOLMOD: not factorized");
    memcpy(c->B->x, rhs, (size_t)e->n * sizeof(double));
    const int ok = cholmod_solve2(CHOLMOD_A, c->L, c->B, NULL, &c->X, NULL, &c->Y, &c->E, &c->cc);
    const int st = agree(c, ok ? FFC_OK : FFC_ERR_MEMORY);
    if (!st) memcpy(y, c->X->x, (size_t)e->n * sizeof(double));
    if (st) return ffc__engine_fail(e, st, FFC_AT_COUNT, e->n, "CHOLMOD: out of memory in a solve of order %ld",
                                    e->n);
    return FFC_OK;
}

/* The supernodal elimination forest of L (parent of supernode s: the one
 * holding the first row below s's diagonal block, so after s), each
 * supernode's root, each dof's position in L's order and each position's
 * supernode; made once per factor. */
static int prune_tree(ffc__chol *c)
{
    if (c->ipm) return FFC_OK;
    const cholmod_factor *L = c->L;
    const long n = c->base.n, ns = (long)L->nsuper;
    const int *perm = L->Perm, *super = L->super, *pi = L->pi, *ls = L->s;
    c->ipm = malloc((size_t)n * sizeof(int));
    c->sn = malloc((size_t)n * sizeof(int));
    c->spar = malloc((size_t)ns * sizeof(int));
    c->sroot = malloc((size_t)ns * sizeof(int));
    c->smark = calloc((size_t)ns, 1);
    c->tmark = calloc((size_t)ns, 1);
    long wrow = 0;
    for (long k = 0; k < ns; k++) {
        const long below = (pi[k + 1] - pi[k]) - (super[k + 1] - super[k]);
        if (below > wrow) wrow = below;
    }
    c->swcap = (wrow > 0 ? wrow : 1) * FFC__BLOCK;
    c->sw = malloc((size_t)c->swcap * sizeof(double));
    if (!c->ipm || !c->sn || !c->spar || !c->sroot || !c->smark || !c->tmark || !c->sw) {
        prune_free(c);
        return FFC_ERR_MEMORY;
    }
    for (long i = 0; i < n; i++) c->ipm[perm[i]] = (int)i;
    for (long k = 0; k < ns; k++)
        for (int j = super[k]; j < super[k + 1]; j++) c->sn[j] = (int)k;
    for (long k = 0; k < ns; k++) {
        const int ncol = super[k + 1] - super[k], nrow = pi[k + 1] - pi[k];
        c->spar[k] = nrow > ncol ? c->sn[ls[pi[k] + ncol]] : -1;
    }
    for (long k = ns - 1; k >= 0; k--) c->sroot[k] = c->spar[k] < 0 ? (int)k : c->sroot[c->spar[k]];
    return FFC_OK;
}

/* marks the supernodes on the paths from those of the dofs d[nd] to the root */
static void prune_mark(const ffc__chol *c, long nd, const long d[])
{
    for (long k = 0; k < nd; k++)
        for (int s = c->sn[c->ipm[d[k]]]; s >= 0 && !c->smark[s]; s = c->spar[s]) c->smark[s] = 1;
}

/* the root of the tree that holds dof i's column of L */
static int prune_root(const ffc__chol *c, long i)
{
    return c->sroot[c->sn[c->ipm[i]]];
}

/* Formulation: P K' P' = L L' (CHOLMOD's supernodal factor, P = L->Perm),
 * so the columns of K'^-1 at the dofs j are x = P' L'^-1 L^-1 P e_j.  The
 * forward solve z = L^-1 P e_j is zero outside the supernodes on the path
 * from j's supernode to the root of the supernodal elimination tree (a
 * column of L only updates rows of its ancestors), and x on a row needs
 * z and x on that row's path alone (the backward solve of a supernode
 * reads only rows below its diagonal block, its ancestors').  So the
 * columns read on the rows C u new u R take the forward solve over the
 * block's paths (Fw) and the backward solve over the rows' paths (bw),
 * not all of L: on Hertz P1 h_c = 0.0125 about 25 % and 65 % of L's
 * entries, against 100 % twice.  Where K has parts that nothing couples
 * (the bodies of a scene: L's forest has a tree for each), z and x are
 * zero outside the trees of the block's dofs, so the backward solve takes
 * bw in those trees alone (a block, in the factor's order, holds one
 * body's columns but where the bodies change): on Hertz's two bodies that
 * halves it, and the values are those of the whole bw (what it skips adds
 * zeros).  X (n x FFC__BLOCK, in L's order) is
 * zero on entry; the block's dofs are among the rows, so Fw lies in bw,
 * and the rows the backward solve visited are cleared at the end.  The
 * values on rows[nrows] go to V (nrows x nb). */
static void pruned_block(ffc__chol *c, long nbl, const long d[], const unsigned char bw[], long nrows,
                         const long rows[], double V[])
{
    const cholmod_factor *L = c->L;
    const long n = c->base.n, ns = (long)L->nsuper;
    const int *super = L->super, *pi = L->pi, *px = L->px, *ls = L->s;
    const double *lx = L->x, one = 1.0, zero = 0.0, mone = -1.0;
    const int ldx = (int)n, nb = (int)nbl;
    double *X = c->Bb->x, *W = c->sw;
    const int *sroot = c->sroot;
    unsigned char *tmark = c->tmark;
    for (long k = 0; k < nbl; k++) {
        X[c->ipm[d[k]] + k * n] = 1.0;
        tmark[prune_root(c, d[k])] = 1;
    }
    prune_mark(c, nbl, d);   /* Fw */
    for (long s = 0; s < ns; s++) {   /* forward, children before parents */
        if (!c->smark[s]) continue;
        c->smark[s] = 0;
        const int k1 = super[s], ncol = super[s + 1] - k1, nrow = pi[s + 1] - pi[s], below = nrow - ncol;
        const double *Ls = lx + px[s];
        dtrsm_("L", "L", "N", "N", &ncol, &nb, &one, Ls, &nrow, X + k1, &ldx);
        if (below == 0) continue;
        dgemm_("N", "N", &below, &nb, &ncol, &one, Ls + ncol, &nrow, X + k1, &ldx, &zero, W, &below);
        const int *ri = ls + pi[s] + ncol;
        for (long c = 0; c < nbl; c++)
            for (int r = 0; r < below; r++) X[ri[r] + c * n] -= W[r + c * below];
    }
    for (long s = ns - 1; s >= 0; s--) {   /* backward, parents before children */
        if (!bw[s] || !tmark[sroot[s]]) continue;
        const int k1 = super[s], ncol = super[s + 1] - k1, nrow = pi[s + 1] - pi[s], below = nrow - ncol;
        const double *Ls = lx + px[s];
        if (below > 0) {
            const int *ri = ls + pi[s] + ncol;
            for (long c = 0; c < nbl; c++)
                for (int r = 0; r < below; r++) W[r + c * below] = X[ri[r] + c * n];
            dgemm_("T", "N", &ncol, &nb, &below, &mone, Ls + ncol, &nrow, W, &below, &one, X + k1, &ldx);
        }
        dtrsm_("L", "L", "T", "N", &ncol, &nb, &one, Ls, &nrow, X + k1, &ldx);
    }
    for (long k = 0; k < nbl; k++)
        for (long r = 0; r < nrows; r++) V[r + k * nrows] = X[c->ipm[rows[r]] + k * n];
    for (long s = 0; s < ns; s++)
        if (bw[s] && tmark[sroot[s]])
            for (long c = 0; c < nbl; c++)
                memset(X + super[s] + c * n, 0, (size_t)(super[s + 1] - super[s]) * sizeof(double));
    for (long k = 0; k < nbl; k++) tmark[prune_root(c, d[k])] = 0;
}

/* the same by whole back-solves (a simplicial factor, or pruning off) */
static int whole_block(ffc__chol *c, long nbl, const long d[], long nrows, const long rows[], double V[])
{
    const long n = c->base.n;
    double *bx = c->Bb->x;
    memset(bx, 0, (size_t)n * FFC__BLOCK * sizeof(double));
    for (long k = 0; k < nbl; k++) bx[d[k] + k * n] = 1.0;
    const int ok = cholmod_solve2(CHOLMOD_A, c->L, c->Bb, NULL, &c->Xb, NULL, &c->Yb, &c->Eb, &c->cc);
    for (long k = 0; k < nbl; k++) bx[d[k] + k * n] = 0.0;   /* (Bb zero again, as pruned_block wants it) */
    if (!ok) return FFC_ERR_MEMORY;
    const double *xb = c->Xb->x;
    for (long k = 0; k < nbl; k++)
        for (long r = 0; r < nrows; r++) V[r + k * nrows] = xb[rows[r] + k * n];
    return FFC_OK;
}

/* the columns of K'^-1 at the dofs d[nc] on rows[nrows] into V (nrows x
 * nc), FFC__BLOCK at a time (bw: the rows' paths when pruned, else NULL) */
static int columns_on_rows(ffc__chol *c, long nc, const long d[], const unsigned char *bw, long nrows,
                           const long rows[], double V[])
{
    for (long k0 = 0; k0 < nc; k0 += FFC__BLOCK) {
        const long nbl = nc - k0 < FFC__BLOCK ? nc - k0 : FFC__BLOCK;
        if (bw) pruned_block(c, nbl, d + k0, bw, nrows, rows, V + k0 * nrows);
        else {
            const int st = whole_block(c, nbl, d + k0, nrows, rows, V + k0 * nrows);
            if (st) return st;
        }
        c->base.info->backsolves += nbl;
    }
    return FFC_OK;
}


/* The entries of the inverse on rows[nrows] in the columns cols[nc], in
 * pieces of at most INV_ENTRIES values: pruned supernodal solves (the
 * columns put in the factor's order, so that a block's columns share
 * their paths) or whole back-solves.  On several ranks each solves a
 * contiguous share of each piece and the shares are gathered, so that
 * every rank holds every column (pruned: shares of equal work, a
 * column's being its tree's part of the backward solves). */
static int chol_inverse(ffc__engine *e, long nc, long cols[], long nrows, const long rows[], ffc__inv_sink sink,
                        void *ctx)
{
    ffc__chol *c = (ffc__chol *)e;
    if (nc <= 0) return FFC_OK;
    if (!e->factored) return ffc__engine_fail(e, FFC_ERR_EMPTY, FFC_AT_NONE, -1, "CHOLMOD: not factorized");
    const int pruned = c->prune && c->L->is_super, ranked = c->rk->size > 1;
    int st = agree(c, pruned ? prune_tree(c) : FFC_OK);
    if (st) return ffc__engine_fail(e, st, FFC_AT_COUNT, e->n, "CHOLMOD: out of memory for the pruned solves");
    const long ns = pruned ? (long)c->L->nsuper : 0;
    const long chunk = nrows > 0 && INV_ENTRIES / nrows > 0 ? INV_ENTRIES / nrows : 1;
    unsigned char *bw = pruned ? calloc((size_t)ns, 1) : NULL;
    double *tw = pruned && ranked ? calloc((size_t)ns + (size_t)nc, sizeof *tw) : NULL;
    long *key = pruned ? malloc((size_t)nc * sizeof *key) : NULL;
    double *V = malloc((size_t)(nrows > 0 ? nrows : 1) * (nc < chunk ? nc : chunk) * sizeof *V);
    st = agree(c, V && (!pruned || (bw && key)) && (!pruned || !ranked || tw) ? FFC_OK : FFC_ERR_MEMORY);
    if (!st && pruned) {   /* the columns in the factor's order; the rows' paths */
        for (long k = 0; k < nc; k++) key[k] = ((long)c->ipm[cols[k]] << 32) | k;
        qsort(key, (size_t)nc, sizeof *key, ffc__cmp_long);
        for (long k = 0; k < nc; k++) key[k] = cols[key[k] & 0xffffffffL];
        memcpy(cols, key, (size_t)nc * sizeof *cols);
        prune_mark(c, nrows, rows);
        memcpy(bw, c->smark, (size_t)ns);
        memset(c->smark, 0, (size_t)ns);
        const int *super = c->L->super, *pi = c->L->pi;
        double vis = 0.0, all = 0.0;
        for (long k = 0; k < ns; k++) {
            const double w = (double)(super[k + 1] - super[k]) * (pi[k + 1] - pi[k]);
            all += w;
            vis += bw[k] ? w : 0.0;
            if (tw && bw[k]) tw[c->sroot[k]] += w;   /* each tree's backward work */
        }
        c->pshare = vis / all;
        if (tw)   /* each column's work, after the trees' */
            for (long k = 0; k < nc; k++) tw[ns + k] = tw[prune_root(c, cols[k])];
    }
    for (long k0 = 0; k0 < nc && !st; k0 += chunk) {
        const long n1 = nc - k0 < chunk ? nc - k0 : chunk;
        if (ranked) {
            long lo = 0, hi = 0;
            if (tw) ffc__ranks_share_by(c->rk, n1, tw + ns + k0, nrows, &lo, &hi);
            else ffc__ranks_share(c->rk, n1, nrows, &lo, &hi);
            st = agree(c, columns_on_rows(c, hi - lo, cols + k0 + lo, bw, nrows, rows, V + lo * nrows));
            if (!st) st = ffc__mpi_allgather(c->rk->comm, V, c->rk->count);
        } else
            st = columns_on_rows(c, n1, cols + k0, bw, nrows, rows, V);
        if (!st) st = sink(ctx, n1, cols + k0, V);
    }
    free(bw); free(tw); free(key); free(V);
    if (st == FFC_ERR_MEMORY)
        return ffc__engine_fail(e, st, FFC_AT_COUNT, nc, "CHOLMOD: out of memory for %ld columns of the inverse "
                                "on %ld rows", nc, nrows);
    return st;
}

void ffc__cholmod_set_mode(ffc__engine *e, int supernodal, int prune)
{
    if (!e || e->op->analyze != chol_analyze) return;
    ffc__chol *c = (ffc__chol *)e;
    c->force_super = supernodal != 0;
    c->prune = prune != 0;
}

void ffc__cholmod_set_rcond(ffc__engine *e, double min_rcond)
{
    if (e && e->op->analyze == chol_analyze) ((ffc__chol *)e)->min_rcond = min_rcond;
}

void ffc__cholmod_mode(const ffc__engine *e, int *supernodal, double *pruned)
{
    const ffc__chol *c = e && e->op->analyze == chol_analyze ? (const ffc__chol *)e : NULL;
    if (supernodal) *supernodal = c && c->L && c->L->is_super;
    if (pruned) *pruned = c ? c->pshare : 0.0;
}

static const ffc__engine_ops chol_ops = {"CHOLMOD", chol_analyze, chol_factorize, chol_solve, chol_inverse,
                                         chol_agree, chol_release, chol_free};

int ffc__cholmod_create(ffc_solve_info *info, ffc__ranks *ranks, ffc__engine **out)
{
    if (!out || !info || !ranks) return FFC_ERR_NULL;
    *out = NULL;
    ffc__chol *c = calloc(1, sizeof *c);
    if (!c) return FFC_ERR_MEMORY;
    c->base.op = &chol_ops;
    c->base.info = info;
    c->base.err.index = -1;
    c->rk = ranks;
    c->prune = 1;
    c->min_rcond = 1e-12;
    info->ranks = ranks->size;
    *out = &c->base;
    return FFC_OK;
}
