/* ffc_eng_mumps.c: the parallel MUMPS engine over an MPI communicator
 * (built with -DFFC_MPI; without it, FFC_ERR_UNAVAILABLE). */
#include <stdlib.h>

#include "ffc_engine.h"
#include "ffc_internal.h"

#ifdef FFC_MPI

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <dmumps_c.h>
#include <mpi.h>

#define ICNTL(k) icntl[(k) - 1]
#define INFOG(k) infog[(k) - 1]
#define INFO(k) info[(k) - 1]
#define CNTL(k) cntl[(k) - 1]

typedef struct {
    ffc__engine base;
    DMUMPS_STRUC_C id;         /* MUMPS's instance */
    MPI_Comm comm;             /* its communicator */
    int rank, ranks;           /* this rank, their count */
    int have;                  /* 1: initialized (job -1 done) */
    MUMPS_INT *ri, *rj;        /* [nloc] this rank's share of the entries (1-based) */
    double *rv;                /* [nloc] */
    long nloc;
    double mb_rank, mb_max;    /* factorization memory: this rank's, the largest (MB) */
} ffc__mumps;

static int mumps_agree(const ffc__engine *e, int ok)
{
    return ffc__mpi_min((int)((const ffc__mumps *)e)->id.comm_fortran, ok);
}

static void call(ffc__mumps *m, int job)
{
    m->id.job = job;
    dmumps_c(&m->id);
}

/* a workspace that MUMPS's analysis estimated too small (integer, real,
 * send or receive buffers: INFOG(1) = -8, -9, -11, -14, -15, -17, -20).
 * Its dynamic scheduling maps the fronts by the ranks' loads at run time,
 * so on oversubscribed cores the same matrix may need more than the
 * estimate in one run and not in the next. */
static int short_workspace(int e)
{
    return e == -8 || e == -9 || e == -11 || e == -14 || e == -15 || e == -17 || e == -20;
}

/* job 4 (analysis and factorization) or 6 (and solve), run again with the
 * estimated workspace doubled, then 4 and 8 times (through ICNTL(14), the
 * percentage added to the estimate) while MUMPS finds it short; INFOG(1) is the same on every
 * rank, so all ranks loop alike. A solve's right-hand side (job 6: rhs,
 * overwritten) is restored from b[n] before each new try. */
static void call_relaxed(ffc__mumps *m, int job, const double *b, long n)
{
    const MUMPS_INT relax = m->id.ICNTL(14) > 0 ? m->id.ICNTL(14) : 20;
    call(m, job);
    for (int k = 1; k <= 3 && short_workspace(m->id.INFOG(1)); k++) {
        m->id.ICNTL(14) = relax * (1 << k) + 100 * ((1 << k) - 1);
        if (b && m->id.rhs && m->rank == 0) memcpy(m->id.rhs, b, (size_t)n * sizeof(double));
        call(m, job);
    }
    m->id.ICNTL(14) = relax;
}

/* a MUMPS instance of symmetry sym over the communicator fcomm (the
 * host works too); FFC_ERR_UNAVAILABLE before MPI_Init */
static int start(ffc__mumps *m, int fcomm, int sym)
{
    int init = 0;
    MPI_Initialized(&init);
    if (!init) return FFC_ERR_UNAVAILABLE;
    m->comm = MPI_Comm_f2c((MPI_Fint)fcomm);
    MPI_Comm_rank(m->comm, &m->rank);
    MPI_Comm_size(m->comm, &m->ranks);
    m->id.comm_fortran = (MUMPS_INT)fcomm;
    m->id.par = 1;
    m->id.sym = sym;
    call(m, -1);
    if (m->id.INFOG(1) < 0) return FFC_ERR_MEMORY;
    m->have = 1;
    return FFC_OK;
}

/* this rank's share of the entries: (ri, rj, rv)[nl] allocated (on every
 * rank, or FFC_ERR_MEMORY on every rank) and handed to MUMPS as its
 * distributed input; the caller fills them (1-based indices) */
static int share(ffc__mumps *m, long nl)
{
    free(m->ri); free(m->rj); free(m->rv);
    m->ri = malloc((size_t)(nl > 0 ? nl : 1) * sizeof(MUMPS_INT));
    m->rj = malloc((size_t)(nl > 0 ? nl : 1) * sizeof(MUMPS_INT));
    m->rv = malloc((size_t)(nl > 0 ? nl : 1) * sizeof(double));
    if (!mumps_agree(&m->base, m->ri && m->rj && m->rv)) return FFC_ERR_MEMORY;
    m->nloc = nl;
    DMUMPS_STRUC_C *id = &m->id;
    id->ICNTL(1) = -1; id->ICNTL(2) = -1; id->ICNTL(3) = -1; id->ICNTL(4) = 0;   /* kernels never print */
    id->ICNTL(18) = 3;       /* distributed input of the entries */
    id->nnz_loc = nl;
    id->nz_loc = (MUMPS_INT)nl;
    id->irn_loc = m->ri;
    id->jcn_loc = m->rj;
    id->a_loc = m->rv;
    return FFC_OK;
}

static void mumps_release(ffc__engine *e)
{
    e->factored = 0;
}

static void mumps_free(ffc__engine *e)
{
    ffc__mumps *m = (ffc__mumps *)e;
    if (!m) return;
    if (m->have) call(m, -2);
    free(m->ri); free(m->rj); free(m->rv);
    free(m);
}

/* this rank's share of A's entries, [lo, hi) of the list, handed to MUMPS */
static int take_share(ffc__mumps *m, const ffc__tri *A)
{
    const long lo = A->nz * m->rank / m->ranks, hi = A->nz * (m->rank + 1) / m->ranks, nl = hi - lo;
    if (share(m, nl)) return FFC_ERR_MEMORY;
    for (long k = 0; k < nl; k++) {
        m->ri[k] = (MUMPS_INT)A->i[lo + k] + 1;
        m->rj[k] = (MUMPS_INT)A->j[lo + k] + 1;
        m->rv[k] = A->v[lo + k];
    }
    return FFC_OK;
}

static int mumps_analyze(ffc__engine *e, const ffc__tri *A)
{
    ffc__mumps *m = (ffc__mumps *)e;
    if (A->n <= 0 || A->nz < 0 || A->n > 2147483647L)
        return ffc__engine_fail(e, FFC_ERR_SIZE, FFC_AT_COUNT, A->n, "MUMPS: order %ld out of range", A->n);
    e->factored = 0;
    e->n = A->n;
    if (take_share(m, A))
        return ffc__engine_fail(e, FFC_ERR_MEMORY, FFC_AT_COUNT, A->nz, "MUMPS: out of memory for %ld entries",
                                A->nz);
    DMUMPS_STRUC_C *id = &m->id;
    id->ICNTL(20) = 0;       /* dense right-hand sides, on the host */
    id->ICNTL(21) = 0;       /* the solution on the host, over the right-hand sides */
    id->ICNTL(24) = 1;       /* null pivots detected ... */
    id->CNTL(3) = 1e-12;     /* ... below 1e-12 of K's norm: CHOLMOD's rcond test */
    id->n = (MUMPS_INT)A->n;
    call(m, 1);              /* analysis */
    const int er = id->INFOG(1);
    if (er == -13 || er < 0)
        return ffc__engine_fail(e, FFC_ERR_MEMORY, FFC_AT_COUNT, A->n, "MUMPS: the analysis of a matrix of order "
                                "%ld with %ld entries failed (INFOG(1) = %d)", A->n, A->nz, er);
    return FFC_OK;
}

static int mumps_factorize(ffc__engine *e, const ffc__tri *A)
{
    ffc__mumps *m = (ffc__mumps *)e;
    if (A->n != e->n) return ffc__engine_fail(e, FFC_ERR_EMPTY, FFC_AT_NONE, -1, "MUMPS: not analysed");
    e->factored = 0;
    if (take_share(m, A))
        return ffc__engine_fail(e, FFC_ERR_MEMORY, FFC_AT_COUNT, A->nz, "MUMPS: out of memory for %ld entries",
                                A->nz);
    DMUMPS_STRUC_C *id = &m->id;
    call_relaxed(m, 2, NULL, 0);  /* factorization */
    const int er = id->INFOG(1);
    int st = FFC_OK;
    if (er == -10 || er == -40 || (er >= 0 && (id->INFOG(28) > 0 || id->INFOG(12) > 0))) st = FFC_ERR_SINGULAR;
    else if (er == -13 || er == -19 || short_workspace(er)) st = FFC_ERR_MEMORY;
    else if (er < 0) st = FFC_ERR_SINGULAR;
    e->info->rcond = 0.0;
    if (st == FFC_ERR_SINGULAR)
        return ffc__engine_fail(e, st, FFC_AT_NONE, -1, "MUMPS: the matrix is singular or not positive definite "
                                "(INFOG(1) = %d, null pivots %d, negative pivots %d)", er, (int)id->INFOG(28),
                                (int)id->INFOG(12));
    if (st)
        return ffc__engine_fail(e, st, FFC_AT_COUNT, A->n, "MUMPS: out of memory factorizing a matrix of order "
                                "%ld with %ld entries (INFOG(1) = %d)", A->n, A->nz, er);
    m->mb_rank = id->INFO(16);
    m->mb_max = id->INFOG(21);
    e->info->ranks = m->ranks;
    e->info->factor_mb = m->mb_rank;
    e->info->factor_mb_max = m->mb_max;
    e->factored = 1;
    return FFC_OK;
}

static int mumps_solve(ffc__engine *e, const double b[], double x[])
{
    ffc__mumps *m = (ffc__mumps *)e;
    if (!e->factored) return ffc__engine_fail(e, FFC_ERR_EMPTY, FFC_AT_NONE, -1, "MUMPS: not factorized");
    memcpy(x, b, (size_t)e->n * sizeof(double));
    /* the host's alone: MUMPS refuses a right-hand side on the other ranks
     * in a later sparse solve (inverse_piece) once one was given */
    m->id.rhs = m->rank == 0 ? x : NULL;
    m->id.nrhs = 1;
    m->id.lrhs = m->id.n;
    call(m, 3);
    if (m->id.INFOG(1) < 0)
        return ffc__engine_fail(e, FFC_ERR_MEMORY, FFC_AT_COUNT, e->n, "MUMPS: a solve of order %ld failed "
                                "(INFOG(1) = %d)", e->n, (int)m->id.INFOG(1));
    MPI_Bcast(x, (int)m->id.n, MPI_DOUBLE, 0, m->comm);
    return FFC_OK;
}

typedef struct { long key, pos; } keyed;   /* an index and where it stands in its list */
static int by_key(const void *a, const void *b)
{
    const long x = ((const keyed *)a)->key, y = ((const keyed *)b)->key;
    return (x > y) - (x < y);
}

/* Entries of the inverse: X[r + c * nrows] = (A^-1)[rows[r], cols[c]]
 * (no index twice in either list), on every rank.  MUMPS prunes its
 * forward and backward solves to the tree paths of the rows and columns
 * asked for (ICNTL(30)). */
static int inverse_piece(ffc__mumps *m, long ncols, const long cols[], long nrows, const long rows[], double X[])
{
    if (!m || (ncols > 0 && (!cols || !rows))) return FFC_ERR_NULL;
    if (!m->base.factored) return FFC_ERR_EMPTY;
    const long n = m->id.n, nz = ncols * nrows;
    if (ncols < 0 || nrows <= 0 || nz > 2147483646L) return FFC_ERR_SIZE;
    if (ncols == 0) return FFC_OK;
    for (long k = 0; k < ncols; k++) if (cols[k] < 0 || cols[k] >= n) return FFC_ERR_INDEX;
    for (long k = 0; k < nrows; k++) if (rows[k] < 0 || rows[k] >= n) return FFC_ERR_INDEX;
    /* MUMPS takes the entries column by column in increasing column order,
     * the rows of each in increasing order: cp and rp order cols and rows */
    keyed *cp = malloc((size_t)ncols * sizeof *cp), *rp = malloc((size_t)nrows * sizeof *rp);
    MUMPS_INT *ptr = malloc((size_t)(n + 1) * sizeof *ptr), *irs = malloc((size_t)nz * sizeof *irs);
    double *rs = malloc((size_t)nz * sizeof *rs);
    int st = mumps_agree(&m->base, cp && rp && ptr && irs && rs && X) ? FFC_OK : FFC_ERR_MEMORY;
    if (!st) {
        for (long k = 0; k < ncols; k++) cp[k] = (keyed){cols[k], k};
        for (long k = 0; k < nrows; k++) rp[k] = (keyed){rows[k], k};
        qsort(cp, (size_t)ncols, sizeof *cp, by_key);
        qsort(rp, (size_t)nrows, sizeof *rp, by_key);
        for (long k = 1; k < ncols && !st; k++) if (cp[k].key == cp[k - 1].key) st = FFC_ERR_VALUE;
        for (long k = 1; k < nrows && !st; k++) if (rp[k].key == rp[k - 1].key) st = FFC_ERR_VALUE;
    }
    if (!st) {
        long p = 0, c = 0;
        for (long j = 0; j < n; j++) {
            ptr[j] = (MUMPS_INT)(p + 1);
            if (c < ncols && cp[c].key == j) {
                for (long r = 0; r < nrows; r++) irs[p++] = (MUMPS_INT)rp[r].key + 1;
                c++;
            }
        }
        ptr[n] = (MUMPS_INT)(p + 1);
        DMUMPS_STRUC_C *id = &m->id;
        id->ICNTL(30) = 1;     /* entries of the inverse: both solves pruned to the rows and columns asked for */
        id->rhs = NULL;        /* (entries of the inverse are returned in rhs_sparse) */
        id->nrhs = (MUMPS_INT)n;
        id->lrhs = (MUMPS_INT)n;
        if (m->rank == 0) {  /* (the host's input; the other ranks' must stay unset) */
            id->nz_rhs = (MUMPS_INT)nz;
            id->irhs_ptr = ptr;
            id->irhs_sparse = irs;
            id->rhs_sparse = rs;
        }
        call(m, 3);
        id->ICNTL(30) = 0;
        id->irhs_ptr = id->irhs_sparse = NULL;
        id->rhs_sparse = NULL;
        id->nz_rhs = 0;
        if (id->INFOG(1) < 0) st = FFC_ERR_MEMORY;
        else {
            MPI_Bcast(rs, (int)nz, MPI_DOUBLE, 0, m->comm);
            for (long c2 = 0; c2 < ncols; c2++)
                for (long r = 0; r < nrows; r++) X[rp[r].pos + cp[c2].pos * nrows] = rs[r + c2 * nrows];
        }
    }
    free(cp); free(rp); free(ptr); free(irs); free(rs);
    return st;
}

enum { INV_ENTRIES = 1 << 21 };   /* values per piece (MUMPS's transient work: about 20 bytes each, 40 MB) */

static int mumps_inverse(ffc__engine *e, long nc, long cols[], long nrows, const long rows[], ffc__inv_sink sink,
                         void *ctx)
{
    ffc__mumps *m = (ffc__mumps *)e;
    if (nc <= 0) return FFC_OK;
    if (!e->factored) return ffc__engine_fail(e, FFC_ERR_EMPTY, FFC_AT_NONE, -1, "MUMPS: not factorized");
    const long chunk = nrows > 0 && INV_ENTRIES / nrows > 0 ? INV_ENTRIES / nrows : 1;
    double *V = malloc((size_t)(nrows > 0 ? nrows : 1) * (nc < chunk ? nc : chunk) * sizeof *V);
    int st = mumps_agree(e, V != NULL) ? FFC_OK : FFC_ERR_MEMORY;
    for (long k0 = 0; k0 < nc && !st; k0 += chunk) {
        const long n1 = nc - k0 < chunk ? nc - k0 : chunk;
        st = inverse_piece(m, n1, cols + k0, nrows, rows, V);
        if (!st) e->info->backsolves += n1;
        if (!st) st = sink(ctx, n1, cols + k0, V);
    }
    free(V);
    if (st == FFC_ERR_MEMORY)
        return ffc__engine_fail(e, st, FFC_AT_COUNT, nc, "MUMPS: out of memory for %ld columns of the inverse on "
                                "%ld rows", nc, nrows);
    return st;
}

static const ffc__engine_ops mumps_ops = {"MUMPS", mumps_analyze, mumps_factorize, mumps_solve, mumps_inverse,
                                          mumps_agree, mumps_release, mumps_free};

int ffc__mumps_create(ffc_solve_info *info, int fcomm, int sym, ffc__engine **out)
{
    if (!out || !info) return FFC_ERR_NULL;
    *out = NULL;
    ffc__mumps *m = calloc(1, sizeof *m);
    if (!m) return FFC_ERR_MEMORY;
    m->base.op = &mumps_ops;
    m->base.info = info;
    m->base.err.index = -1;
    /* symmetric: LDL^T (its null and negative pivots are counted; SYM=1 counts no null ones) */
    const int st = start(m, fcomm, sym ? 2 : 0);
    if (st) { free(m); return st; }
    info->ranks = m->ranks;
    info->factor_mb = info->factor_mb_max = 0.0;
    *out = &m->base;
    return FFC_OK;
}

int ffc__mumps_solve_once(int fcomm, int own, const ffc__tri *A, const double b[], double x[], ffc_error *err)
{
    const long n = A->n, nt = A->nz;
    ffc__mumps m = {0};
    int st = start(&m, fcomm, 0);   /* general: a contact tangent with friction is not symmetric */
    if (st) return st;
    const long lo = own ? 0 : nt * m.rank / m.ranks, nl = own ? nt : nt * (m.rank + 1) / m.ranks - lo;
    st = share(&m, nl);
    if (!st) {
        for (long k = 0; k < nl; k++) {
            m.ri[k] = (MUMPS_INT)A->i[lo + k] + 1;
            m.rj[k] = (MUMPS_INT)A->j[lo + k] + 1;
            m.rv[k] = A->v[lo + k];
        }
        DMUMPS_STRUC_C *id = &m.id;
        /* no null-pivot detection: like UMFPACK, a tiny pivot (a body that
         * only contact will hold) gives a huge solution along its rigid
         * motion, which the scene library's free-body step shortens; an
         * exactly zero pivot is refused (INFOG(1) = -10) */
        id->ICNTL(24) = 0;
        id->ICNTL(10) = -2;      /* two steps of iterative refinement (UMFPACK does two by default): the
                                    saddle matrices with tgv rows lost 1e-5 of a pressure without them */
        id->n = (MUMPS_INT)n;
        memcpy(x, b, (size_t)n * sizeof(double));
        id->rhs = m.rank == 0 ? x : NULL;   /* (the host's alone, as in mumps_solve) */
        id->nrhs = 1;
        id->lrhs = (MUMPS_INT)n;
        call_relaxed(&m, 6, b, n);  /* analysis, factorization and solve */
        const int e = id->INFOG(1);
        if (e == -10) st = FFC_ERR_SINGULAR;
        else if (e < 0) st = FFC_ERR_MEMORY;
        else MPI_Bcast(x, (int)n, MPI_DOUBLE, 0, m.comm);
        if (st && err) {
            err->status = st;
            err->where = FFC_AT_COUNT;
            err->index = n;
            snprintf(err->msg, sizeof err->msg, "MUMPS: %s (order %ld, %ld entries, INFOG(1) = %d)",
                     st == FFC_ERR_SINGULAR ? "a zero pivot" : "out of memory", n, nt, e);
        }
    }
    call(&m, -2);
    free(m.ri); free(m.rj); free(m.rv);
    return st;
}

#else /* a build without MPI */

int ffc__mumps_create(ffc_solve_info *info, int fcomm, int sym, ffc__engine **out)
{
    (void)info; (void)fcomm; (void)sym;
    if (out) *out = NULL;
    return FFC_ERR_UNAVAILABLE;
}
int ffc__mumps_solve_once(int fcomm, int own, const ffc__tri *A, const double b[], double x[], ffc_error *err)
{
    (void)fcomm; (void)own; (void)A; (void)b; (void)x; (void)err;
    return FFC_ERR_UNAVAILABLE;
}

#endif
