/* ffc_mumps.c: a scene's bulk matrix factorized and solved by parallel
 * MUMPS over an MPI communicator (built with -DFFC_MPI; without it every
 * call answers FFC_ERR_UNAVAILABLE). */
#include <stdlib.h>

#include "ffc.h"
#include "ffc_mumps.h"
#include "ffc_internal.h"

#ifdef FFC_MPI

#include <math.h>
#include <string.h>

#include <dmumps_c.h>
#include <mpi.h>

#define ICNTL(k) icntl[(k) - 1]
#define INFOG(k) infog[(k) - 1]
#define INFO(k) info[(k) - 1]
#define CNTL(k) cntl[(k) - 1]

struct ffc__mumps {
    DMUMPS_STRUC_C id;         /* MUMPS's instance */
    MPI_Comm comm;             /* its communicator */
    int rank, ranks;           /* this rank, their count */
    int have;                  /* 1: initialized (job -1 done) */
    int factored;              /* 1: a factorization is held */
    MUMPS_INT *ri, *rj;        /* [nloc] this rank's share of the entries (1-based) */
    double *rv;                /* [nloc] */
    long nloc;
    double mb_rank, mb_max;    /* factorization memory: this rank's, the largest (MB) */
};

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
    if (!ffc__mumps_agree(m, m->ri && m->rj && m->rv)) return FFC_ERR_MEMORY;
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

int ffc__mumps_create(int fcomm, ffc__mumps **out)
{
    if (!out) return FFC_ERR_NULL;
    *out = NULL;
    ffc__mumps *m = calloc(1, sizeof *m);
    if (!m) return FFC_ERR_MEMORY;
    /* symmetric (LDL^T: its null and negative pivots are counted; SYM=1 counts no null ones) */
    const int st = start(m, fcomm, 2);
    if (st) { free(m); return st; }
    *out = m;
    return FFC_OK;
}

void ffc__mumps_free(ffc__mumps *m)
{
    if (!m) return;
    if (m->have) call(m, -2);
    free(m->ri); free(m->rj); free(m->rv);
    free(m);
}

int ffc__mumps_factor(ffc__mumps *m, long n, long nz, const int ti[], const int tj[], const double tv[])
{
    if (!m) return FFC_ERR_NULL;
    if (n <= 0 || nz < 0 || n > 2147483647L) return FFC_ERR_SIZE;
    /* this rank's share: the entries [lo, hi) */
    const long lo = nz * m->rank / m->ranks, hi = nz * (m->rank + 1) / m->ranks, nl = hi - lo;
    if (share(m, nl)) return FFC_ERR_MEMORY;
    for (long k = 0; k < nl; k++) {
        m->ri[k] = (MUMPS_INT)ti[lo + k] + 1;
        m->rj[k] = (MUMPS_INT)tj[lo + k] + 1;
        m->rv[k] = tv[lo + k];
    }
    DMUMPS_STRUC_C *id = &m->id;
    id->ICNTL(20) = 0;       /* dense right-hand sides, on the host */
    id->ICNTL(21) = 0;       /* the solution on the host, over the right-hand sides */
    id->ICNTL(24) = 1;       /* null pivots detected ... */
    id->CNTL(3) = 1e-12;     /* ... below 1e-12 of K's norm: CHOLMOD's rcond test */
    id->n = (MUMPS_INT)n;
    m->factored = 0;
    call_relaxed(m, 4, NULL, 0);  /* analysis and factorization */
    const int e = id->INFOG(1);
    if (e == -10 || e == -40 || (e >= 0 && (id->INFOG(28) > 0 || id->INFOG(12) > 0))) return FFC_ERR_SINGULAR;
    if (e == -13 || e == -19 || short_workspace(e)) return FFC_ERR_MEMORY;
    if (e < 0) return FFC_ERR_SINGULAR;
    m->mb_rank = id->INFO(16);
    m->mb_max = id->INFOG(21);
    m->factored = 1;
    return FFC_OK;
}

int ffc__mumps_solve(ffc__mumps *m, long nrhs, double B[])
{
    if (!m || !B) return FFC_ERR_NULL;
    if (!m->factored) return FFC_ERR_EMPTY;
    if (nrhs <= 0 || (long)m->id.n * nrhs > 2147483647L) return FFC_ERR_SIZE;
    /* the host's alone: MUMPS refuses a right-hand side on the other ranks
     * in a later sparse solve (ffc__mumps_inverse) once one was given */
    m->id.rhs = m->rank == 0 ? B : NULL;
    m->id.nrhs = (MUMPS_INT)nrhs;
    m->id.lrhs = m->id.n;
    call(m, 3);
    if (m->id.INFOG(1) < 0) return FFC_ERR_MEMORY;
    MPI_Bcast(B, (int)((long)m->id.n * nrhs), MPI_DOUBLE, 0, m->comm);
    return FFC_OK;
}

typedef struct { long key, pos; } keyed;   /* an index and where it stands in its list */
static int by_key(const void *a, const void *b)
{
    const long x = ((const keyed *)a)->key, y = ((const keyed *)b)->key;
    return (x > y) - (x < y);
}

int ffc__mumps_agree(ffc__mumps *m, int ok)
{
    return m ? ffc__mpi_min((int)m->id.comm_fortran, ok) : ok;
}

int ffc__mumps_inverse(ffc__mumps *m, long ncols, const long cols[], long nrows, const long rows[], double X[])
{
    if (!m || (ncols > 0 && (!cols || !rows))) return FFC_ERR_NULL;
    if (!m->factored) return FFC_ERR_EMPTY;
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
    int st = ffc__mumps_agree(m, cp && rp && ptr && irs && rs && X) ? FFC_OK : FFC_ERR_MEMORY;
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

int ffc_parallel_solve(const ffc_parallel *p, long n, long nt, const long Ti[], const long Tj[], const double Tv[],
                       const double b[], double x[], long *bad)
{
    if (!p || !b || !x || (nt > 0 && (!Ti || !Tj || !Tv))) return FFC_ERR_NULL;
    if (n <= 0 || nt < 0 || n > 2147483647L) return FFC_ERR_SIZE;
    if (p->engine != FFC_ENGINE_MUMPS) return p->engine == FFC_ENGINE_CHOLMOD ? FFC_ERR_UNAVAILABLE : FFC_ERR_VALUE;
    int st = ffc__check_triplets(n, nt, Ti, Tj, Tv, bad);
    if (st) return st;
    for (long i = 0; i < n; i++)
        if (!isfinite(b[i])) { if (bad) *bad = i; return FFC_ERR_NONFINITE; }
    ffc__mumps m = {0};
    st = start(&m, p->comm, 0);   /* general: a contact tangent with friction is not symmetric */
    if (st) return st;
    const long lo = p->own ? 0 : nt * m.rank / m.ranks, nl = p->own ? nt : nt * (m.rank + 1) / m.ranks - lo;
    st = share(&m, nl);
    if (!st) {
        for (long k = 0; k < nl; k++) {
            m.ri[k] = (MUMPS_INT)Ti[lo + k] + 1;
            m.rj[k] = (MUMPS_INT)Tj[lo + k] + 1;
            m.rv[k] = Tv[lo + k];
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
        id->rhs = m.rank == 0 ? x : NULL;   /* (the host's alone, as in ffc__mumps_solve) */
        id->nrhs = 1;
        id->lrhs = (MUMPS_INT)n;
        call_relaxed(&m, 6, b, n);  /* analysis, factorization and solve */
        const int e = id->INFOG(1);
        if (e == -10) st = FFC_ERR_SINGULAR;
        else if (e < 0) st = FFC_ERR_MEMORY;
        else MPI_Bcast(x, (int)n, MPI_DOUBLE, 0, m.comm);
    }
    call(&m, -2);
    free(m.ri); free(m.rj); free(m.rv);
    return st;
}

void ffc__mumps_info(const ffc__mumps *m, int *ranks, double *mb_rank, double *mb_max)
{
    if (ranks) *ranks = m ? m->ranks : 1;
    if (mb_rank) *mb_rank = m ? m->mb_rank : 0.0;
    if (mb_max) *mb_max = m ? m->mb_max : 0.0;
}

#else /* a build without MPI */

int ffc__mumps_create(int fcomm, ffc__mumps **out)
{
    (void)fcomm;
    if (out) *out = NULL;
    return FFC_ERR_UNAVAILABLE;
}
void ffc__mumps_free(ffc__mumps *m) { (void)m; }
int ffc_parallel_solve(const ffc_parallel *p, long n, long nt, const long Ti[], const long Tj[], const double Tv[],
                       const double b[], double x[], long *bad)
{
    (void)n; (void)nt; (void)Ti; (void)Tj; (void)Tv; (void)bad;
    if (!p || !b || !x) return FFC_ERR_NULL;
    return FFC_ERR_UNAVAILABLE;
}
int ffc__mumps_factor(ffc__mumps *m, long n, long nz, const int ti[], const int tj[], const double tv[])
{
    (void)m; (void)n; (void)nz; (void)ti; (void)tj; (void)tv;
    return FFC_ERR_UNAVAILABLE;
}
int ffc__mumps_solve(ffc__mumps *m, long nrhs, double B[])
{
    (void)m; (void)nrhs; (void)B;
    return FFC_ERR_UNAVAILABLE;
}
int ffc__mumps_agree(ffc__mumps *m, int ok)
{
    (void)m;
    return ok;
}
int ffc__mumps_inverse(ffc__mumps *m, long ncols, const long cols[], long nrows, const long rows[], double X[])
{
    (void)m; (void)ncols; (void)cols; (void)nrows; (void)rows; (void)X;
    return FFC_ERR_UNAVAILABLE;
}
void ffc__mumps_info(const ffc__mumps *m, int *ranks, double *mb_rank, double *mb_max)
{
    (void)m;
    if (ranks) *ranks = 1;
    if (mb_rank) *mb_rank = 0.0;
    if (mb_max) *mb_max = 0.0;
}

#endif
