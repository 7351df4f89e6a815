/* ffc_engine.h: the linear engines (CHOLMOD, UMFPACK, parallel MUMPS, PETSc)
 * behind one interface: analyze, factorize, solve, selected entries of
 * the inverse, release, free (internal). */
#ifndef FFC_ENGINE_H
#define FFC_ENGINE_H

#include "ffc.h"

/* A sparse matrix handed to an engine: triplets, 0-based int indices,
 * duplicates summed. */
typedef struct {
    long n;              /* order */
    long nz;             /* entries (count) */
    const int *i, *j;    /* [nz] row and column of each entry */
    const double *v;     /* [nz] values */
    int sym;             /* 1: the lower triangle of a symmetric positive definite matrix
                            (CHOLMOD, MUMPS LDL^T); 0: a general matrix (UMFPACK, MUMPS LU) */
} ffc__tri;

/* The ranks that share an engine's work (one process: size 1), with the
 * counts of an all-gather (ffc__mpi_allgather's layout). */
typedef struct {
    int comm;            /* the communicator (Fortran handle) */
    int rank, size;      /* this rank, the ranks */
    long *count;         /* [size] work: the values each rank contributes */
} ffc__ranks;

/* This rank's contiguous share [*lo, *hi) of n items and every rank's
 * count of values (unit per item) in r->count, in rank order. */
void ffc__ranks_share(ffc__ranks *r, long n, long unit, long *lo, long *hi);
/* The same with the items weighted by w[n] (each rank's weight about 1 /
 * size of the sum, an item to the rank that holds its middle). */
void ffc__ranks_share_by(ffc__ranks *r, long n, const double w[], long unit, long *lo, long *hi);

typedef struct ffc__engine ffc__engine;

/* Where selected entries of the inverse go, piece by piece:
 * V[r + k * nrows] = (A^-1)[rows[r], cols[k]] for k < nc; nonzero stops
 * the call with that status. */
typedef int (*ffc__inv_sink)(void *ctx, long nc, const long cols[], const double V[]);

/* The operations of an engine.  Each returns FFC_OK or a negative status
 * and, on failure, leaves the reason in the engine's err (kind, index,
 * message). */
typedef struct {
    const char *name;
    /* the ordering and symbolic factorization of A's pattern */
    int (*analyze)(ffc__engine *e, const ffc__tri *A);
    /* the numeric factorization of A, whose pattern was analyzed */
    int (*factorize)(ffc__engine *e, const ffc__tri *A);
    /* x[n] = A^-1 b[n] (distinct arrays; on every rank) */
    int (*solve)(ffc__engine *e, const double b[], double x[]);
    /* the entries of A^-1 on rows[nrows] in the columns cols[nc], handed
     * to sink in pieces; cols may be reordered in place (the order the
     * pieces come in) */
    int (*inverse)(ffc__engine *e, long nc, long cols[], long nrows, const long rows[], ffc__inv_sink sink,
                   void *ctx);
    /* 1 when ok is 1 on every rank that shares the engine (a collective call) */
    int (*agree)(const ffc__engine *e, int ok);
    /* the factor dropped (the engine kept) */
    void (*release)(ffc__engine *e);
    void (*free)(ffc__engine *e);
} ffc__engine_ops;

/* What every engine holds first. */
struct ffc__engine {
    const ffc__engine_ops *op;
    ffc_solve_info *info;   /* counters it adds to (backsolves, rcond, ranks, memory); never NULL */
    ffc_error err;          /* the reason of its last failure */
    long n;                 /* the order of the matrix last analyzed (0: none) */
    int factored;           /* 1: a numeric factor is held */
};

/* The engines.  info: the counters it adds to (kept by the caller, who
 * outlives the engine).  CHOLMOD on one process, or on every rank of
 * ranks->comm (ranks->size > 1: each making and holding the whole
 * factor, the inverse's columns shared out; ranks stays the caller's); UMFPACK on one process; MUMPS
 * over the ranks of fcomm (sym: 1 LDL^T of a symmetric positive definite
 * matrix, 0 LU).  FFC_ERR_UNAVAILABLE for MUMPS in a build without MPI or
 * before MPI_Init. */
int ffc__cholmod_create(ffc_solve_info *info, ffc__ranks *ranks, ffc__engine **out);
int ffc__umfpack_create(ffc_solve_info *info, ffc__engine **out);
int ffc__mumps_create(ffc_solve_info *info, int fcomm, int sym, ffc__engine **out);
/* PETSc's Krylov solvers and preconditioners (ffc_full_set_iterative), on
 * the ranks opt names; FFC_ERR_UNAVAILABLE in a build without PETSc.
 * ffc__petsc_info: its counters. */
int ffc__petsc_create(ffc_solve_info *info, const ffc_iterative *opt, ffc__engine **out);
int ffc__petsc_info(const ffc__engine *e, ffc_iterative_info *out);
/* the dofs[nb] (ascending, in [0, n)) its next set-ups solve exactly after
 * each multigrid cycle (nb = 0: none) */
int ffc__petsc_set_block(ffc__engine *e, long nb, const long dofs[]);

/* CHOLMOD only (test hooks and statistics; nothing for another engine):
 * the factor's kind from the next factorization (supernodal = 1: CHOLMOD's
 * supernodal factor whatever the size; 0: CHOLMOD chooses) and the
 * inverse's solves (prune = 1, the default: pruned to the paths of the
 * rows asked for; 0: whole back-solves); whether the factor is supernodal
 * and the share of its entries the last pruned backward solves visited. */
void ffc__cholmod_set_mode(ffc__engine *e, int supernodal, int prune);
/* the reciprocal condition below which a factor is singular (1e-12; 0:
 * only a factorization that fails is, as for a matrix whose Dirichlet
 * rows hold FreeFEM's tgv on the diagonal) */
void ffc__cholmod_set_rcond(ffc__engine *e, double min_rcond);
void ffc__cholmod_mode(const ffc__engine *e, int *supernodal, double *pruned);
/* MUMPS only: a general matrix's one-off solve A x = b on the ranks of
 * fcomm, each passing the same entries or (own = 1) its own (A their sum). */
int ffc__mumps_solve_once(int fcomm, int own, const ffc__tri *A, const double b[], double x[], ffc_error *err);

/* an engine's failure recorded: err = {st, kind, index, message} (printf
 * style); returns st */
int ffc__engine_fail(ffc__engine *e, int st, ffc_where kind, long index, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* The selected entries of the inverse by a solve of each unit vector, a
 * column at a time (an engine without pruned solves). */
int ffc__inverse_by_solves(ffc__engine *e, long nc, const long cols[], long nrows, const long rows[],
                           ffc__inv_sink sink, void *ctx);

#endif
