/* ffc_pdense.c: the dense LU of a condensed Newton system shared over the
 * ranks (ScaLAPACK's pdgetrf / pdgetrs on a 1 x N process grid, columns in
 * blocks of NB dealt out in turn); without -DFFC_MPI, FFC_ERR_UNAVAILABLE. */
#include <stdlib.h>

#include "ffc.h"
#include "ffc_pdense.h"

#ifdef FFC_MPI
#include <math.h>
#include <string.h>

#include <mpi.h>

enum { NB = 64 };   /* columns per block */

/* BLACS and ScaLAPACK (libscalapack-openmpi: no C header) */
int Csys2blacs_handle(MPI_Comm comm);
void Cblacs_gridinit(int *ctxt, const char *order, int nprow, int npcol);
void Cblacs_gridexit(int ctxt);
void Cfree_blacs_system_handle(int handle);
int numroc_(const int *n, const int *nb, const int *iproc, const int *isrc, const int *nprocs);
void descinit_(int *desc, const int *m, const int *n, const int *mb, const int *nb, const int *irsrc,
               const int *icsrc, const int *ctxt, const int *lld, int *info);
void pdgetrf_(const int *m, const int *n, double *a, const int *ia, const int *ja, const int *desca, int *ipiv,
              int *info);
void pdgetrs_(const char *trans, const int *n, const int *nrhs, const double *a, const int *ia, const int *ja,
              const int *desca, const int *ipiv, double *b, const int *ib, const int *jb, const int *descb,
              int *info);

struct ffc__pdense {
    MPI_Comm comm;       /* the ranks */
    int rank, ranks;
    int handle, ctxt;    /* BLACS system handle and grid context */
    long a;              /* order of the reserved matrix */
    long cap;            /* doubles allocated in A */
    double *A;           /* [a * nloc] this rank's columns (leading dimension a) */
    int *piv;            /* [a + NB] pivots */
    int factored;        /* 1: A holds the LU of an a x a matrix */
};

int ffc__pdense_create(int fcomm, ffc__pdense **out)
{
    if (!out) return FFC_ERR_NULL;
    *out = NULL;
    int init = 0;
    MPI_Initialized(&init);
    if (!init) return FFC_ERR_UNAVAILABLE;
    ffc__pdense *d = calloc(1, sizeof *d);
    if (!d) return FFC_ERR_MEMORY;
    d->comm = MPI_Comm_f2c((MPI_Fint)fcomm);
    MPI_Comm_rank(d->comm, &d->rank);
    MPI_Comm_size(d->comm, &d->ranks);
    d->handle = Csys2blacs_handle(d->comm);
    d->ctxt = d->handle;
    Cblacs_gridinit(&d->ctxt, "Row", 1, d->ranks);
    *out = d;
    return FFC_OK;
}

void ffc__pdense_free(ffc__pdense *d)
{
    if (!d) return;
    Cblacs_gridexit(d->ctxt);
    Cfree_blacs_system_handle(d->handle);
    free(d->A);
    free(d->piv);
    free(d);
}

/* columns of an a x a matrix on this rank */
static int local_cols(const ffc__pdense *d, long a)
{
    const int n = (int)a, nb = NB, zero = 0;
    return numroc_(&n, &nb, &d->rank, &zero, &d->ranks);
}

double *ffc__pdense_reserve(ffc__pdense *d, long a)
{
    if (!d || a <= 0 || a > 46340) return NULL;
    const long need = a * (long)(local_cols(d, a) > 0 ? local_cols(d, a) : 1);
    int ok = 1, all = 0;
    if (need > d->cap || !d->piv || a + NB > d->cap) {
        double *A = realloc(d->A, (size_t)need * sizeof(double));
        int *p = A ? realloc(d->piv, (size_t)(a + NB) * sizeof(int)) : NULL;
        if (A) d->A = A;
        if (p) { d->piv = p; d->cap = need > a + NB ? need : a + NB; }
        ok = A && p;
    }
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, d->comm);
    if (!all) return NULL;
    d->a = a;
    d->factored = 0;
    return d->A;
}

long ffc__pdense_local(const ffc__pdense *d, long j)
{
    const long blk = j / NB;
    if (blk % d->ranks != d->rank) return -1;
    return (blk / d->ranks) * NB + j % NB;
}

static int descriptor(const ffc__pdense *d, int m, int n, int nb, int desc[9])
{
    const int zero = 0, lld = m > 0 ? m : 1;
    int info = 0;
    descinit_(desc, &m, &n, &nb, &nb, &zero, &zero, &d->ctxt, &lld, &info);
    return info;
}

int ffc__pdense_factor(ffc__pdense *d, long a)
{
    if (!d || a != d->a) return FFC_ERR_SIZE;
    const int n = (int)a, one = 1;
    const long nl = local_cols(d, a);
    /* the largest entry, for the pivot test (max: the same bits everywhere) */
    double amax = 0.0;
    for (long k = 0; k < a * nl; k++) amax = fmax(amax, fabs(d->A[k]));
    MPI_Allreduce(MPI_IN_PLACE, &amax, 1, MPI_DOUBLE, MPI_MAX, d->comm);
    if (!isfinite(amax)) return FFC_ERR_NONFINITE;
    int desc[9], info = descriptor(d, n, n, NB, desc);
    if (info) return FFC_ERR_VALUE;
    pdgetrf_(&n, &n, d->A, &one, &one, desc, d->piv, &info);
    if (info < 0) return FFC_ERR_VALUE;
    /* every pivot (U's diagonal, in the columns each rank holds) */
    int ok = 1, all = 0;
    for (long j = 0; j < a; j++) {
        const long jl = ffc__pdense_local(d, j);
        if (jl >= 0 && !(fabs(d->A[j + jl * a]) > 1e-15 * amax)) ok = 0;
    }
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, d->comm);
    if (!all) return FFC_ERR_SINGULAR;
    d->factored = 1;
    return FFC_OK;
}

int ffc__pdense_solve(ffc__pdense *d, long a, double t[])
{
    if (!d || !t) return FFC_ERR_NULL;
    if (!d->factored || a != d->a) return FFC_ERR_EMPTY;
    const int n = (int)a, one = 1;
    int desca[9], descb[9], info = descriptor(d, n, n, NB, desca);
    if (!info) info = descriptor(d, n, 1, NB, descb);   /* the right-hand side: on rank 0 (grid column 0) */
    if (info) return FFC_ERR_VALUE;
    pdgetrs_("N", &n, &one, d->A, &one, &one, desca, d->piv, t, &one, &one, descb, &info);
    if (info) return FFC_ERR_VALUE;
    MPI_Bcast(t, n, MPI_DOUBLE, 0, d->comm);
    return FFC_OK;
}

#else

int ffc__pdense_create(int fcomm, ffc__pdense **out)
{
    (void)fcomm;
    if (out) *out = NULL;
    return FFC_ERR_UNAVAILABLE;
}
void ffc__pdense_free(ffc__pdense *d) { (void)d; }
double *ffc__pdense_reserve(ffc__pdense *d, long a) { (void)d; (void)a; return NULL; }
long ffc__pdense_local(const ffc__pdense *d, long j) { (void)d; (void)j; return -1; }
int ffc__pdense_factor(ffc__pdense *d, long a) { (void)d; (void)a; return FFC_ERR_UNAVAILABLE; }
int ffc__pdense_solve(ffc__pdense *d, long a, double t[]) { (void)d; (void)a; (void)t; return FFC_ERR_UNAVAILABLE; }

#endif
