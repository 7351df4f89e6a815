/* ffc_bulk_state.h: the bulk's state, shared by the solvers on its linear
 * engine (ffc_bulk.c: K and its factor; ffc_columns.c: the compliance;
 * ffc_csolve.c: the condensed solve; ffc_cnewton.c, ffc_cdirection.c:
 * the condensed Newton; ffc_saddle.c: the node-to-surface saddle point);
 * internal. */
#ifndef FFC_BULK_STATE_H
#define FFC_BULK_STATE_H

#include "ffc_bulk.h"
#include "ffc_engine.h"
#include "ffc_pdense.h"

/* BLAS and LAPACK */
void dtrsm_(const char *side, const char *uplo, const char *ta, const char *diag, const int *m, const int *n,
            const double *alpha, const double *a, const int *lda, double *b, const int *ldb);
void dsyrk_(const char *uplo, const char *trans, const int *n, const int *k, const double *alpha, const double *a,
            const int *lda, const double *beta, double *c, const int *ldc);
void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
void dpotrs_(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda, double *b,
             const int *ldb, int *info);
void dgemv_(const char *trans, const int *m, const int *n, const double *alpha, const double *a, const int *lda,
            const double *x, const int *incx, const double *beta, double *y, const int *incy);
void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a, const int *lda, const int *ipiv,
             double *b, const int *ldb, int *info);

struct ffc__bulk {
    /* K (ffc_bulk.c) */
    long n;                    /* dofs */
    long nt;                   /* triplets of K */
    long *Ti, *Tj;             /* [nt] K's triplets (both triangles) */
    double *Tv;                /* [nt] (force/length) */
    double *diag;              /* [n] K's diagonal */
    long nlift;                /* K's triplets in a Dirichlet column of a free row (count) */
    long *lift;                /* [nlift] their indices (ffc__bulk_lift) */
    unsigned char *big;        /* [n] 1 on Dirichlet rows (diagonal >= 1e12 x the median) */
    double kfree;              /* mean diagonal of the other rows (force/length) */
    double *sh;                /* [n] shift s on the dofs of a singular K */
    /* the linear engine that factorizes K' + S */
    ffc__engine *eng;          /* CHOLMOD (default), or parallel MUMPS */
    ffc__ranks rk;             /* the ranks that hold the factor, each all of it (size 1: one process; with
                                  MUMPS, 1: it shares the factor itself) */
    int factored;              /* 1: a factor is held */
    ffc__pdense *pd;           /* the condensed Newton's dense LU shared over the ranks (NULL: none) */
    int kdist;                 /* 1: the kept LU (ka, kdof) is pd's, not klu */
    ffc_solve_info info;
    /* the compliance (ffc_columns.c) */
    long mmax;                 /* contact dofs C takes at most */
    long m, ld;                /* contact dofs, leading dimension of G */
    long *dof;                 /* [ld] contact dofs */
    double *G;                 /* [ld*ld] compliance (column-major) */
    long nr;                   /* rows R: the dofs the contact evaluation may read (count) */
    long *rows;                /* [nr] */
    long *rpos;                /* [n] position in rows, or -1 */
    double *H;                 /* [nr*ld] the compliance columns of C on the rows R (column-major, leading
                                  dimension nr; the rows of C in it are G's) */
    long *pos;                 /* [n] work (-1) */
    long *nd;                  /* [n] work: new contact dofs */
    double *A;                 /* [ld*ld] work: I + G Kcc (NULL until its first use) */
    long *piv;                 /* [ld] work */
    double *xc, *w, *r, *dx, *t; /* [ld], [n], [n], [n], [n] work */
    double *kv;                /* [kvcap] work: Kc's values without Dirichlet rows and columns */
    long kvcap;
    /* the condensed Newton (ffc_cnewton.c, ffc_cdirection.c) */
    double *Gc;                /* [ld*ld] Cholesky factor L of G (lower, leading dimension ld) */
    long mc;                   /* the dofs Gc covers (its first mc rows and columns) */
    long *ti, *tj;             /* [tcap] contact tangent triplets */
    double *tv;                /* [tcap] */
    long tcap;
    double *t_eval;            /* where the contact evaluations add their wall time (seconds), or NULL */
    double cstate[3];          /* the last contact evaluation's state (ffc__contact_fn: counts) */
    double *Mw, *Gw;           /* [wcap] the dense tangent and G on its support (a x a) */
    long wcap;
    long ka;                   /* the kept LU of the last direction: its order (0: none) */
    long *kdof;                /* [kcap] the dofs of its support, in order */
    double *klu;               /* [kcap*kcap] its LU factors (leading dimension ka) */
    int *kpiv;                 /* [kcap] its pivots */
    long kcap;
    double *gv;                /* [gcap] GMRES work: the Krylov basis and its Hessenberg matrix */
    long gcap;
    double *rv;                /* [rcap] ranked work: the terms' values, G U, the p x p system */
    long rcap;
    long *ri;                  /* [ricap] ranked work: the terms' starts and entries, pivots */
    long ricap;
    double *bprev, *xprev;     /* [n] the last closing solve, K'^-1 bprev = xprev (NULL until the first) */
    int prev;                  /* 1: they hold for the present factor */
};

/* ffc_bulk.c */
/* 1 when ok holds on every rank sharing the factor (a collective call) */
int ffc__bulk_all(const ffc__bulk *b, int ok);
/* st on every rank, or FFC_ERR_MEMORY where another rank failed */
int ffc__bulk_agree(const ffc__bulk *b, int st);
/* the factorization of K' + S, S = kfree on the dofs nd[nnew] */
int ffc__bulk_factorize(ffc__bulk *b, long nnew, const long nd[]);
/* K alone, then K + S on nd[nnew] when K is singular */
int ffc__bulk_factorize_first(ffc__bulk *b, long nnew, const long nd[]);
/* three nodes far apart in each body of the seeds (see the file) */
int ffc__bulk_spread_dofs(ffc__bulk *b, long nseed, const long seed[], long *nset);
/* y = (K' + S)^-1 rhs, one back-solve (timed, counted, checked finite) */
int ffc__bulk_backsolve(ffc__bulk *b, const double rhs[], double y[]);
/* t = rhs with the Dirichlet values lifted (the columns of K and of
 * (Ti, Tj, Tv)[nt] at those dofs moved to the right-hand side) */
void ffc__bulk_lift(const ffc__bulk *b, long nt, const long Ti[], const long Tj[], const double Tv[],
                    const double rhs[], double t[]);
/* r = rhs - (K + Kc) x */
void ffc__bulk_residual(const ffc__bulk *b, long nt, const long Ti[], const long Tj[], const double Tv[],
                        const double rhs[], const double x[], double r[]);

/* ffc_columns.c */
/* G and the dense work grown to hold m contact dofs */
int ffc__bulk_grow(ffc__bulk *b, long m);
/* the dense work A (NULL when out of memory) */
double *ffc__bulk_dense_a(ffc__bulk *b);
/* the compliance columns of the dofs nd[nnew] (timed) */
int ffc__bulk_add_columns(ffc__bulk *b, long nnew, const long nd[]);
/* the rows R set (see the file) */
int ffc__bulk_set_rows(ffc__bulk *b, long nr, const long rows[], long *bad);
/* nd[nnew] join C; FFC_ERR_CAPACITY past cap */
int ffc__bulk_add_to_c(ffc__bulk *b, long nnew, const long nd[], long cap, long *bad);
/* the shifted dofs that C lacks join it */
int ffc__bulk_shifted_into_c(ffc__bulk *b, long cap, long *bad);
/* the free dofs of cand[nc] (whole: of their nodes) into b->nd */
int ffc__bulk_free_dofs(ffc__bulk *b, long nc, const long cand[], int whole, long *nnew, long *bad);
/* Gc extended to the columns added since the last call */
int ffc__bulk_factor_g(ffc__bulk *b);
/* x = G^-1 x */
void ffc__bulk_g_inverse(const ffc__bulk *b, double x[]);

/* ffc_cdirection.c */
double ffc__dotn(long m, const double x[], const double y[]);
/* y = alpha A x + beta y (A n x k), shared over the ranks */
int ffc__bulk_gemv(ffc__bulk *b, long n, long k, double alpha, const double *A, long lda, const double x[],
                   double beta, double y[]);
/* the condensed Newton directions (see the file) */
int ffc__bulk_direction(ffc__bulk *b, long nt, const double rho[], double dy[], double dz[], long ap[], long ad[],
                        double q[], double t[], double s[], long *na, long *bad);
int ffc__bulk_direction_ranked(ffc__bulk *b, long nt, const double rho[], double dy[], double dz[], double q[],
                               double gdz[], long *np, long *bad);

#endif
