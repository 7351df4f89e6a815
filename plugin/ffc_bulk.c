/* ffc_bulk.c: the bulk stiffness of a small-strain scene factorized once
 * (CHOLMOD) and the Newton systems (K + Kc) x = b solved on the contact
 * dofs (the compliance G grown by pruned block solves, see ffc.h). */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <suitesparse/cholmod.h>

#include "ffc_bulk.h"
#include "ffc_internal.h"
#include "ffc_mumps.h"
#include "ffc_pdense.h"
#include "ffc_super.h"

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
void dtrsv_(const char *uplo, const char *ta, const char *diag, const int *n, const double *a, const int *lda,
            double *x, const int *incx);
void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a, const int *lda, const int *ipiv,
             double *b, const int *ldb, int *info);
void dgemm_(const char *ta, const char *tb, const int *m, const int *n, const int *k, const double *alpha,
            const double *a, const int *lda, const double *b, const int *ldb, const double *beta, double *c,
            const int *ldc);

enum { BLOCK = 128 };  /* compliance columns per block back-solve (README "Pruned solves": 128 against
                          64, the same at 44k dofs, about 10 % less at 141k) */
enum { REFRESH = 8 };  /* the condensed Newton recomputes y = d0_C + G z and H z from z every this many
                          iterations (between, it adds the steps G dz, H dz) */
enum { PDENSE_MIN = 200 }; /* on several ranks, the condensed Newton's dense LU of this order and more is
                              shared over them (ScaLAPACK); a smaller one is factorized on every rank */

struct ffc__bulk {
    long n;                    /* dofs */
    long nt;                   /* triplets of K */
    long *Ti, *Tj;             /* [nt] K's triplets (both triangles) */
    double *Tv;                /* [nt] (force/length) */
    double *diag;              /* [n] K's diagonal */
    long nlift;                /* K's triplets in a Dirichlet column of a free row (count) */
    long *lift;                /* [nlift] their indices (lift_dirichlet) */
    unsigned char *big;        /* [n] 1 on Dirichlet rows (diagonal >= 1e12 x the median) */
    double kfree;              /* mean diagonal of the other rows (force/length) */
    double *sh;                /* [n] shift s on the dofs of the first contact tangent */
    int started;               /* cholmod_start called */
    cholmod_common cc;
    cholmod_factor *L;         /* of K + diag(sh); NULL until the first solve */
    cholmod_dense *B, *X, *Y, *E;       /* one right-hand side and solve2's work */
    cholmod_dense *Bb, *Xb, *Yb, *Eb;   /* a block of BLOCK right-hand sides */
    ffc__mumps *mp;            /* parallel MUMPS in place of CHOLMOD's factor (NULL: CHOLMOD); B is then
                                  its right-hand side, solved in place, and Bb the zeroed work vector of
                                  the compliance columns (entries of K^-1, add_columns) */
    int factored;              /* 1: a factor (L, or MUMPS's) is held */
    ffc__pdense *pd;           /* with MUMPS: the dense LU shared over the same ranks (NULL: none) */
    int kdist;                 /* 1: the kept LU (ka, kdof) is pd's, not klu */
    long m, ld;                /* contact dofs, leading dimension of G */
    long *dof;                 /* [ld] contact dofs */
    double *G;                 /* [ld*ld] compliance (column-major) */
    long *pos;                 /* [n] work (-1) */
    long *nd;                  /* [n] work: new contact dofs */
    double *A;                 /* [ld*ld] work: I + G Kcc (NULL until its first use) */
    long *piv;                 /* [ld] work */
    double *xc, *w, *r, *dx, *t; /* [ld], [n], [n], [n], [n] work */
    double *kv;                /* [kvcap] work: Kc's values without Dirichlet rows and columns */
    long kvcap;
    long mmax;                 /* contact dofs this path takes at most */
    ffc_solve_info info;
    /* the condensed Newton (ffc__bulk_newton) */
    double *Gc;                /* [ld*ld] Cholesky factor L of G (lower, leading dimension ld) */
    long mc;                   /* the dofs Gc covers (its first mc rows and columns) */
    long *ti, *tj;             /* [tcap] contact tangent triplets */
    double *tv;                /* [tcap] */
    long tcap;
    double *t_eval;            /* where contact_eval adds its wall time (seconds), or NULL */
    double cstate[3];          /* the last contact evaluation's state (ffc__contact_fn: counts) */
    double *Mw, *Gw;           /* [wcap] the dense tangent and G on its support (a x a) */
    long wcap;
    /* the last dense LU of a condensed Newton direction, kept as the
     * preconditioner of the next ones on the same support (GMRES) */
    long ka;                   /* its order (0: none) */
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
    long nr;                   /* rows R: the dofs the contact evaluation may read (count) */
    long *rows;                /* [nr] */
    long *rpos;                /* [n] position in rows, or -1 */
    double *H;                 /* [nr*ld] the compliance columns of C on the rows R (column-major, leading
                                  dimension nr; the rows of C in it are G's) */
    /* CHOLMOD replicated on the ranks of a communicator: each computes a share of the compliance columns */
    int rcomm;                 /* the communicator (Fortran handle) */
    int rrank, rsize;          /* this rank, the ranks (rsize 1: one process, nothing shared) */
    long *rcount;              /* [rsize] work: the values each rank solved */
    int ncomm;                 /* the ranks of rcomm on this machine (Fortran handle; valid when nsize > 1) */
    int nrank, nsize;          /* this rank among them, their count: they factorize K by subtrees, each
                                  into its own L, and exchange the values (numeric_on_node) */
    int split;                 /* the machine's ranks that made the last factor's subtrees (ffc_super.c; 0: none) */
    signed char *spart;        /* [nsuper] their sets: each supernode's (-1: above the sets); NULL: no split
                                  (the machine's ranks did not make the factor together). The single
                                  back-solves are split the same way (split_solve) */
    double *sx;                /* [n + sbelow + n + split * ntop] split_solve's work (NULL until its first use) */
    long *scnt;                /* [nsize] its counts of values per rank */
    long sbelow, ntop;         /* the most rows below a supernode's diagonal block; the columns above the sets */
    /* the pruned solves of a supernodal factor (pruned_block), made with the factor */
    int prune;                 /* 1: compliance columns by pruned solves when L is supernodal (default) */
    int force_super;           /* 1: a supernodal L whatever its size (test hook; 0: CHOLMOD chooses) */
    int *ipm;                  /* [n] position of each dof in L's order (the inverse of L->Perm) */
    int *sn;                   /* [n] the supernode of each of L's columns */
    int *spar;                 /* [nsuper] each supernode's parent in the supernodal elimination tree, or -1 */
    int *sroot;                /* [nsuper] the root of each supernode's tree (the forest has one tree per
                                  part of K that nothing couples: each body, before contact) */
    unsigned char *smark;      /* [nsuper] work: 1 on the supernodes a solve visits */
    unsigned char *tmark;      /* [nsuper] work: 1 on the roots of the trees a block of columns lies in */
    double *sw;                /* [swcap] work: a supernode's rows below its diagonal block x BLOCK */
    double pshare;             /* the share of L's entries the last pruned backward solves visited */
    long swcap;
    /* the last condensed Newton's closing solve, K'^-1 bprev = xprev: the next call's first solve
     * when its right-hand side is the same (an augmentation of the same load step) */
    double *bprev, *xprev;     /* [n] (NULL until the first closing solve) */
    int prev;                  /* 1: they hold for the present factor */
};

/* 1 when ok holds on every rank of a shared factorization (MUMPS, or
 * CHOLMOD on every rank; a collective call), ok itself with one process */
static int all_ranks(const ffc__bulk *b, int ok)
{
    return b->mp ? ffc__mumps_agree(b->mp, ok) : b->rsize > 1 ? ffc__mpi_min(b->rcomm, ok) : ok;
}

/* Every rank of a shared factorization takes the same branch: st, or
 * FFC_ERR_MEMORY where another rank failed (st itself with one process). */
static int agree(const ffc__bulk *b, int st)
{
    return all_ranks(b, st == FFC_OK) ? FFC_OK : st ? st : FFC_ERR_MEMORY;
}

/* drops the pruned solves' tree and work (made again with the next factor) */
static void prune_free(ffc__bulk *b)
{
    free(b->ipm); free(b->sn); free(b->spar); free(b->sroot); free(b->smark); free(b->tmark); free(b->sw);
    b->ipm = b->sn = b->spar = b->sroot = NULL;
    b->smark = b->tmark = NULL;
    b->sw = NULL;
    b->swcap = 0;
}

/* the machine's communicator released (ranks alone again) */
static void node_free(ffc__bulk *b)
{
    if (b->nsize > 1) ffc__mpi_comm_free(b->ncomm);
    b->nsize = 1;
}

static void bulk_free_factor(ffc__bulk *b)
{
    if (!b->started) return;
    cholmod_dense **d[] = {&b->B, &b->X, &b->Y, &b->E, &b->Bb, &b->Xb, &b->Yb, &b->Eb};
    for (size_t k = 0; k < sizeof d / sizeof *d; k++)
        if (*d[k]) cholmod_free_dense(d[k], &b->cc);
    if (b->L) cholmod_free_factor(&b->L, &b->cc);
    b->split = 0;
    free(b->spart); free(b->sx); free(b->scnt);
    b->spart = NULL;
    b->sx = NULL;
    b->scnt = NULL;
    prune_free(b);
    b->prev = 0;
    b->factored = 0;
    b->m = 0;
}

void ffc__bulk_free(ffc__bulk *b)
{
    if (!b) return;
    bulk_free_factor(b);
    if (b->started) cholmod_finish(&b->cc);
    ffc__mumps_free(b->mp);
    ffc__pdense_free(b->pd);
    free(b->Ti); free(b->Tj); free(b->Tv); free(b->diag); free(b->big); free(b->sh); free(b->lift);
    free(b->dof); free(b->G); free(b->pos); free(b->nd); free(b->A); free(b->piv);
    free(b->rv); free(b->ri);
    free(b->xc); free(b->w); free(b->r); free(b->dx); free(b->t); free(b->kv);
    free(b->Gc); free(b->ti); free(b->tj); free(b->tv); free(b->Mw); free(b->Gw);
    free(b->rows); free(b->rpos); free(b->H); free(b->bprev); free(b->xprev);
    free(b->kdof); free(b->klu); free(b->kpiv); free(b->gv); free(b->rcount);
    node_free(b);
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
    b->prune = 1;
    b->rsize = 1;
    b->nsize = 1;
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
    double *d = malloc(nn * sizeof(double));
    if (!b->Ti || !b->Tj || !b->Tv || !b->diag || !b->big || !b->sh || !b->pos || !b->nd || !b->w || !b->r ||
        !b->dx || !b->t || !d) {
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
    ffc__mumps *m = NULL;
    const int st = ffc__mumps_create(fcomm, &m);
    if (st) return st;
    bulk_free_factor(b);
    ffc__mumps_free(b->mp);
    b->mp = m;
    b->rsize = 1;
    node_free(b);
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
    ffc__mumps_free(b->mp);
    b->mp = NULL;
    free(b->rcount);
    b->rcount = count;
    b->rcomm = fcomm;
    b->rrank = rank;
    b->rsize = size;
    node_free(b);
    int nc = 0, nr = 0, ns = 1;
    if (size > 1 && ffc__mpi_node(fcomm, &nc, &nr, &ns) == FFC_OK) {
        b->ncomm = nc;
        b->nrank = nr;
        b->nsize = ns;
        if (ns < 2) ffc__mpi_comm_free(nc);
    }
    shared_lu(b, fcomm, size > 1);
    return FFC_OK;
}

/* grows G (and the dense work) to hold m contact dofs: by a quarter at
 * least, in steps of 64 (doubling left up to three quarters of G, Gc and
 * A untouched but paid for, the kernel zeroing whole huge pages of them:
 * 4,459 contact dofs took 8,192^2 entries each, 512 MB) */
static int grow(ffc__bulk *b, long m)
{
    if (m <= b->ld) return FFC_OK;
    long ld = b->ld ? b->ld + b->ld / 4 : 64;
    if (ld < m) ld = m;
    ld = (ld + 63) / 64 * 64;
    const long top = (b->mmax + 63) / 64 * 64;   /* (never above the contact dofs' limit, rounded) */
    if (ld > top) ld = top > m ? top : m;
    double *G = calloc((size_t)ld * ld, sizeof(double));
    long *dof = malloc((size_t)ld * sizeof(long)), *piv = malloc((size_t)ld * sizeof(long));
    double *xc = malloc((size_t)ld * sizeof(double));
    double *Gc = malloc((size_t)ld * ld * sizeof(double));
    double *H = b->nr ? realloc(b->H, (size_t)b->nr * ld * sizeof(double)) : b->H;
    if (H) b->H = H;
    if (!G || !dof || !piv || !xc || !Gc || (b->nr && !H)) {
        free(G); free(dof); free(piv); free(xc); free(Gc);
        return FFC_ERR_MEMORY;
    }
    for (long c = 0; c < b->mc; c++) memcpy(Gc + c * ld, b->Gc + c * b->ld, (size_t)b->mc * sizeof(double));
    free(b->Gc);
    b->Gc = Gc;
    for (long c = 0; c < b->m; c++) {
        memcpy(G + c * ld, b->G + c * b->ld, (size_t)b->m * sizeof(double));
        dof[c] = b->dof[c];
    }
    free(b->G); free(b->A); free(b->dof); free(b->piv); free(b->xc);
    b->G = G; b->A = NULL; b->dof = dof; b->piv = piv; b->xc = xc; /* (A: at its first use, dense_a) */
    b->ld = ld;
    return FFC_OK;
}

/* the dense work A (ld x ld), allocated at its first use: the ranked
 * condensed Newton never needs it (NULL when out of memory) */
static double *dense_a(ffc__bulk *b)
{
    if (!b->A) b->A = malloc((size_t)b->ld * b->ld * sizeof(double));
    return b->A;
}

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* split_solve's work: x [n], the rows below one supernode [sbelow], the
 * values gathered [n + split * ntop: at most n, or the ranks' updates of
 * the rows above the sets], the counts [nsize] */
static int split_work(ffc__bulk *b)
{
    const cholmod_factor *L = b->L;
    const long ns = (long)L->nsuper;
    const int *super = L->super, *pi = L->pi;
    b->sbelow = 1;
    b->ntop = 0;
    for (long s = 0; s < ns; s++) {
        const long ncol = super[s + 1] - super[s], below = (pi[s + 1] - pi[s]) - ncol;
        if (below > b->sbelow) b->sbelow = below;
        if (b->spart[s] < 0) b->ntop += ncol;
    }
    b->sx = malloc((size_t)(2 * b->n + b->sbelow + b->split * b->ntop) * sizeof(double));
    b->scnt = malloc((size_t)b->nsize * sizeof(long));
    return b->sx && b->scnt ? FFC_OK : FFC_ERR_MEMORY;
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
 * supernodes above them (b->spart, as the machine's ranks factorized
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
static int split_solve(ffc__bulk *b, const double rhs[], double y[])
{
    if (!b->sx) {
        const int st = agree(b, split_work(b));
        if (st) {
            free(b->sx); free(b->scnt);
            b->sx = NULL;
            b->scnt = NULL;
            return st;
        }
    }
    const cholmod_factor *L = b->L;
    const long n = b->n, ns = (long)L->nsuper, ntop = b->ntop;
    const int *super = L->super, *perm = L->Perm;
    const signed char *part = b->spart;
    const int parts = b->split, me = b->nrank < parts ? b->nrank : -2;
    double *x = b->sx, *t = x + n, *g = t + b->sbelow;
    long *cnt = b->scnt;
    for (long k = 0; k < n; k++) x[k] = rhs[perm[k]];
    for (long s = 0; s < ns; s++)
        if (part[s] < 0) memset(x + super[s], 0, (size_t)(super[s + 1] - super[s]) * sizeof(double));
    for (long s = 0; s < ns; s++)
        if (part[s] == me) super_forward(L, s, x, t);
    int st = FFC_OK;
    if (ntop > 0) {
        for (int r = 0; r < b->nsize; r++) cnt[r] = r < parts ? ntop : 0;
        if (me >= 0)
            for (long s = 0, i = me * ntop; s < ns; s++)
                for (int c = super[s]; c < super[s + 1] && part[s] < 0; c++) g[i++] = x[c];
        st = ffc__mpi_allgather(b->ncomm, g, cnt);
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
    for (int r = 0; r < b->nsize; r++) cnt[r] = 0;
    for (long s = 0; s < ns; s++)
        if (part[s] >= 0) cnt[part[s]] += super[s + 1] - super[s];
    long off = 0;
    for (int r = 0; r < me; r++) off += cnt[r];
    for (long s = 0; s < ns && me >= 0; s++)
        for (int c = super[s]; c < super[s + 1] && part[s] == me; c++) g[off++] = x[c];
    st = ffc__mpi_allgather(b->ncomm, g, cnt);
    if (st) return st;
    off = 0;
    for (int r = 0; r < parts; r++)
        for (long s = 0; s < ns; s++)
            for (int c = super[s]; c < super[s + 1] && part[s] == r; c++) x[c] = g[off++];
    for (long k = 0; k < n; k++) y[perm[k]] = x[k];
    return FFC_OK;
}

/* y = (K + S)^-1 rhs, one back-solve */
static int backsolve_timed(ffc__bulk *b, const double rhs[], double y[])
{
    int st;
    if (b->spart && !b->mp) {   /* (the ranks of the machine split it) */
        st = agree(b, split_solve(b, rhs, y));
        b->info.split_solves += st == FFC_OK;
    } else {
        memcpy(b->B->x, rhs, (size_t)b->n * sizeof(double));
        if (b->mp) st = ffc__mumps_solve(b->mp, 1, b->B->x);
        else {   /* (CHOLMOD on every rank) */
            const int ok = cholmod_solve2(CHOLMOD_A, b->L, b->B, NULL, &b->X, NULL, &b->Y, &b->E, &b->cc);
            st = agree(b, ok ? FFC_OK : FFC_ERR_MEMORY);
        }
        if (!st) memcpy(y, b->mp ? b->B->x : b->X->x, (size_t)b->n * sizeof(double));
    }
    if (st) return st;
    b->info.backsolves++;
    for (long i = 0; i < b->n; i++)
        if (!isfinite(y[i])) return FFC_ERR_NONFINITE;
    return FFC_OK;
}

/* backsolve_timed, its wall time added to info.t_backsolves */
static int backsolve(ffc__bulk *b, const double rhs[], double y[])
{
    const double t0 = seconds();
    const int st = backsolve_timed(b, rhs, y);
    b->info.t_backsolves += seconds() - t0;
    return st;
}

/* b->info.rcond of the numeric b->L; a factor whose estimate is below
 * 1e-12 is refused (FFC_ERR_SINGULAR) */
static int conditioned(ffc__bulk *b)
{
    b->info.rcond = cholmod_rcond(b->L, &b->cc);
    return b->info.rcond >= 1e-12 ? FFC_OK : FFC_ERR_SINGULAR;
}

/* The numeric factorization of A into the analysed b->L; b->info.rcond */
static int numeric(ffc__bulk *b, cholmod_sparse *A)
{
    cholmod_factorize(A, b->L, &b->cc);
    if (b->cc.status == CHOLMOD_NOT_POSDEF || b->L->minor < b->L->n) return FFC_ERR_SINGULAR;
    if (b->cc.status < CHOLMOD_OK) return FFC_ERR_MEMORY;
    return conditioned(b);
}

/* the values of the runs of consecutive supernodes of set `part` of the
 * split (-1: those above the sets), broadcast from the machine's rank
 * `root` into every rank's L */
static int bcast_part(ffc__bulk *b, const signed char spart[], int part, int root)
{
    const cholmod_factor *L = b->L;
    const long ns = (long)L->nsuper;
    const int *px = L->px;
    double *x = L->x;
    for (long s = 0; s < ns;) {
        if (spart[s] != part) { s++; continue; }
        long e = s;
        while (e < ns && spart[e] == part) e++;
        const int st = ffc__mpi_bcast_from(b->ncomm, root, x + px[s], (long)px[e] - px[s]);
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
static int numeric_on_node(ffc__bulk *b, cholmod_sparse *A)
{
    const cholmod_factor *L = b->L;
    double sig[4] = {(double)L->xsize, (double)L->nsuper, (double)L->ssize, 0.0}, s0[4];
    const int *perm = L->Perm;
    for (size_t k = 0; k < L->n; k++) sig[3] += (double)perm[k] * (double)((k % 1021) + 1);
    memcpy(s0, sig, sizeof sig);
    int st = ffc__mpi_bcast_idle(b->ncomm, s0, 4);
    if (st) return st;
    const int same = ffc__mpi_min(b->ncomm, memcmp(s0, sig, sizeof sig) == 0);   /* (alike on the machine) */
    const int threads = ffc__mpi_min(b->rcomm, b->nsize);
    /* L made numeric (its values not yet touched) */
    cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, b->L, &b->cc);
    st = b->cc.status < CHOLMOD_OK || !b->L->x ? FFC_ERR_MEMORY : FFC_OK;
    int sst = FFC_OK;
    ffc__super *sp = same && !st ? ffc__super_create(b->L, A, threads, &sst) : NULL;
    if (!all_ranks(b, sp != NULL)) {
        ffc__super_free(sp);
        return numeric(b, A);
    }
    b->spart = malloc((size_t)b->L->nsuper);
    if (!all_ranks(b, b->spart != NULL)) {
        ffc__super_free(sp);
        return FFC_ERR_MEMORY;
    }
    memcpy(b->spart, ffc__super_parts(sp), (size_t)b->L->nsuper);
    b->split = threads;
    double *x = b->L->x, head[2] = {0.0, 0.0};   /* rank 0's status and rcond */
    int mine = 1;
    if (b->nrank < threads) {
        const int old = ffc__blas_threads(1);
        mine = ffc__super_numeric(sp, b->L, x, b->nrank) == FFC_OK;
        ffc__blas_threads(old);
    }
    const int all = ffc__mpi_min(b->ncomm, mine);
    for (int p = 0; p < threads && all && !st; p++) st = bcast_part(b, b->spart, p, p);
    if (st) {
        ffc__super_free(sp);
        return st;
    }
    if (b->nrank == 0) {
        head[0] = all ? FFC_OK : FFC_ERR_SINGULAR;
        if (all) {
            const int old = ffc__blas_threads(threads);
            head[0] = ffc__super_numeric(sp, b->L, x, -1);
            ffc__blas_threads(old);
        }
        if (head[0] == FFC_OK) head[0] = conditioned(b);
        head[1] = b->info.rcond;
    }
    ffc__super_free(sp);
    if ((st = ffc__mpi_bcast_idle(b->ncomm, head, 2))) return st;
    if (head[0] == FFC_OK && (st = bcast_part(b, b->spart, -1, 0))) return st;
    b->info.rcond = head[1];
    return (int)head[0];
}

/* the factorization of K' + S, S = diag(sh) on the dofs nd[nnew], K' = K
 * with each Dirichlet row and column replaced by kfree on the diagonal (the
 * values of those dofs are moved to the right-hand side: the same solution
 * as the tgv rows' to within 1/tgv, and a factor whose pivots show a
 * singular K: its estimated reciprocal condition below 1e-12 is refused) */
static int factorize_timed(ffc__bulk *b, long nnew, const long nd[])
{
    if (!b->started) {
        cholmod_start(&b->cc);
        b->cc.print = 0;              /* kernels never print */
        b->cc.error_handler = NULL;
        b->started = 1;
    }
    b->cc.supernodal = b->force_super ? CHOLMOD_SUPERNODAL : CHOLMOD_AUTO;
    for (long k = 0; k < nnew; k++) b->sh[nd[k]] = b->kfree;
    long nlow = 0;
    for (long t = 0; t < b->nt; t++) nlow += b->Ti[t] >= b->Tj[t] && !b->big[b->Ti[t]] && !b->big[b->Tj[t]];
    cholmod_triplet *T = cholmod_allocate_triplet((size_t)b->n, (size_t)b->n, (size_t)(nlow + b->n), -1,
                                                  CHOLMOD_REAL, &b->cc);
    int st = agree(b, T ? FFC_OK : FFC_ERR_MEMORY);   /* (a shared factorization: every rank enters it, or none) */
    if (st) {
        if (T) cholmod_free_triplet(&T, &b->cc);
        for (long k = 0; k < nnew; k++) b->sh[nd[k]] = 0.0;
        return st;
    }
    int *ti = T->i, *tj = T->j;
    double *tv = T->x;
    long c = 0;
    for (long t = 0; t < b->nt; t++)
        if (b->Ti[t] >= b->Tj[t] && !b->big[b->Ti[t]] && !b->big[b->Tj[t]]) {
            ti[c] = (int)b->Ti[t]; tj[c] = (int)b->Tj[t]; tv[c] = b->Tv[t]; c++;
        }
    for (long i = 0; i < b->n; i++)
        if (b->sh[i] != 0.0 || b->big[i]) { ti[c] = tj[c] = (int)i; tv[c] = b->big[i] ? b->kfree : b->sh[i]; c++; }
    T->nnz = (size_t)c;
    cholmod_sparse *A = NULL;
    if (b->mp) { /* MUMPS: the same lower triangle, shared out over the ranks */
        st = ffc__mumps_factor(b->mp, b->n, c, ti, tj, tv);
        b->info.rcond = 0.0;
    } else {
        A = cholmod_triplet_to_sparse(T, (size_t)c, &b->cc);
        if (!A) st = FFC_ERR_MEMORY;
        else {
            b->L = cholmod_analyze(A, &b->cc);
            if (!b->L) st = FFC_ERR_MEMORY;
        }
    }
    cholmod_free_triplet(&T, &b->cc);
    if (!b->mp) st = agree(b, st);   /* (every rank analysed A, or none goes on) */
    if (!st && !b->mp) {
        /* one factorization per machine when every rank has a machine-mate */
        const int node = b->rsize > 1 && all_ranks(b, b->L->is_super && b->nsize > 1);
        st = node ? numeric_on_node(b, A) : numeric(b, A);
    }
    if (A) cholmod_free_sparse(&A, &b->cc);
    if (!st) {
        b->B = cholmod_zeros((size_t)b->n, 1, CHOLMOD_REAL, &b->cc);
        b->Bb = cholmod_zeros((size_t)b->n, BLOCK, CHOLMOD_REAL, &b->cc);
        if (!b->B || !b->Bb) st = FFC_ERR_MEMORY;
    }
    st = agree(b, st);   /* (a shared factorization: one rank short of memory is every rank's failure) */
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

/* factorize_timed, its wall time added to info.t_factor */
static int factorize(ffc__bulk *b, long nnew, const long nd[])
{
    b->prev = 0;
    const double t0 = seconds();
    const int st = factorize_timed(b, nnew, nd);
    b->info.t_factor += seconds() - t0;
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
static int spread_dofs(ffc__bulk *b, long nseed, const long seed[], long *nset)
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
static int factorize_first(ffc__bulk *b, long nnew, const long nd[])
{
    int st = factorize(b, 0, NULL);
    if (st == FFC_ERR_SINGULAR && nnew > 0) st = factorize(b, nnew, nd);
    return st;
}

/* The supernodal elimination forest of L (parent of supernode s: the one
 * holding the first row below s's diagonal block, so after s), each
 * supernode's root, each dof's position in L's order and each position's
 * supernode; made once per factor. */
static int prune_tree(ffc__bulk *b)
{
    if (b->ipm) return FFC_OK;
    const cholmod_factor *L = b->L;
    const long n = b->n, ns = (long)L->nsuper;
    const int *perm = L->Perm, *super = L->super, *pi = L->pi, *ls = L->s;
    b->ipm = malloc((size_t)n * sizeof(int));
    b->sn = malloc((size_t)n * sizeof(int));
    b->spar = malloc((size_t)ns * sizeof(int));
    b->sroot = malloc((size_t)ns * sizeof(int));
    b->smark = calloc((size_t)ns, 1);
    b->tmark = calloc((size_t)ns, 1);
    long wrow = 0;
    for (long k = 0; k < ns; k++) {
        const long below = (pi[k + 1] - pi[k]) - (super[k + 1] - super[k]);
        if (below > wrow) wrow = below;
    }
    b->swcap = (wrow > 0 ? wrow : 1) * BLOCK;
    b->sw = malloc((size_t)b->swcap * sizeof(double));
    if (!b->ipm || !b->sn || !b->spar || !b->sroot || !b->smark || !b->tmark || !b->sw) {
        prune_free(b);
        return FFC_ERR_MEMORY;
    }
    for (long i = 0; i < n; i++) b->ipm[perm[i]] = (int)i;
    for (long k = 0; k < ns; k++)
        for (int c = super[k]; c < super[k + 1]; c++) b->sn[c] = (int)k;
    for (long k = 0; k < ns; k++) {
        const int ncol = super[k + 1] - super[k], nrow = pi[k + 1] - pi[k];
        b->spar[k] = nrow > ncol ? b->sn[ls[pi[k] + ncol]] : -1;
    }
    for (long k = ns - 1; k >= 0; k--) b->sroot[k] = b->spar[k] < 0 ? (int)k : b->sroot[b->spar[k]];
    return FFC_OK;
}

/* marks the supernodes on the paths from those of the dofs d[nd] to the root */
static void prune_mark(const ffc__bulk *b, long nd, const long d[])
{
    for (long k = 0; k < nd; k++)
        for (int s = b->sn[b->ipm[d[k]]]; s >= 0 && !b->smark[s]; s = b->spar[s]) b->smark[s] = 1;
}

/* the root of the tree that holds dof i's column of L */
static int prune_root(const ffc__bulk *b, long i)
{
    return b->sroot[b->sn[b->ipm[i]]];
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
 * zeros).  X (n x BLOCK, in L's order) is
 * zero on entry; the block's dofs are among the rows, so Fw lies in bw,
 * and the rows the backward solve visited are cleared at the end.  The
 * values on rows[nrows] go to V (nrows x nb). */
static void pruned_block(ffc__bulk *b, long nbl, const long d[], const unsigned char bw[], long nrows,
                         const long rows[], double V[])
{
    const cholmod_factor *L = b->L;
    const long n = b->n, ns = (long)L->nsuper;
    const int *super = L->super, *pi = L->pi, *px = L->px, *ls = L->s;
    const double *lx = L->x, one = 1.0, zero = 0.0, mone = -1.0;
    const int ldx = (int)n, nb = (int)nbl;
    double *X = b->Bb->x, *W = b->sw;
    const int *sroot = b->sroot;
    unsigned char *tmark = b->tmark;
    for (long k = 0; k < nbl; k++) {
        X[b->ipm[d[k]] + k * n] = 1.0;
        tmark[prune_root(b, d[k])] = 1;
    }
    prune_mark(b, nbl, d);   /* Fw */
    for (long s = 0; s < ns; s++) {   /* forward, children before parents */
        if (!b->smark[s]) continue;
        b->smark[s] = 0;
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
        for (long r = 0; r < nrows; r++) V[r + k * nrows] = X[b->ipm[rows[r]] + k * n];
    for (long s = 0; s < ns; s++)
        if (bw[s] && tmark[sroot[s]])
            for (long c = 0; c < nbl; c++)
                memset(X + super[s] + c * n, 0, (size_t)(super[s + 1] - super[s]) * sizeof(double));
    for (long k = 0; k < nbl; k++) tmark[prune_root(b, d[k])] = 0;
}

/* the same by whole back-solves (a simplicial factor, or pruning off) */
static int whole_block(ffc__bulk *b, long nbl, const long d[], long nrows, const long rows[], double V[])
{
    const long n = b->n;
    double *bx = b->Bb->x;
    memset(bx, 0, (size_t)n * BLOCK * sizeof(double));
    for (long k = 0; k < nbl; k++) bx[d[k] + k * n] = 1.0;
    const int ok = cholmod_solve2(CHOLMOD_A, b->L, b->Bb, NULL, &b->Xb, NULL, &b->Yb, &b->Eb, &b->cc);
    for (long k = 0; k < nbl; k++) bx[d[k] + k * n] = 0.0;   /* (Bb zero again, as pruned_block wants it) */
    if (!ok) return FFC_ERR_MEMORY;
    const double *xb = b->Xb->x;
    for (long k = 0; k < nbl; k++)
        for (long r = 0; r < nrows; r++) V[r + k * nrows] = xb[rows[r] + k * n];
    return FFC_OK;
}

/* the columns of K'^-1 at the dofs d[nc] on rows[nrows] into V (nrows x
 * nc), BLOCK at a time (bw: the rows' paths when pruned, else NULL) */
static int columns_on_rows(ffc__bulk *b, long nc, const long d[], const unsigned char *bw, long nrows,
                           const long rows[], double V[])
{
    for (long k0 = 0; k0 < nc; k0 += BLOCK) {
        const long nbl = nc - k0 < BLOCK ? nc - k0 : BLOCK;
        if (bw) pruned_block(b, nbl, d + k0, bw, nrows, rows, V + k0 * nrows);
        else {
            const int st = whole_block(b, nbl, d + k0, nrows, rows, V + k0 * nrows);
            if (st) return st;
        }
        b->info.backsolves += nbl;
    }
    return FFC_OK;
}

/* On the ranks of a replicated bulk: this rank's contiguous share
 * [*lo, *hi) of n items, and every rank's count of values (unit per item)
 * in b->rcount, in rank order (ffc__mpi_allgather's layout) */
static void rank_share(ffc__bulk *b, long n, long unit, long *lo, long *hi)
{
    for (int r = 0; r < b->rsize; r++) b->rcount[r] = (n * (r + 1) / b->rsize - n * r / b->rsize) * unit;
    *lo = n * b->rrank / b->rsize;
    *hi = n * (b->rrank + 1) / b->rsize;
}

/* the same share with the items weighted by w[n] (each rank's weight about
 * 1 / rsize of the sum, an item to the rank that holds its middle) */
static void rank_share_by(ffc__bulk *b, long n, const double w[], long unit, long *lo, long *hi)
{
    double all = 0.0, acc = 0.0;
    for (long k = 0; k < n; k++) all += w[k];
    for (long r = 0, k0 = 0, k = 0; r < b->rsize; r++, k0 = k) {
        const double goal = all * (double)(r + 1) / b->rsize;
        while (k < n && (r == b->rsize - 1 || acc + 0.5 * w[k] < goal)) acc += w[k++];
        b->rcount[r] = (k - k0) * unit;
        if (r == b->rrank) { *lo = k0; *hi = k; }
    }
}

/* The compliance columns of the dofs nd[nnew]: their values on the rows
 * read (C, the new dofs, R: each once), in pieces of at most INV_ENTRIES
 * values, each column put into the zero vector x on those rows only,
 * handed to the bookkeeping (G, dof, H) and cleared again.  Where they
 * come from:
 * - parallel MUMPS: entries of K^-1 by its pruned solves (ffc__mumps_inverse);
 * - CHOLMOD: pruned supernodal solves (pruned_block, the columns in the
 *   factor's order: a block's columns then share their paths) or whole
 *   back-solves;
 * - CHOLMOD replicated on the ranks of a communicator: each rank solves
 *   a contiguous share of each piece and the shares are gathered, so that
 *   every rank keeps every column (pruned: shares of equal work, a
 *   column's being its tree's part of the backward solves).
 * With several ranks every rank takes the same branches: a failure on one
 * is every rank's (FFC_ERR_MEMORY when it was another's). */
enum { INV_ENTRIES = 1 << 21 };   /* values per piece (MUMPS's transient work: about 20 bytes each, 40 MB;
                                     fewer columns per solve lost its pruning's gain) */

static int add_columns_timed(ffc__bulk *b, long nnew, const long nd[])
{
    int st = agree(b, grow(b, b->m + nnew));
    if (st) return st;
    const long n = b->n, m0 = b->m;
    const int pruned = !b->mp && b->prune && b->L->is_super;
    if ((st = agree(b, pruned ? prune_tree(b) : FFC_OK))) return st;
    long *rows = malloc((size_t)(m0 + nnew + b->nr + 1) * sizeof *rows), nrows = 0;
    long *d = malloc((size_t)(nnew + 1) * sizeof *d);
    double *x = calloc((size_t)n, sizeof *x);
    unsigned char *bw = pruned ? calloc((size_t)b->L->nsuper, 1) : NULL;
    double *tw = pruned && b->rsize > 1 ? calloc((size_t)b->L->nsuper + (size_t)nnew, sizeof *tw) : NULL;
    if (rows && x)
        for (long k = 0; k < m0 + nnew + b->nr; k++) {
            const long i = k < m0 ? b->dof[k] : k < m0 + nnew ? nd[k - m0] : b->rows[k - m0 - nnew];
            if (!x[i]) { x[i] = 1.0; rows[nrows++] = i; }
        }
    if (rows && x)
        for (long r = 0; r < nrows; r++) x[rows[r]] = 0.0;
    const long chunk = nrows > 0 && INV_ENTRIES / nrows > 0 ? INV_ENTRIES / nrows : 1;
    double *V = malloc((size_t)(nrows > 0 ? nrows : 1) * (nnew < chunk ? nnew : chunk) * sizeof *V);
    st = agree(b, rows && d && x && V && (!pruned || bw) && (!pruned || b->rsize == 1 || tw) ? FFC_OK
                                                                                            : FFC_ERR_MEMORY);
    if (!st) {
        memcpy(d, nd, (size_t)nnew * sizeof *d);
        if (pruned) {   /* the new columns in the factor's order; the rows' paths */
            for (long k = 0; k < nnew; k++) d[k] = ((long)b->ipm[nd[k]] << 32) | k;
            qsort(d, (size_t)nnew, sizeof *d, ffc__cmp_long);
            for (long k = 0; k < nnew; k++) d[k] = nd[d[k] & 0xffffffffL];
            prune_mark(b, nrows, rows);
            memcpy(bw, b->smark, (size_t)b->L->nsuper);
            memset(b->smark, 0, (size_t)b->L->nsuper);
            const int *super = b->L->super, *pi = b->L->pi;
            double vis = 0.0, all = 0.0;
            for (long k = 0; k < (long)b->L->nsuper; k++) {
                const double e = (double)(super[k + 1] - super[k]) * (pi[k + 1] - pi[k]);
                all += e;
                vis += bw[k] ? e : 0.0;
                if (tw && bw[k]) tw[b->sroot[k]] += e;   /* each tree's backward work */
            }
            b->pshare = vis / all;
            if (tw)   /* each column's work, after the trees' */
                for (long k = 0; k < nnew; k++) tw[b->L->nsuper + k] = tw[prune_root(b, d[k])];
        }
    }
    for (long k0 = 0; k0 < nnew && !st; k0 += chunk) {
        const long nc = nnew - k0 < chunk ? nnew - k0 : chunk;
        if (b->mp) st = ffc__mumps_inverse(b->mp, nc, d + k0, nrows, rows, V);
        else if (b->rsize > 1) {
            long lo = 0, hi = 0;
            if (tw) rank_share_by(b, nc, tw + b->L->nsuper + k0, nrows, &lo, &hi);
            else rank_share(b, nc, nrows, &lo, &hi);
            st = agree(b, columns_on_rows(b, hi - lo, d + k0 + lo, bw, nrows, rows, V + lo * nrows));
            if (!st) st = ffc__mpi_allgather(b->rcomm, V, b->rcount);
        } else
            st = columns_on_rows(b, nc, d + k0, bw, nrows, rows, V);
        if (b->mp && !st) b->info.backsolves += nc;
        for (long k = 0; k < nc && !st; k++) {
            for (long r = 0; r < nrows; r++) x[rows[r]] = V[r + k * nrows];
            st = ffc_reduced_add(n, b->ld, b->m, b->dof, b->G, x, d[k0 + k]);
            for (long r = 0; r < b->nr && !st; r++) b->H[r + b->m * b->nr] = x[b->rows[r]];
            for (long r = 0; r < nrows; r++) x[rows[r]] = 0.0;
            if (!st) b->m++;
        }
    }
    free(rows); free(d); free(x); free(bw); free(tw); free(V);
    if (st) return st;
    b->info.columns += nnew;
    return FFC_OK;
}

/* add_columns_timed, its wall time added to info.t_columns */
static int add_columns(ffc__bulk *b, long nnew, const long nd[])
{
    const double t0 = seconds();
    const int st = add_columns_timed(b, nnew, nd);
    b->info.t_columns += seconds() - t0;
    return st;
}

/* r = b - (K + Kc) x */
static void residual(const ffc__bulk *b, long nt, const long Ti[], const long Tj[], const double Tv[],
                     const double rhs[], const double x[], double r[])
{
    memcpy(r, rhs, (size_t)b->n * sizeof(double));
    for (long t = 0; t < b->nt; t++) r[b->Ti[t]] -= b->Tv[t] * x[b->Tj[t]];
    for (long t = 0; t < nt; t++) r[Ti[t]] -= Tv[t] * x[Tj[t]];
}

/* the residual's size: the free rows against |b_free| + max free diagonal
 * |x_free|; a Dirichlet row's residual / diagonal (the error of the imposed
 * value) against |x|_inf */
static double residual_size(const ffc__bulk *b, const double rhs[], const double x[], const double r[])
{
    double rf = 0.0, bf = 0.0, xf = 0.0, dmax = 0.0, xinf = 0.0, rd = 0.0;
    for (long i = 0; i < b->n; i++) {
        xinf = fmax(xinf, fabs(x[i]));
        if (b->big[i]) { rd = fmax(rd, fabs(r[i]) / b->diag[i]); continue; }
        rf += r[i] * r[i];
        bf += rhs[i] * rhs[i];
        xf += x[i] * x[i];
        dmax = fmax(dmax, b->diag[i]);
    }
    const double e1 = sqrt(rf) / (sqrt(bf) + dmax * sqrt(xf) + 1e-300);
    const double e2 = rd / (xinf + 1e-300);
    return fmax(e1, e2);
}

/* one solve of (K + Kc) x = rhs on the contact dofs (two back-solves):
 * the Dirichlet values g = rhs / diag on their rows, their columns of K and
 * Kc times g moved to the right-hand side, Kc without Dirichlet rows and
 * columns (b->kv, filled by the caller) */
/* t = rhs with the Dirichlet values g = rhs / diag on their rows (times
 * the factor's kfree) and the columns of K and Kc (Ti, Tj, Tv)[nt] at
 * those dofs, times g, moved to the right-hand side */
static void lift_dirichlet(const ffc__bulk *b, long nt, const long Ti[], const long Tj[], const double Tv[],
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

static int solve_once(ffc__bulk *b, long nt, const long Ti[], const long Tj[], const double Tv[],
                      const double rhs[], double x[])
{
    const long n = b->n;
    double *t = b->t;
    lift_dirichlet(b, nt, Ti, Tj, Tv, rhs, t);
    int st = backsolve(b, t, x);
    if (st) return st;
    if (b->m > 0 && !dense_a(b)) return FFC_ERR_MEMORY;
    st = ffc_reduced_solve(n, b->ld, b->m, b->dof, b->G, nt, Ti, Tj, b->kv, b->sh, x, b->xc, b->w, b->A, b->piv,
                           b->pos);
    if (st) return st;
    st = backsolve(b, b->w, b->r);
    if (st) return st;
    for (long i = 0; i < n; i++) x[i] -= b->r[i];
    return FFC_OK;
}

int ffc__bulk_solve(ffc__bulk *b, long nt, const long Ti[], const long Tj[], const double Tv[], const double rhs[],
                    double x[], long *bad)
{
    if (!b || !rhs || !x || (nt > 0 && (!Ti || !Tj || !Tv))) return FFC_ERR_NULL;
    if (nt < 0) return FFC_ERR_SIZE;
    const long n = b->n;
    int st = ffc__check_triplets(n, nt, Ti, Tj, Tv, bad);
    if (st) return st;
    for (long i = 0; i < n; i++)
        if (!isfinite(rhs[i])) {
            if (bad) *bad = i;
            return FFC_ERR_NONFINITE;
        }
    b->info.solves++;
    if (nt > b->kvcap) {
        double *kv = realloc(b->kv, (size_t)nt * sizeof(double));
        if (!kv) return FFC_ERR_MEMORY;
        b->kv = kv;
        b->kvcap = nt;
    }
    for (long t = 0; t < nt; t++) b->kv[t] = b->big[Ti[t]] || b->big[Tj[t]] ? 0.0 : Tv[t];
    /* the contact dofs that Kc touches for the first time */
    long nnew = 0;
    st = ffc_reduced_missing(n, b->m, b->dof, nt, Ti, Tj, b->kv, n, b->nd, &nnew, b->pos);
    if (st) return st;
    if (b->m + nnew > b->mmax) {
        if (bad) *bad = b->m + nnew;
        return FFC_ERR_CAPACITY;
    }
    if (!b->factored) {
        st = factorize_first(b, nnew, b->nd);
        if (st) return st;
    }
    if (nnew) {
        st = add_columns(b, nnew, b->nd);
        if (st) return st;
    }
    b->info.m = b->m;
    st = solve_once(b, nt, Ti, Tj, Tv, rhs, x);
    if (st) return st;
    /* iterative refinement: at most two corrections, while they help */
    residual(b, nt, Ti, Tj, Tv, rhs, x, b->r);
    double e = residual_size(b, rhs, x, b->r);
    for (int k = 0; k < 2 && e > 1e-13; k++) {
        double *dx = b->dx;
        memcpy(b->w, b->r, (size_t)n * sizeof(double)); /* solve_once overwrites w and r */
        st = solve_once(b, nt, Ti, Tj, Tv, b->w, dx);
        if (st) return st;
        for (long i = 0; i < n; i++) x[i] += dx[i];
        residual(b, nt, Ti, Tj, Tv, rhs, x, b->r);
        const double e2 = residual_size(b, rhs, x, b->r);
        b->info.refinements++;
        if (!(e2 < 0.5 * e)) { e = e2; break; }
        e = e2;
    }
    b->info.residual = e;
    if (!(e <= 1e-6)) return FFC_ERR_SINGULAR;
    return FFC_OK;
}

void ffc__bulk_info(const ffc__bulk *b, ffc_solve_info *info)
{
    if (b) *info = b->info;
    else memset(info, 0, sizeof *info);
    info->ranks = b ? b->rsize : 1;
    info->factor_ranks = b && b->spart ? b->nsize : 1;
    info->factor_split = b && b->spart ? b->split : 1;
    if (b && b->mp) ffc__mumps_info(b->mp, &info->ranks, &info->factor_mb, &info->factor_mb_max);
}

long ffc__bulk_n(const ffc__bulk *b) { return b ? b->n : 0; }

double ffc__bulk_kfree(const ffc__bulk *b) { return b ? b->kfree : 0.0; }

/* ------------------------------------------------- the condensed Newton */

/* The rows R: the dofs rows[nr] the contact evaluation may read.  A set
 * that is not within the kept one joins it and drops the compliance
 * columns (they lack the new rows; they are computed again as needed). */
static int set_rows(ffc__bulk *b, long nr, const long rows[], long *bad)
{
    const long n = b->n;
    if (!b->rpos) {
        if (!(b->rpos = malloc((size_t)n * sizeof(long)))) return FFC_ERR_MEMORY;
        for (long i = 0; i < n; i++) b->rpos[i] = -1;
    }
    long fresh = 0;
    for (long k = 0; k < nr; k++) {
        if (rows[k] < 0 || rows[k] >= n) { *bad = k; return FFC_ERR_INDEX; }
        fresh += b->rpos[rows[k]] < 0;
    }
    if (!fresh && (b->nr || !b->m)) return FFC_OK;
    long *rw = realloc(b->rows, (size_t)(b->nr + fresh + 1) * sizeof(long));
    if (!rw) return FFC_ERR_MEMORY;
    b->rows = rw;
    for (long k = 0; k < nr; k++)
        if (b->rpos[rows[k]] < 0) { b->rpos[rows[k]] = b->nr; b->rows[b->nr++] = rows[k]; }
    free(b->H);
    b->H = b->ld ? malloc((size_t)(b->nr ? b->nr : 1) * b->ld * sizeof(double)) : NULL;
    b->m = b->mc = 0;
    b->info.m = 0;
    return b->ld && !b->H ? FFC_ERR_MEMORY : FFC_OK;
}

/* the dofs nd[nnew] (free, not in C) join C: their compliance columns;
 * FFC_ERR_CAPACITY (*bad = the count C would have) beyond cap */
static int add_to_c(ffc__bulk *b, long nnew, const long nd[], long cap, long *bad)
{
    if (!nnew) return FFC_OK;
    if (b->m + nnew > cap) { *bad = b->m + nnew; return FFC_ERR_CAPACITY; }
    const int st = add_columns(b, nnew, nd);
    b->info.m = b->m;
    return st;
}

/* ------------------------------------------------- test hooks (ffc_bulk.h) */

void ffc__bulk_set_columns_mode(ffc__bulk *b, int supernodal, int prune)
{
    if (!b) return;
    b->force_super = supernodal != 0;
    b->prune = prune != 0;
}

int ffc__bulk_columns(ffc__bulk *b, long nr, const long rows[], long nnew, const long nd[], long *bad)
{
    if (!b || (nr > 0 && !rows) || (nnew > 0 && !nd) || !bad) return FFC_ERR_NULL;
    if (nr < 0 || nnew < 0) return FFC_ERR_SIZE;
    for (long k = 0; k < nnew; k++)
        if (nd[k] < 0 || nd[k] >= b->n) { *bad = k; return FFC_ERR_INDEX; }
    int st = b->factored ? FFC_OK : factorize(b, 0, NULL);
    if (!st) st = set_rows(b, nr, rows, bad);
    if (!st) st = add_to_c(b, nnew, nd, b->mmax, bad);
    return st;
}

long ffc__bulk_compliance(const ffc__bulk *b, const long **dof, const double **G, long *ld, const double **H,
                          int *supernodal, double *pruned)
{
    if (pruned) *pruned = b->pshare;
    if (dof) *dof = b->dof;
    if (G) *G = b->G;
    if (ld) *ld = b->ld;
    if (H) *H = b->H;
    if (supernodal) *supernodal = b->L && b->L->is_super;
    return b->m;
}

/* The free dofs of cand[nc] (each once), or with whole = 1 every free
 * dof of their nodes, into b->nd[*nnew] */
static int free_dofs(ffc__bulk *b, long nc, const long cand[], int whole, long *nnew, long *bad)
{
    long c = 0;
    int st = FFC_OK;
    for (long k = 0; k < nc && !st; k++) {
        if (cand[k] < 0 || cand[k] >= b->n) { *bad = k; st = FFC_ERR_INDEX; break; }
        const long d0 = whole ? cand[k] - cand[k] % 3 : cand[k], d1 = whole ? d0 + 2 : d0;
        for (long d = d0; d <= d1; d++) {
            if (d >= b->n || b->big[d] || b->pos[d] != -1) continue;
            b->pos[d] = -2;
            b->nd[c++] = d;
        }
    }
    for (long k = 0; k < c; k++) b->pos[b->nd[k]] = -1;
    *nnew = st ? 0 : c;
    return st;
}

/* the shifted dofs that C lacks join it (their shift is part of the
 * condensed problem: K + S factorized, -S on C) */
static int shifted_into_c(ffc__bulk *b, long cap, long *bad)
{
    for (long k = 0; k < b->m; k++) b->pos[b->dof[k]] = k;
    long nnew = 0;
    for (long i = 0; i < b->n; i++)
        if (b->sh[i] != 0.0 && b->pos[i] == -1) b->nd[nnew++] = i;
    for (long k = 0; k < b->m; k++) b->pos[b->dof[k]] = -1;
    return add_to_c(b, nnew, b->nd, cap, bad);
}

/* The first factorization: K alone; when K is singular (a body that only
 * contact holds), K + S shifted on the nodes the contact force reaches
 * (reach[nreach]), else on the linked points' facets (cand[nc]); see
 * factorize.  FFC_ERR_CAPACITY, no factor kept, when the shift would put
 * more than cap dofs in C.  The shifted dofs belong to C (their shift is
 * part of the condensed problem). */
static int first_factor(ffc__bulk *b, long nreach, const long reach[], long nc, const long cand[], long cap,
                        long *bad)
{
    int st = FFC_OK;
    if (!b->factored) {
        st = factorize(b, 0, NULL);
        for (int pass = 0; pass < 3 && st == FFC_ERR_SINGULAR; pass++) {
            long nset = 0;
            if (pass == 0) {   /* three nodes far apart in each body of the reach and the facets */
                long *sd = malloc((size_t)(nreach + nc + 1) * sizeof(long));
                if (!sd) return FFC_ERR_MEMORY;
                if (nreach) memcpy(sd, reach, (size_t)nreach * sizeof(long));
                if (nc) memcpy(sd + nreach, cand, (size_t)nc * sizeof(long));
                st = agree(b, spread_dofs(b, nreach + nc, sd, &nset));
                free(sd);
            } else
                st = pass == 2 ? free_dofs(b, nc, cand, 0, &nset, bad) : free_dofs(b, nreach, reach, 1, &nset, bad);
            if (st) return st;
            if (!nset) { st = FFC_ERR_SINGULAR; continue; }
            if (b->m + nset > cap) { *bad = b->m + nset; return FFC_ERR_CAPACITY; }
            st = factorize(b, nset, b->nd);
        }
        if (st) return st;
    }
    return shifted_into_c(b, cap, bad);
}

/* the free dofs outside C that the force in b->r or a triplet of the
 * tangent (b->ti, tj, tv)[nt] (free row and column; with ranked, the
 * FFC_TANGENT_RANKED form, its row: tj is a term) reaches, into
 * b->nd[*nnew]; FFC_ERR_INDEX (*bad = the dof) for one outside the rows */
static int reached(ffc__bulk *b, long nt, int ranked, long *nnew, long *bad)
{
    long *pos = b->pos, c = 0;
    int st = FFC_OK;
    for (long k = 0; k < b->m; k++) pos[b->dof[k]] = k;
#define REACH(i_)                                                                                                  \
    do {                                                                                                           \
        const long d_ = (i_);                                                                                      \
        if (b->big[d_] || pos[d_] != -1) break;                                                                    \
        if (b->rpos[d_] < 0) { *bad = d_; st = FFC_ERR_INDEX; break; }                                             \
        pos[d_] = -2;                                                                                              \
        b->nd[c++] = d_;                                                                                           \
    } while (0)
    for (long i = 0; i < b->n && !st; i++)
        if (b->r[i] != 0.0) REACH(i);
    for (long e = 0; e < nt && !st; e++)
        if (ranked) {
            if (b->tv[e] != 0.0) REACH(b->ti[e]);
        } else if (b->tv[e] != 0.0 && !b->big[b->ti[e]] && !b->big[b->tj[e]]) {
            REACH(b->ti[e]);
            if (!st) REACH(b->tj[e]);
        }
#undef REACH
    for (long k = 0; k < c; k++) pos[b->nd[k]] = -1;
    for (long k = 0; k < b->m; k++) pos[b->dof[k]] = -1;
    *nnew = st ? 0 : c;
    return st;
}

/* Gc = the Cholesky factor L of G, extended to the columns added since
 * the last call: with G = [G11 G12; G21 G22] and L11 known,
 * L21 = (L11^-1 G12)^T and L22 = chol(G22 - L21 L21^T), O(mc^2 k) for k
 * new columns (a factorization from scratch would take m^3 / 3 at every
 * growth of C) */
static int factor_g(ffc__bulk *b)
{
    const long m = b->m, mc = b->mc, k = m - mc, ld = b->ld;
    if (k == 0) return FFC_OK;
    if (ld > 2147483647L) return FFC_ERR_SIZE;
    const int mci = (int)mc, ki = (int)k, ldi = (int)ld;
    const double one = 1.0, mone = -1.0;
    double *L = b->Gc;
    /* the new columns' rows: G12 into L's upper block, then solved and
     * moved below the diagonal */
    for (long j = mc; j < m; j++) memcpy(L + j * ld, b->G + j * ld, (size_t)m * sizeof(double));
    if (mc > 0) {
        dtrsm_("L", "L", "N", "N", &mci, &ki, &one, L, &ldi, L + mc * ld, &ldi); /* L11^-1 G12 */
        for (long j = mc; j < m; j++)
            for (long i = 0; i < mc; i++) L[j + i * ld] = L[i + j * ld];  /* L21 = (L11^-1 G12)^T */
        dsyrk_("L", "N", &ki, &mci, &mone, L + mc, &ldi, &one, L + mc + mc * ld, &ldi); /* G22 - L21 L21^T */
    }
    int info = 0;
    dpotrf_("L", &ki, L + mc + mc * ld, &ldi, &info);
    if (info) return FFC_ERR_SINGULAR;
    b->mc = m;
    return FFC_OK;
}

/* x = G^-1 x (m) */
static void g_inverse(const ffc__bulk *b, double x[])
{
    const int mi = (int)b->m, one = 1, ldi = (int)b->ld;
    int info = 0;
    if (mi) dpotrs_("L", &mi, &one, b->Gc, &ldi, x, &mi, &info);
}

/* the contact force F (into b->r) and, with a tangent, its triplets
 * (b->ti, tj, tv)[*nt] at w; the triplet buffers grow as needed */
static int contact_eval(ffc__bulk *b, ffc__contact_fn fn, void *ctx, const double w[], int tangent, long *nt,
                        double *fmag, long *bad)
{
    long need = tangent && b->tcap == 0 ? 4096 : 0;
    for (int pass = 0; pass < 3; pass++) {
        if (need > b->tcap) {
            long *ti = realloc(b->ti, (size_t)need * sizeof(long));
            if (ti) b->ti = ti;
            long *tj = ti ? realloc(b->tj, (size_t)need * sizeof(long)) : NULL;
            if (tj) b->tj = tj;
            double *tv = tj ? realloc(b->tv, (size_t)need * sizeof(double)) : NULL;
            if (!tv) return FFC_ERR_MEMORY;
            b->tv = tv;
            b->tcap = need;
        }
        memset(b->r, 0, (size_t)b->n * sizeof(double));
        const double t0 = seconds();
        int st = fn(ctx, w, tangent, b->r, tangent ? b->tcap : 0, b->ti, b->tj, b->tv, nt, fmag, b->cstate, bad);
        if (b->t_eval) *b->t_eval += seconds() - t0;
        if (st != FFC_ERR_CAPACITY || !tangent) return st;
        need = *nt + *nt / 2 + 64;
    }
    return FFC_ERR_CAPACITY;
}

/* Fp = F_C - sh_C y from the force in b->r; FFC_ERR_INDEX (*bad = the
 * dof) when the force reaches a free dof outside C */
static int force_c(const ffc__bulk *b, const double y[], double Fp[], long *bad)
{
    for (long k = 0; k < b->m; k++) b->pos[b->dof[k]] = k;
    int st = FFC_OK;
    for (long i = 0; i < b->n && !st; i++)
        if (b->r[i] != 0.0 && !b->big[i] && b->pos[i] < 0) { *bad = i; st = FFC_ERR_INDEX; }
    for (long k = 0; k < b->m; k++) {
        const long d = b->dof[k];
        Fp[k] = b->r[d] - b->sh[d] * y[k];
        if (!isfinite(Fp[k])) { *bad = d; st = st ? st : FFC_ERR_NONFINITE; }
        b->pos[d] = -1;
    }
    return st;
}

static double dot(long m, const double x[], const double y[])
{
    double v = 0.0;
    for (long k = 0; k < m; k++) v += x[k] * y[k];
    return v;
}

/* the full step taken on the residual alone (rt[m]: rho there, the last
 * evaluation; rn: |rho| at the start, s0 its contact state): |rho| at
 * least halved and the contact state as it was, no kink of the law between */
static int full_step_taken(const ffc__bulk *b, long m, const double rt[], double rn, const double s0[3])
{
    return sqrt(dot(m, rt, rt)) <= 0.5 * rn && b->cstate[0] == s0[0] && b->cstate[1] == s0[1] &&
           b->cstate[2] == s0[2];
}

enum { KRYLOV = 20 };       /* GMRES: basis vectors per cycle */
enum { RANKED_SLOW = 2 };   /* the condensed Newton: ranked iterations that did not gain 10x on an
                               unchanged active set before the rest of a call takes the consistent
                               tangent */

/* Solves (I + Gaa M) t = t (a x a, both dense column-major) by GMRES,
 * right-preconditioned with the kept LU of an earlier system on the same
 * support, to a true residual of 1e-14 of the right-hand side (the LU's
 * own accuracy: a looser one costs Newton iterations on a penalty-stiff
 * system).  Returns the iterations, or -1 when it does not get there in
 * two cycles (t is then unchanged: the caller factorizes afresh). */
/* y[n] += v x[n] (distinct arrays; GCC's -O2 cost model leaves the loop
 * scalar, the "cheap" one vectorizes it: element by element, the same
 * results) */
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("tree-loop-vectorize", "vect-cost-model=cheap")))
#endif
static void axpy(long n, double v, const double *restrict x, double *restrict y)
{
    for (long r = 0; r < n; r++) y[r] += v * x[r];
}

/* w[a] overwritten by the kept LU's solution (shared over the ranks when
 * it is pd's); nonzero on failure */
static int kept_solve(ffc__bulk *b, long a, double w[])
{
    if (b->kdist) return ffc__pdense_solve(b->pd, a, w);
    const int ai = (int)a, one = 1;
    int info = 0;
    dgetrs_("N", &ai, &one, b->klu, &ai, b->kpiv, w, &ai, &info);
    return info;
}

static int gmres_kept(ffc__bulk *b, long a, const double M[], const double Gaa[], double t[])
{
    const long k1 = KRYLOV + 1, need = a * (k1 + 4) + k1 * KRYLOV + 3 * k1;
    if (need > b->gcap) {
        double *g = realloc(b->gv, (size_t)need * sizeof(double));
        if (!g) return -1;
        b->gv = g;
        b->gcap = need;
    }
    double *V = b->gv, *x = V + a * k1, *w = x + a, *z = w + a, *rb = z + a, *H = rb + a, *cs = H + k1 * KRYLOV,
           *sn = cs + k1, *g = sn + k1;
    const int ai = (int)a, one = 1;
    const double d1 = 1.0, d0 = 0.0;
    int iters = 0;
    double bn = 0.0;
    for (long r = 0; r < a; r++) { rb[r] = t[r]; x[r] = 0.0; bn += t[r] * t[r]; }
    bn = sqrt(bn);
    if (bn == 0.0) return 0;
    /* w = A v = v + Gaa (M v) */
#define AMUL(v_, out_)                                                                                             \
    do {                                                                                                           \
        dgemv_("N", &ai, &ai, &d1, M, &ai, (v_), &one, &d0, z, &one);                                              \
        memcpy((out_), (v_), (size_t)a * sizeof(double));                                                          \
        dgemv_("N", &ai, &ai, &d1, Gaa, &ai, z, &one, &d1, (out_), &one);                                          \
    } while (0)
    for (int cycle = 0; cycle < 2; cycle++) {
        /* r = b - A x into V[:, 0] */
        AMUL(x, w);
        double beta = 0.0;
        for (long r = 0; r < a; r++) { V[r] = rb[r] - w[r]; beta += V[r] * V[r]; }
        beta = sqrt(beta);
        if (beta <= 1e-14 * bn) {
            memcpy(t, x, (size_t)a * sizeof(double));
            return iters;
        }
        for (long r = 0; r < a; r++) V[r] /= beta;
        for (long i = 0; i < k1; i++) g[i] = 0.0;
        g[0] = beta;
        long j = 0;
        for (; j < KRYLOV; j++) {
            /* w = A P^-1 V[:, j] */
            memcpy(w, V + j * a, (size_t)a * sizeof(double));
            if (kept_solve(b, a, w)) return -1;
            double *vj1 = V + (j + 1) * a;
            AMUL(w, vj1);
            iters++;
            double *h = H + j * k1;
            for (long i = 0; i <= j; i++) { /* modified Gram-Schmidt */
                h[i] = dot(a, vj1, V + i * a);
                for (long r = 0; r < a; r++) vj1[r] -= h[i] * V[i * a + r];
            }
            h[j + 1] = sqrt(dot(a, vj1, vj1));
            if (h[j + 1] > 0.0)
                for (long r = 0; r < a; r++) vj1[r] /= h[j + 1];
            for (long i = 0; i < j; i++) { /* earlier rotations */
                const double hi = cs[i] * h[i] + sn[i] * h[i + 1];
                h[i + 1] = -sn[i] * h[i] + cs[i] * h[i + 1];
                h[i] = hi;
            }
            const double rr = hypot(h[j], h[j + 1]);
            if (!(rr > 0.0)) return -1;
            cs[j] = h[j] / rr;
            sn[j] = h[j + 1] / rr;
            h[j] = rr;
            h[j + 1] = 0.0;
            g[j + 1] = -sn[j] * g[j];
            g[j] *= cs[j];
            if (fabs(g[j + 1]) <= 1e-15 * bn) { j++; break; }
        }
        /* y = H^-1 g (upper triangular j x j), x += P^-1 V y */
        for (long i = j - 1; i >= 0; i--) {
            double v = g[i];
            for (long c = i + 1; c < j; c++) v -= H[c * k1 + i] * g[c];
            g[i] = v / H[i * k1 + i];
        }
        for (long r = 0; r < a; r++) w[r] = 0.0;
        for (long i = 0; i < j; i++)
            for (long r = 0; r < a; r++) w[r] += g[i] * V[i * a + r];
        if (kept_solve(b, a, w)) return -1;
        for (long r = 0; r < a; r++) x[r] += w[r];
    }
    /* the true residual after the last cycle */
    AMUL(x, w);
    double rn = 0.0;
    for (long r = 0; r < a; r++) rn += (rb[r] - w[r]) * (rb[r] - w[r]);
#undef AMUL
    if (!(sqrt(rn) <= 1e-14 * bn)) return -1;
    memcpy(t, x, (size_t)a * sizeof(double));
    return iters;
}

/* Products with G, H and G U on the ranks of a replicated bulk (rsize >
 * 1): each rank computes a contiguous share of the rows (of the columns
 * for G U) and one all-gather gives every rank all of them.  These
 * products are bound by memory bandwidth, which the ranks of one machine
 * share: computed whole on every rank, two ranks took each one about
 * twice as long as one process; shared, G and H are streamed once in all.
 * Every value is that of the rank that computed it: the same bits on
 * every rank.  Below SHARE_MIN entries every rank computes the product
 * whole (the all-gather's latency would cost more). */
enum { SHARE_MIN = 1 << 15 };

/* y = alpha A x + beta y, A n x k (column-major, leading dimension lda) */
static int shared_gemv(ffc__bulk *b, long n, long k, double alpha, const double *A, long lda, const double x[],
                       double beta, double y[])
{
    const int one = 1, ki = (int)k, ldai = (int)lda;
    if (n <= 0 || k <= 0) return FFC_OK;   /* (the callers' cases: y as it was) */
    if (b->rsize < 2 || n * k < SHARE_MIN) {
        const int ni = (int)n;
        dgemv_("N", &ni, &ki, &alpha, A, &ldai, x, &one, &beta, y, &one);
        return FFC_OK;
    }
    long lo, hi;
    rank_share(b, n, 1, &lo, &hi);
    const int ni = (int)(hi - lo);
    if (ni > 0) dgemv_("N", &ni, &ki, &alpha, A + lo, &ldai, x, &one, &beta, y + lo, &one);
    return ffc__mpi_allgather(b->rcomm, y, b->rcount);
}

/* The Newton direction dy of (I + G Kc') dy = -G rho, Kc' = Kc_CC - S from
 * the triplets (b->ti, tj, tv)[nt], reduced to Kc's support a: with
 * q = G rho, t + G_aa M t = -q_a (dense LU, b->A), dy = -q - G_Ca M t;
 * and the change of the reaction z = G^-1 (y - d0_C) it makes, by the
 * Newton equation G^-1 dy = -rho - Kc' dy: dz = -rho - E_a M dy_a.
 * ap[m], ad[m], q[m], t[m], s[m] work; *na the support's size. */
static int direction(ffc__bulk *b, long nt, const double rho[], double dy[], double dz[], long ap[], long ad[],
                     double q[], double t[], double s[], long *na, long *bad)
{
    const long m = b->m, ld = b->ld;
    for (long k = 0; k < m; k++) b->pos[b->dof[k]] = k;
    int st = FFC_OK;
    /* support: dofs with a tangent entry or a shift */
    long a = 0;
    for (long k = 0; k < m; k++) ap[k] = -1;
    for (long e = 0; e < nt && !st; e++) {
        const long i = b->ti[e], j = b->tj[e];
        if (b->tv[e] == 0.0 || b->big[i] || b->big[j]) continue;
        if (!isfinite(b->tv[e])) { *bad = i; st = FFC_ERR_NONFINITE; break; }
        if (b->pos[i] < 0 || b->pos[j] < 0) { *bad = b->pos[i] < 0 ? i : j; st = FFC_ERR_INDEX; break; }
        const long pi = b->pos[i], pj = b->pos[j];
        if (ap[pi] < 0) { ap[pi] = a; ad[a++] = pi; }
        if (ap[pj] < 0) { ap[pj] = a; ad[a++] = pj; }
    }
    for (long k = 0; k < m && !st; k++)
        if (b->sh[b->dof[k]] != 0.0 && ap[k] < 0) { ap[k] = a; ad[a++] = k; }
    *na = a;
    const int one = 1, ai = (int)a;
    const double d1 = 1.0, d0 = 0.0;
    if (!st && a * a > b->wcap) { /* the dense work of the support, grown as needed */
        double *Mw = realloc(b->Mw, (size_t)(a * a) * sizeof(double));
        if (Mw) b->Mw = Mw;
        double *Gw = Mw ? realloc(b->Gw, (size_t)(a * a) * sizeof(double)) : NULL;
        if (Gw) { b->Gw = Gw; b->wcap = a * a; }
        else st = FFC_ERR_MEMORY;
    }
    double *M = b->Mw, *Gaa = b->Gw;
    st = agree(b, st);   /* (a rank's failure is every rank's before the shared product) */
    if (!st) st = shared_gemv(b, m, m, 1.0, b->G, ld, rho, 0.0, q); /* q = G rho */
    if (!st && a > 0) {
        /* M = Kc' on the support (dense, a x a), G_aa */
        for (long k = 0; k < a * a; k++) M[k] = 0.0;
        for (long e = 0; e < nt; e++) {
            const long i = b->ti[e], j = b->tj[e];
            if (b->tv[e] == 0.0 || b->big[i] || b->big[j]) continue;
            M[ap[b->pos[i]] + ap[b->pos[j]] * a] += b->tv[e];
        }
        for (long k = 0; k < m; k++)
            if (b->sh[b->dof[k]] != 0.0) M[ap[k] + ap[k] * a] -= b->sh[b->dof[k]];
        for (long c = 0; c < a; c++) {
            const double *g = b->G + ad[c] * ld;
            for (long r = 0; r < a; r++) Gaa[r + c * a] = g[ad[r]];
        }
        for (long r = 0; r < a; r++) t[r] = -q[ad[r]];
        /* on the support of the kept LU: GMRES preconditioned by it (a few
         * a^2 products instead of an a^3 LU; the support stays the same
         * over most iterations of a step) */
        int reuse = b->ka == a;
        for (long r = 0; r < a && reuse; r++) reuse = b->kdof[r] == b->dof[ad[r]];
        const int git = reuse ? gmres_kept(b, a, M, Gaa, t) : -1;
        if (git > 10) b->ka = 0; /* (slow to converge: a fresh LU next time) */
        if (git >= 0) b->info.kept++;
        /* else A = I + G_aa M, column by column over M's nonzeros (a few
         * dozen per column: a^2 x that, against 2 a^3 for a dense product) */
        /* (several ranks and a large support: each rank builds the columns
         * it holds and the LU is shared, ffc__pdense) */
        const int dist = git < 0 && b->pd && a >= PDENSE_MIN;
        double *A = git < 0 && !dist ? dense_a(b) : b->A;
        if (git < 0 && !dist && !A) st = FFC_ERR_MEMORY;
        double *Al = dist ? ffc__pdense_reserve(b->pd, a) : NULL;
        if (dist && !Al) st = FFC_ERR_MEMORY;
        for (long j = 0; j < a && git < 0 && !st; j++) {
            long jl = 0;
            if (dist && (jl = ffc__pdense_local(b->pd, j)) < 0) continue;
            double *aj = dist ? Al + jl * a : A + j * a;
            for (long r = 0; r < a; r++) aj[r] = 0.0;
            aj[j] = 1.0;
            const double *mj = M + j * a;
            for (long i = 0; i < a; i++)
                if (mj[i] != 0.0) axpy(a, mj[i], Gaa + i * a, aj);
        }
        if (git < 0 && !st) {
            if (dist) {
                st = ffc__pdense_factor(b->pd, a);
                if (!st) st = ffc__pdense_solve(b->pd, a, t);
            } else
                st = ffc__lu_solve(a, A, b->piv, t);
            if (!st && a > b->kcap) { /* keep the LU */
                long *kd = realloc(b->kdof, (size_t)a * sizeof(long));
                if (kd) b->kdof = kd;
                int *kp = kd ? realloc(b->kpiv, (size_t)a * sizeof(int)) : NULL;
                if (kp) b->kpiv = kp;
                double *kl = kp ? realloc(b->klu, (size_t)(a * a) * sizeof(double)) : NULL;
                if (kl) { b->klu = kl; b->kcap = a; }
            }
            b->ka = 0;
            if (!st && a <= b->kcap) {
                if (!dist) {
                    memcpy(b->klu, A, (size_t)(a * a) * sizeof(double));
                    memcpy(b->kpiv, b->piv, (size_t)a * sizeof(int));
                }
                for (long r = 0; r < a; r++) b->kdof[r] = b->dof[ad[r]];
                b->ka = a;
                b->kdist = dist;
            }
        }
        if (!st) dgemv_("N", &ai, &ai, &d1, M, &ai, t, &one, &d0, s, &one); /* s = M t */
    }
    if (!st) {
        for (long k = 0; k < m; k++) dy[k] = -q[k];
        for (long r = 0; r < a; r++) {
            const double *g = b->G + ad[r] * ld; /* G symmetric: column ad[r] = row ad[r] */
            const double sr = s[r];
            for (long k = 0; k < m; k++) dy[k] -= g[k] * sr;
        }
        for (long k = 0; k < m; k++) dz[k] = -rho[k];
        if (a > 0) {
            for (long r = 0; r < a; r++) t[r] = dy[ad[r]];
            dgemv_("N", &ai, &ai, &d1, M, &ai, t, &one, &d0, s, &one);
            for (long r = 0; r < a; r++) dz[ad[r]] -= s[r];
        }
    }
    for (long k = 0; k < m; k++) b->pos[b->dof[k]] = -1;
    return st;
}

/* Formulation (the ranked direction).  With the tangent in ranked form
 * (FFC_TANGENT_RANKED) Kc' = U V^T - S_C: term k's columns U_k, V_k from
 * the triplets (b->ti = dof, b->tj = 2 k or 2 k + 1, b->tv)[nt] (Dirichlet
 * rows dropped), and a shifted dof d of C one more term (-s_d e_d, e_d).
 * The Newton equation (I + G Kc') dy = -q, q = G rho, is then (Woodbury)
 *     (I_p + V^T G U) w = -V^T q,   dy = -q - (G U) w,
 * a p x p system for p terms (an active slave node gives one term without
 * friction, four with) in place of the a x a one on the tangent's support
 * (three dofs of every slave and master node it couples); and
 * dz = -rho - Kc' dy = -rho - U (V^T dy).  Building G U takes m nnz(U),
 * V^T G U p nnz(V), the LU p^3 / 1.5.  *np the terms; ranked work grown
 * in b->rv, b->ri. */
/* sum over the entries e of list l of val[e] x[idx[e]] (the ranked lists:
 * start[l] .. start[l + 1]) */
static double list_dot(const long start[], const long idx[], const double val[], long l, const double x[])
{
    double v = 0.0;
    for (long e = start[l]; e < start[l + 1]; e++) v += val[e] * x[idx[e]];
    return v;
}

static int direction_ranked(ffc__bulk *b, long nt, const double rho[], double dy[], double dz[], double q[],
                            double gdz[], long *np, long *bad)
{
    const long m = b->m, ld = b->ld;
    for (long k = 0; k < m; k++) b->pos[b->dof[k]] = k;
    int st = FFC_OK;
    long p = 0, ne = 0, nsh = 0;
    for (long e = 0; e < nt; e++) {
        const long i = b->ti[e];
        if (b->tv[e] == 0.0 || b->big[i]) continue;
        if (!isfinite(b->tv[e])) { *bad = i; st = FFC_ERR_NONFINITE; break; }
        if (b->pos[i] < 0 || b->tj[e] < 0) { *bad = i; st = FFC_ERR_INDEX; break; }
        if (b->tj[e] / 2 + 1 > p) p = b->tj[e] / 2 + 1;
        ne++;
    }
    for (long k = 0; k < m; k++) nsh += b->sh[b->dof[k]] != 0.0;
    const long pt = p + nsh, nl = 2 * pt;
    *np = pt;
    /* work: the lists' starts [nl + 1], fill [nl], entries [ne + 2 nsh], pivots [pt];
     * values [ne + 2 nsh], G U [m pt], the system [pt pt], w [pt] */
    const long needi = 2 * nl + 1 + ne + 2 * nsh + pt, needv = ne + 2 * nsh + m * pt + pt * pt + 2 * pt;
    if (!st && needi > b->ricap) {
        long *ri = realloc(b->ri, (size_t)needi * sizeof(long));
        if (ri) { b->ri = ri; b->ricap = needi; }
        else st = FFC_ERR_MEMORY;
    }
    if (!st && needv > b->rcap) {
        double *rv = realloc(b->rv, (size_t)needv * sizeof(double));
        if (rv) { b->rv = rv; b->rcap = needv; }
        else st = FFC_ERR_MEMORY;
    }
    st = agree(b, st);   /* (a rank's failure is every rank's before the shared products) */
    if (st) {
        for (long k = 0; k < m; k++) b->pos[b->dof[k]] = -1;
        return st;
    }
    long *start = b->ri, *fill = start + nl + 1, *idx = fill + nl, *piv = idx + ne + 2 * nsh;
    double *val = b->rv, *GU = val + ne + 2 * nsh, *S = GU + m * pt, *wv = S + pt * pt, *vd = wv + pt;
    for (long l = 0; l <= nl; l++) start[l] = 0;
    for (long e = 0; e < nt; e++)
        if (b->tv[e] != 0.0 && !b->big[b->ti[e]]) start[b->tj[e] + 1]++;
    for (long j = p; j < pt; j++) start[2 * j + 1] = start[2 * j + 2] = 1; /* a shift term: one entry each */
    for (long l = 0; l < nl; l++) { start[l + 1] += start[l]; fill[l] = start[l]; }
    for (long e = 0; e < nt; e++) {
        if (b->tv[e] == 0.0 || b->big[b->ti[e]]) continue;
        const long at = fill[b->tj[e]]++;
        idx[at] = b->pos[b->ti[e]];
        val[at] = b->tv[e];
    }
    for (long k = 0, j = p; k < m; k++) {
        const double sh = b->sh[b->dof[k]];
        if (sh == 0.0) continue;
        idx[fill[2 * j]] = k; val[fill[2 * j]++] = -sh;
        idx[fill[2 * j + 1]] = k; val[fill[2 * j + 1]++] = 1.0;
        j++;
    }
    for (long k = 0; k < m; k++) b->pos[b->dof[k]] = -1;
    st = shared_gemv(b, m, m, 1.0, b->G, ld, rho, 0.0, q); /* q = G rho */
    if (st) return st;
    /* G U, column by column (G symmetric: its column c is row c); shared
     * out by columns on the ranks of a replicated bulk */
    const int split = b->rsize > 1 && pt * m >= SHARE_MIN;
    long k0 = 0, k1 = pt;
    if (split) rank_share(b, pt, m, &k0, &k1);
    for (long k = k0; k < k1; k++) {
        double *gu = GU + k * m;
        for (long r = 0; r < m; r++) gu[r] = 0.0;
        for (long e = start[2 * k]; e < start[2 * k + 1]; e++) axpy(m, val[e], b->G + idx[e] * ld, gu);
    }
    if (split && (st = ffc__mpi_allgather(b->rcomm, GU, b->rcount))) return st;
    /* S = I + V^T G U, wv = -V^T q; S column by column (one column of G U
     * read for all of V's columns) */
    for (long k = 0; k < pt; k++) wv[k] = -list_dot(start, idx, val, 2 * k + 1, q);
    for (long l = 0; l < pt; l++)
        for (long k = 0; k < pt; k++) S[k + l * pt] = (k == l) + list_dot(start, idx, val, 2 * k + 1, GU + l * m);
    st = ffc__lu_solve(pt, S, piv, wv);
    if (st) return st;
    /* dy = -q - G U w;  dz = -rho - U (V^T dy) */
    for (long k = 0; k < m; k++) dy[k] = -q[k];
    st = shared_gemv(b, m, pt, -1.0, GU, m, wv, 1.0, dy);
    if (st) return st;
    for (long k = 0; k < m; k++) dz[k] = -rho[k];
    for (long k = 0; k < pt; k++) vd[k] = list_dot(start, idx, val, 2 * k + 1, dy);
    for (long k = 0; k < pt; k++)
        for (long e = start[2 * k]; e < start[2 * k + 1]; e++) dz[idx[e]] -= val[e] * vd[k];
    /* G dz = -q - (G U) (V^T dy), from the products at hand (G U is m x p,
     * G m x m) */
    for (long k = 0; k < m; k++) gdz[k] = -q[k];
    return shared_gemv(b, m, pt, -1.0, GU, m, vd, 1.0, gdz);
}

/* Formulation (the closing solve kept).  A call ends at u' = u + d0 - x,
 * x = K'^-1 (-P_C^T z), and K d0 = b' = f - K u on the free rows, so the
 * next call's b'' = f - K u' = -P_C^T z when the load, the Dirichlet
 * values and K' are the same (an augmentation: only the multipliers
 * changed, and they are not in b'), and its d0 is x (with a shift S, a
 * body that only contact holds, b'' has S (d0 - x) more and is solved
 * afresh, unless S (d0 - x) is as small as below).  Taken when b''
 * (lifted) equals that right-hand side to REUSE_TOL of its largest entry
 * and to the force tolerance tol of the call (what differs is the
 * round-off of the residual f - K u' that the caller formed, and of the
 * two solves; the difference is left in the free rows' residual of the
 * returned state, below tol); every rank decides alike. */
#define REUSE_TOL 1e-10
static int same_rhs(const ffc__bulk *b, const double rhs[], double tol)
{
    int ok = b->prev;
    if (ok) {
        double e = 0.0, s = 0.0;
        for (long i = 0; i < b->n; i++) {
            const double d = fabs(rhs[i] - b->bprev[i]);
            if (!(d <= e)) e = d;   /* (a NaN stays: no reuse, and the solve reports it) */
            s = fmax(s, fabs(b->bprev[i]));
        }
        ok = s > 0.0 && e <= REUSE_TOL * s && e <= tol;
    }
    return all_ranks(b, ok);
}

/* keeps the closing solve K'^-1 rhs = x (nothing kept when short of memory) */
static void keep_closing(ffc__bulk *b, const double rhs[], const double x[])
{
    const size_t bytes = (size_t)b->n * sizeof(double);
    if (!b->bprev) b->bprev = malloc(bytes);
    if (!b->xprev) b->xprev = malloc(bytes);
    b->prev = b->bprev && b->xprev;
    if (!b->prev) return;
    memcpy(b->bprev, rhs, bytes);
    memcpy(b->xprev, x, bytes);
}

int ffc__bulk_newton(ffc__bulk *b, long nr, const long rows[], long nc, const long cand[], ffc__contact_fn fn,
                     void *ctx, const double r[], double u[], const ffc_newton_opts *o, ffc_newton_info *info,
                     long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!b || !fn || !r || !u || !o || !info || (nc > 0 && !cand) || (nr > 0 && !rows)) return FFC_ERR_NULL;
    memset(info, 0, sizeof *info);
    b->t_eval = &info->t_eval;
    if (nc < 0 || nr < 0) return FFC_ERR_SIZE;
    if (o->max_iter < 1 || o->max_ls < 0 || !(o->ls_tol > 0 && o->ls_tol < 1) || !(o->ftol > 0) ||
        !isfinite(o->ftol) || !(o->frel >= 0) || !isfinite(o->frel) || o->max_dofs < 0 || o->min_iter < 0 || o->min_iter > 1 ||
        (o->tangent != FFC_TANGENT_CONSISTENT && o->tangent != FFC_TANGENT_MATERIAL && o->tangent != FFC_TANGENT_RANKED))
        return FFC_ERR_VALUE;
    const long n = b->n;
    for (long i = 0; i < n; i++)
        if (!isfinite(r[i]) || !isfinite(u[i])) { *bad = i; return FFC_ERR_NONFINITE; }
    const long cap = o->max_dofs > 0 && o->max_dofs < b->mmax ? o->max_dofs : b->mmax;
    int st = set_rows(b, nr, rows, bad);
    if (st) return st;
    /* the contact force at u: b' = -(r - F_c(u)) on free rows, -r on
     * Dirichlet rows (into w); the dofs it reaches join C */
    double *w = b->w, *d0 = b->dx, *rhs = b->t;
    long nt = 0, nnew = 0;
    double fm = 0.0, fscale = 0.0; /* the contact force scale: its largest at an iteration's start */
    st = contact_eval(b, fn, ctx, u, FFC_TANGENT_NONE, &nt, &fm, bad);
    info->evals++;
    if (!st) {
        for (long i = 0; i < n; i++) w[i] = b->big[i] ? -r[i] : b->r[i] - r[i];
        st = reached(b, 0, 0, &nnew, bad);
    }
    long *reach = NULL;
    if (!st && !b->factored) { /* (the force's dofs kept: free_dofs writes b->nd) */
        reach = malloc((size_t)(nnew + 1) * sizeof(long));
        if (!reach) st = FFC_ERR_MEMORY;
        else memcpy(reach, b->nd, (size_t)nnew * sizeof(long));
    }
    if (!st) st = first_factor(b, nnew, reach, nc, cand, cap, bad);
    free(reach);
    if (!st) st = reached(b, 0, 0, &nnew, bad);
    if (!st) st = add_to_c(b, nnew, b->nd, cap, bad);
    if (!st) st = factor_g(b);
    if (st) return st;
    /* d0 = K^-1 b' with the Dirichlet values moved to the right-hand side
     * (or the last call's closing solve, when b' is its right-hand side) */
    lift_dirichlet(b, 0, NULL, NULL, NULL, w, rhs);
    if (same_rhs(b, rhs, fmax(o->ftol, o->frel * fm))) {
        memcpy(d0, b->xprev, (size_t)n * sizeof(double));
        b->info.reused++;
    } else
        st = backsolve(b, rhs, d0);
    if (st) return st;
    long m = b->m;
    /* C grows up to mm dofs.  m-vectors: y = d_C, z = G^-1 (y - d0_C) (the
     * reaction that holds C at y: the primary unknown; y = d0_C + G z
     * advanced by the same steps and recomputed from z every REFRESH
     * iterations, so that the two drift apart by round-off only), rho, dy, dz,
     * gdz = G dz, Fp, rt, q, t, s, d0_C; ap, ad; on the rows: hz = H z,
     * hdz = H dz (the displacement of the rows outside C: u + d0 + H z) */
    const long nrb = b->nr;
    const size_t mm = (size_t)(m + nrb < cap ? m + nrb : (cap > m ? cap : m)) + 1, mr = (size_t)nrb + 1;
    double *buf = malloc((12 * mm + 2 * mr) * sizeof(double));
    long *ibuf = malloc(2 * mm * sizeof(long));
    if (!buf || !ibuf) { free(buf); free(ibuf); return FFC_ERR_MEMORY; }
    double *y = buf, *z = y + mm, *rho = z + mm, *dy = rho + mm, *dz = dy + mm, *gdz = dz + mm, *Fp = gdz + mm,
           *rt = Fp + mm, *q = rt + mm, *tt = q + mm, *ss = tt + mm, *d0c = ss + mm, *hz = d0c + mm, *hdz = hz + mr;
    long *ap = ibuf, *ad = ibuf + mm;
    int mi = (int)m, nri = (int)nrb, ldi = (int)b->ld; /* (G's leading dimension grows with C) */
    const int one = 1;
    const double d1 = 1.0, d0s = 0.0;
    /* y = d0_C + G z */
#define Y_OF_Z()                                                                                                   \
    do {                                                                                                           \
        memcpy(y, d0c, (size_t)m * sizeof(double));                                                                \
        if (m) dgemv_("N", &mi, &mi, &d1, b->G, &ldi, z, &one, &d1, y, &one);                                      \
    } while (0)
    /* hz = H z */
#define HZ()                                                                                                       \
    do {                                                                                                           \
        if (m && nrb) dgemv_("N", &nri, &mi, &d1, b->H, &nri, z, &one, &d0s, hz, &one);                            \
        else for (long k = 0; k < nrb; k++) hz[k] = 0.0;                                                           \
    } while (0)
    /* w at z + a dz: the rows u + d0 + H (z + a dz), C's dofs u + yc */
#define W_AT(a_, yc_)                                                                                              \
    do {                                                                                                           \
        for (long k = 0; k < nrb; k++) w[b->rows[k]] = u[b->rows[k]] + d0[b->rows[k]] + hz[k] + (a_) * hdz[k];     \
        for (long k = 0; k < m; k++) w[b->dof[k]] = u[b->dof[k]] + (yc_)[k];                                       \
    } while (0)
    /* the dofs b->nd[nnew] join C at the state z: d0_C, z = 0 and y there */
#define JOIN()                                                                                                     \
    do {                                                                                                           \
        const long m0_ = m;                                                                                        \
        st = add_to_c(b, nnew, b->nd, cap, bad);                                                                   \
        if (st) break;                                                                                             \
        m = b->m;                                                                                                  \
        mi = (int)m;                                                                                               \
        ldi = (int)b->ld;                                                                                          \
        for (long k = m0_; k < m; k++) {                                                                           \
            d0c[k] = d0[b->dof[k]];                                                                                \
            z[k] = 0.0;                                                                                            \
            y[k] = d0c[k] + dot(m0_, b->G + k * b->ld, z); /* G symmetric: row k = column k */                     \
        }                                                                                                          \
        info->grown += nnew;                                                                                       \
    } while (0)
    /* the start: C held at u (y = 0), the rest equilibrated.  y = 0
     * exactly (d0_C + G z is zero to round-off): the first evaluation sees
     * u itself on C, as a Newton step of the full system would (a point just
     * touching sits on the kink of the law, where round-off would pick the
     * other side) */
#define START()                                                                                                    \
    do {                                                                                                           \
        for (long k = 0; k < m; k++) { d0c[k] = d0[b->dof[k]]; z[k] = -d0c[k]; y[k] = 0.0; }                       \
        g_inverse(b, z);                                                                                           \
        HZ();                                                                                                      \
        W_AT(0.0, y);                                                                                              \
    } while (0)
    for (long i = 0; i < n; i++) w[i] = u[i] + (b->big[i] ? d0[i] : 0.0);
    for (long k = 0; k < nrb; k++) hdz[k] = 0.0;
    START();
    int status = FFC_INFO_MAXIT, restart = 0, starting = 1;
    double last = 1.0, rprev = HUGE_VAL;
    int stall = 0, slow = 0, tmode = o->tangent;
    long nal = -1, nap = -2;   /* the ranked terms of the last direction and of the one before it (at
                                  the state before; the count stands for the active set) */
    for (int it = 0; !st; it++) {
        const int tan = it < o->max_iter ? tmode : FFC_TANGENT_NONE;
        st = contact_eval(b, fn, ctx, w, tan, &nt, &fm, bad);
        fscale = fmax(fscale, fm);
        info->evals++;
        if (!st) st = reached(b, tan ? nt : 0, tan == FFC_TANGENT_RANKED, &nnew, bad);
        if (!st && nnew && starting) {
            /* the start reaches dofs outside C (at the first call of a load
             * step the rest moves by the whole increment): they join C and
             * are held at u too */
            JOIN();
            if (!st) st = factor_g(b);
            if (st) break;
            START();
            it--;
            continue;
        }
        if (!st && nnew) JOIN();
        if (!st) st = force_c(b, y, Fp, bad);
        if (st) break;
        for (long k = 0; k < m; k++) rho[k] = z[k] + Fp[k];
        const double rn = sqrt(dot(m, rho, rho));
        double state0[3]; /* the contact state at z (the full step's test) */
        memcpy(state0, b->cstate, sizeof state0);
        info->res = rn;
        const double tol = fmax(o->ftol, o->frel * fscale);
        /* converged: the force test; or the round-off floor within 1e3 of
         * it: a full step that changed nothing, or two iterations in a row
         * that did not halve the residual (the noise of rho is about
         * eps |Kc G| |z|: with a stiff penalty it lies above a tight tol).
         * An iteration restarted because C grew in its line search is the
         * same state: not counted */
        const int fresh = !restart;   /* (a restart repeats the state: its direction replaces the last) */
        if (!restart) {
            if (info->nhist < FFC_NEWTON_HIST) info->hist[info->nhist++] = rn;
            stall = rn < 0.5 * rprev ? 0 : stall + 1;
            slow += tmode == FFC_TANGENT_RANKED && rprev < HUGE_VAL && !(rn < 0.1 * rprev) && nal == nap;
            rprev = rn;
        }
        restart = 0;
        if ((rn <= tol || ((last <= 1e-14 || stall >= 2) && rn <= 1e3 * tol)) &&
            (info->iters >= o->min_iter || !(rn > 0.0))) { status = FFC_OK; break; }
        if (it == o->max_iter) break;
        if (slow >= RANKED_SLOW) {
            /* ranked directions that RANKED_SLOW times did not gain 10x
             * on an unchanged active set: the geometric terms matter here
             * (a corner, a coarse facet), and the rest of the call takes
             * the consistent tangent (this iteration again, at the same
             * state).  An iteration whose direction had other terms than
             * the one before (the active set moved) is not counted: while
             * the contact zone forms (a load step's first call) the
             * residual rises and falls with the active set whatever the
             * tangent, and a ranked iteration costs a few products of G
             * where a consistent one costs an LU of the tangent's support
             * (Hertz P1 h_c 0.0125, counting them: 53 Newton iterations,
             * 24 of them consistent with supports of up to 1,632 dofs;
             * not: 44, none consistent, the same F to 11 digits) */
            tmode = FFC_TANGENT_CONSISTENT;
            slow = 0;
            info->switched = 1;
            restart = 1;
            it--;
            continue;
        }
        long na = 0;
        starting = 0;
        st = tmode == FFC_TANGENT_RANKED ? direction_ranked(b, nt, rho, dy, dz, q, gdz, &na, bad)
                       : direction(b, nt, rho, dy, dz, ap, ad, q, tt, ss, &na, bad);
        if (st) break;
        if (na > info->support) info->support = na;
        if (fresh) nap = nal;
        nal = na;
        /* the step of y that the step of z makes: G dz (= dy to the accuracy
         * of the dense solve; the ranked direction made it) */
        if (tmode != FFC_TANGENT_RANKED) st = shared_gemv(b, m, m, 1.0, b->G, b->ld, dz, 0.0, gdz);
        if (st) break;
        /* rho at z + a dz into rt; its g = rt . gdz; a force that reaches
         * a dof outside C: it joins C and the iteration restarts */
#define TRIAL(a_)                                                                                                  \
    do {                                                                                                           \
        for (long k = 0; k < m; k++) rt[k] = y[k] + (a_) * gdz[k];                                                 \
        W_AT(a_, rt);                                                                                              \
        st = contact_eval(b, fn, ctx, w, FFC_TANGENT_NONE, &nt, &fm, bad);                                         \
        info->evals++;                                                                                             \
        if (!st) st = reached(b, 0, 0, &nnew, bad);                                                                   \
        if (!st && nnew) { JOIN(); restart = 1; }                                                                  \
        if (!st && !restart) {                                                                                     \
            st = force_c(b, rt, Fp, bad);                                                                          \
            for (long k = 0; k < m; k++) rt[k] = z[k] + (a_) * dz[k] + Fp[k];                                      \
        }                                                                                                          \
    } while (0)
        double g0 = dot(m, rho, gdz);
        int whole = 0; /* the full step, taken on |rho| alone */
        if (!(g0 < 0) && tmode == FFC_TANGENT_CONSISTENT) {
            /* g(0) >= 0 for the consistent tangent: first its full step,
             * taken where it at least halves |rho| and leaves the contact
             * state as it was (with friction the
             * tangent is not symmetric and g need not fall along a good
             * Newton step: see the line search below) */
            st = shared_gemv(b, nrb, m, 1.0, b->H, nrb, dz, 0.0, hdz);
            if (st) break;
            TRIAL(1.0);
            if (st) break;
            if (restart) { /* C grew: the iteration again, as below */
                HZ();
                W_AT(0.0, y);
                it--;
                continue;
            }
            whole = full_step_taken(b, m, rt, rn, state0);
            if (!whole) {
                /* the consistent tangent is indefinite here: the material
                 * one's direction (w back at this iteration's state) */
                W_AT(0.0, y);
                st = contact_eval(b, fn, ctx, w, FFC_TANGENT_MATERIAL, &nt, &fm, bad);
                info->evals++;
                if (!st) st = direction(b, nt, rho, dy, dz, ap, ad, q, tt, ss, &na, bad);
                if (st) break;
                if (na > info->support) info->support = na;
                info->fallbacks++;
                st = shared_gemv(b, m, m, 1.0, b->G, b->ld, dz, 0.0, gdz);
                if (st) break;
                g0 = dot(m, rho, gdz);
            }
        }
        if (!whole && !(g0 < 0)) { status = FFC_INFO_NODESCENT; break; }
        if (!whole) st = shared_gemv(b, nrb, m, 1.0, b->H, nrb, dz, 0.0, hdz);
        if (st) break;
        double a = 1.0;
        if (o->max_ls > 0 && !whole) {
            /* the root of g(a) on [0, 1] by regula falsi (Illinois), taken
             * once |g| <= ls_tol |g(0)|, or a = 1 while g < 0 there, or
             * a = 1 where |rho| has at least halved with the contact state
             * as it was (no kink of the law crossed).  (The last: with
             * friction the tangent is not symmetric, and g(0) = -dz' G Kt
             * G dz can be small against |rho| |G dz|; on a pad in full
             * slip the full step cut |rho| 7,500-fold while g(1) was
             * -40 g(0), and the root of g, a = 0.14 at every iteration,
             * converged linearly: 60 iterations, no convergence.) */
            double alo = 0.0, glo = g0, ahi = 1.0, ghi = 0.0, at = -1.0; /* at: the last trial's a (rt) */
            int side = 0;
            for (int ls = 0; ls < o->max_ls; ls++) {
                TRIAL(a);
                at = a;
                if (st || restart) break;
                const double g = dot(m, rt, gdz);
                if (fabs(g) <= o->ls_tol * fabs(g0) || (g < 0 && a == ahi)) break;
                if (a == 1.0 && full_step_taken(b, m, rt, rn, state0)) break;
                if (g < 0) {
                    alo = a; glo = g;
                    if (side == -1) ghi *= 0.5;
                    side = -1;
                } else {
                    ahi = a; ghi = g;
                    if (side == 1) glo *= 0.5;
                    side = 1;
                }
                const double an = alo - glo * (ahi - alo) / (ghi - glo);
                a = fmax(alo + 0.05 * (ahi - alo), fmin(an, ahi - 0.05 * (ahi - alo)));
            }
            /* a step that makes |rho| ten times larger is halved */
            for (int ls = 0; ls < o->max_ls && !st && !restart; ls++) {
                if (a != at) TRIAL(a);
                if (st || restart || sqrt(dot(m, rt, rt)) <= 10 * rn) break;
                a *= 0.5;
            }
        }
#undef TRIAL
        if (st) break;
        if (restart) { /* the same state, C grown: w as before, the iteration again */
            HZ();
            W_AT(0.0, y);
            it--;
            continue;
        }
        info->iters++;
        /* z += a dz, and y = d0_C + G z, hz = H z by the same steps (G dz and
         * H dz are at hand; recomputed from z every REFRESH iterations) */
        for (long k = 0; k < m; k++) z[k] += a * dz[k];
        if (info->iters % REFRESH == 0) {
            Y_OF_Z();
            HZ();
        } else {
            for (long k = 0; k < m; k++) y[k] += a * gdz[k];
            for (long k = 0; k < nrb; k++) hz[k] += a * hdz[k];
        }
        for (long k = 0; k < nrb; k++) hdz[k] = 0.0;
        W_AT(0.0, y);
        double dn = 0.0, yn = 0.0;
        for (long k = 0; k < m; k++) {
            dn += a * a * gdz[k] * gdz[k];
            yn += w[b->dof[k]] * w[b->dof[k]];
        }
        last = a == 1.0 ? sqrt(dn / fmax(yn, 1e-300)) : 1.0;
    }
#undef Y_OF_Z
#undef HZ
#undef W_AT
#undef JOIN
#undef START
    info->m = m;
    if (!st) {
        /* d = d0 + K^-1 P_C^T z: the state whose residual is rho (d_C = y;
         * not d0 - K^-1 P_C^T F_c, which moves C by G rho and the contact
         * force by about Kc G rho, a hundred times rho at the automatic
         * penalty) */
        memset(rhs, 0, (size_t)n * sizeof(double));
        for (long k = 0; k < m; k++) rhs[b->dof[k]] = -z[k];
        st = backsolve(b, rhs, b->r);
        if (!st)
            for (long i = 0; i < n; i++) u[i] += d0[i] - b->r[i];
        if (!st) keep_closing(b, rhs, b->r);
    }
    free(buf);
    free(ibuf);
    b->info.solves++;
    return st ? st : status;
}

/* ------------------------------------ the node-to-surface saddle point */

/* The rows (Bi, Bj, Bv, Fv)[nt] of nr constraints (see ffc__bulk_saddle)
 * and the dense system of one saddle solve: S = Cm - B G Bf' (nr x nr),
 * or, with shifted dofs in C, the coupled [I - G S_C, G Bf'; B, Cm]
 * (m + nr), LU-factored in A (leading dimension na). */
typedef struct {
    long nt, nr;
    const long *Bi, *Bj;
    const double *Bv, *Fv;
    int coupled;      /* 1: the coupled system (a shift in C) */
    long na;          /* its order */
    double *A;        /* [na*na] its LU factors */
    int *piv;         /* [na] */
    double *W;        /* [m*nr] G Bf' (Schur form) */
    double *v;        /* [na] work */
} saddle_sys;

/* x = K'^-1 (rhs lifted), m: one saddle solve with the factored system
 * (rhs[n] the force rows, c[nr] the constraint rows) */
static int saddle_once(ffc__bulk *b, const saddle_sys *S, const double rhs[], const double c[], double x[],
                       double mult[])
{
    const long n = b->n, m = b->m, nr = S->nr;
    double *t = b->t, *x0 = b->dx;
    lift_dirichlet(b, 0, NULL, NULL, NULL, rhs, t);
    int st = backsolve(b, t, x0);
    if (st) return st;
    double *v = S->v;
    const int nai = (int)S->na, one = 1;
    int info = 0;
    if (!S->coupled) {
        /* S mult = c - B x0 */
        for (long r = 0; r < nr; r++) v[r] = c[r];
        for (long e = 0; e < S->nt; e++)
            if (S->Bj[e] < n && S->Bv[e] != 0.0) v[S->Bi[e]] -= S->Bv[e] * x0[S->Bj[e]];
        if (nr) dgetrs_("N", &nai, &one, S->A, &nai, S->piv, v, &nai, &info);
        if (info) return FFC_ERR_SINGULAR;
        memcpy(mult, v, (size_t)nr * sizeof(double));
    } else {
        /* [I - G S_C, G Bf'; B, Cm] [y; mult] = [x0_C; c] */
        for (long k = 0; k < m; k++) v[k] = x0[b->dof[k]];
        for (long r = 0; r < nr; r++) v[m + r] = c[r];
        dgetrs_("N", &nai, &one, S->A, &nai, S->piv, v, &nai, &info);
        if (info) return FFC_ERR_SINGULAR;
        memcpy(mult, v + m, (size_t)nr * sizeof(double));
    }
    /* x = x0 + K'^-1 (S_C y - Bf' mult) */
    memset(t, 0, (size_t)n * sizeof(double));
    for (long e = 0; e < S->nt; e++)
        if (S->Bj[e] < n && S->Fv[e] != 0.0 && !b->big[S->Bj[e]]) t[S->Bj[e]] -= S->Fv[e] * mult[S->Bi[e]];
    if (S->coupled)
        for (long k = 0; k < m; k++) t[b->dof[k]] += b->sh[b->dof[k]] * v[k];
    st = backsolve(b, t, x);
    if (st) return st;
    for (long i = 0; i < n; i++) x[i] += x0[i];
    return FFC_OK;
}

/* the residuals of the saddle system at (x, mult): ru = rhs - K x - Bf'
 * mult (K with its tgv rows), rc = c - B x - Cm mult; their relative size:
 * the free rows and the constraint rows against |rhs_free - K_fd g| + |c|
 * (the right-hand side once the Dirichlet values g are lifted: fs), not
 * against |K| |x| (which would pass the huge x of a body that nothing
 * holds); a Dirichlet row's residual / diagonal against |x|_inf */
static double saddle_residual(const ffc__bulk *b, const saddle_sys *S, const double rhs[], const double c[],
                              double fs, const double x[], const double mult[], double ru[], double rc[])
{
    const long n = b->n;
    residual(b, 0, NULL, NULL, NULL, rhs, x, ru);
    double cs = 0.0, rs = 0.0, rd = 0.0, xinf = 0.0;
    for (long r = 0; r < S->nr; r++) { rc[r] = c[r]; cs += c[r] * c[r]; }
    for (long e = 0; e < S->nt; e++) {
        const long i = S->Bi[e], j = S->Bj[e];
        if (j < n) {
            if (!b->big[j]) ru[j] -= S->Fv[e] * mult[i];
            rc[i] -= S->Bv[e] * x[j];
        } else rc[i] -= S->Bv[e] * mult[j - n];
    }
    for (long r = 0; r < S->nr; r++) rs += rc[r] * rc[r];
    for (long i = 0; i < n; i++) {
        xinf = fmax(xinf, fabs(x[i]));
        if (b->big[i]) rd = fmax(rd, fabs(ru[i]) / b->diag[i]);
        else rs += ru[i] * ru[i];
    }
    return fmax(sqrt(rs) / (fs + sqrt(cs) + 1e-300), rd / (xinf + 1e-300));
}

int ffc__bulk_saddle(ffc__bulk *b, long nt, const long Bi[], const long Bj[], const double Bv[], const double Fv[],
                     long nr, const double c[], const double rhs[], double x[], double mult[], long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!b || !rhs || !x || (nt > 0 && (!Bi || !Bj || !Bv || !Fv)) || (nr > 0 && (!c || !mult))) return FFC_ERR_NULL;
    if (nt < 0 || nr < 0) return FFC_ERR_SIZE;
    const long n = b->n;
    for (long e = 0; e < nt; e++) {
        if (Bi[e] < 0 || Bi[e] >= nr || Bj[e] < 0 || Bj[e] >= n + nr) { *bad = e; return FFC_ERR_INDEX; }
        if (!isfinite(Bv[e]) || !isfinite(Fv[e])) { *bad = e; return FFC_ERR_NONFINITE; }
    }
    for (long i = 0; i < n; i++)
        if (!isfinite(rhs[i])) { *bad = i; return FFC_ERR_NONFINITE; }
    for (long r = 0; r < nr; r++)
        if (!isfinite(c[r])) { *bad = n + r; return FFC_ERR_NONFINITE; }
    /* C: the free dofs of the rows' columns, and the shifted dofs */
    for (long k = 0; k < b->m; k++) b->pos[b->dof[k]] = k;
    long nnew = 0;
    for (long e = 0; e < nt; e++) {
        const long j = Bj[e];
        if (j >= n || b->big[j] || (Bv[e] == 0.0 && Fv[e] == 0.0) || b->pos[j] != -1) continue;
        b->pos[j] = -2;
        b->nd[nnew++] = j;
    }
    for (long k = 0; k < nnew; k++) b->pos[b->nd[k]] = -1;
    for (long k = 0; k < b->m; k++) b->pos[b->dof[k]] = -1;
    if (b->m + nnew > b->mmax) { *bad = b->m + nnew; return FFC_ERR_CAPACITY; }
    int st = FFC_OK;
    if (!b->factored && (st = factorize_first(b, nnew, b->nd))) return st;
    if ((st = add_to_c(b, nnew, b->nd, b->mmax, bad)) || (st = shifted_into_c(b, b->mmax, bad))) return st;
    const int coupled = b->info.shift != 0.0; /* (the factor is of K + S) */
    b->info.solves++;
    const long m = b->m, ld = b->ld, na = coupled ? m + nr : nr;
    if (na > 46340) return FFC_ERR_SIZE; /* (na^2 within an int for LAPACK) */
    saddle_sys S = {nt, nr, Bi, Bj, Bv, Fv, coupled, na, NULL, NULL, NULL, NULL};
    S.A = malloc((size_t)(na * na + 1) * sizeof(double));
    S.piv = malloc((size_t)(na + 1) * sizeof(int));
    S.W = coupled ? NULL : malloc((size_t)(m * nr + 1) * sizeof(double));
    S.v = malloc((size_t)(na + 1) * sizeof(double));
    double *ru = malloc((size_t)(n + nr + 1) * sizeof(double)), *dm = malloc((size_t)(nr + 1) * sizeof(double));
    if (!S.A || !S.piv || (!coupled && !S.W) || !S.v || !ru || !dm) st = FFC_ERR_MEMORY;
    for (long k = 0; k < m; k++) b->pos[b->dof[k]] = k;
    if (!st && !coupled) {
        /* W = G Bf' (m x nr), column by row: G's column of each entry's dof */
        double *W = S.W, *A = S.A;
        memset(W, 0, (size_t)(m * nr) * sizeof(double));
        for (long e = 0; e < nt; e++) {
            const long j = Bj[e];
            if (j >= n || Fv[e] == 0.0 || b->big[j]) continue;
            const double *g = b->G + b->pos[j] * ld, f = Fv[e];
            double *w = W + Bi[e] * m;
            for (long k = 0; k < m; k++) w[k] += f * g[k];
        }
        /* S = Cm - B W */
        memset(A, 0, (size_t)(nr * nr) * sizeof(double));
        for (long e = 0; e < nt; e++) {
            const long i = Bi[e], j = Bj[e];
            if (j >= n) { A[i + (j - n) * nr] += Bv[e]; continue; }
            if (Bv[e] == 0.0 || b->big[j]) continue;
            const long pj = b->pos[j];
            const double v = Bv[e];
            for (long r = 0; r < nr; r++) A[i + r * nr] -= v * W[pj + r * m];
        }
    } else if (!st) {
        /* [I - G S_C, G Bf'; B, Cm] */
        double *A = S.A;
        memset(A, 0, (size_t)(na * na) * sizeof(double));
        for (long k = 0; k < m; k++) {
            const double sk = b->sh[b->dof[k]];
            A[k + k * na] = 1.0;
            if (sk != 0.0)
                for (long r = 0; r < m; r++) A[r + k * na] -= b->G[r + k * ld] * sk;
        }
        for (long e = 0; e < nt; e++) {
            const long i = Bi[e], j = Bj[e];
            if (j >= n) { A[m + i + (m + j - n) * na] += Bv[e]; continue; }
            if (b->big[j]) continue;
            const long pj = b->pos[j];
            if (Fv[e] != 0.0)
                for (long r = 0; r < m; r++) A[r + (m + i) * na] += b->G[r + pj * ld] * Fv[e];
            A[m + i + pj * na] += Bv[e];
        }
    }
    for (long k = 0; k < m; k++) b->pos[b->dof[k]] = -1;
    if (!st && na > 0) {
        const int nai = (int)na;
        int info = 0;
        dgetrf_(&nai, &nai, S.A, &nai, S.piv, &info);
        if (info) st = FFC_ERR_SINGULAR;
    }
    /* the scale of the residual test: the free rows of the lifted rhs */
    double fs = 0.0;
    lift_dirichlet(b, 0, NULL, NULL, NULL, rhs, b->t);
    for (long i = 0; i < n; i++)
        if (!b->big[i]) fs += b->t[i] * b->t[i];
    fs = sqrt(fs);
    if (!st) st = saddle_once(b, &S, rhs, c, x, mult);
    /* iterative refinement: at most two corrections, while they help */
    double e = 0.0;
    if (!st) e = saddle_residual(b, &S, rhs, c, fs, x, mult, ru, ru + n);
    for (int k = 0; !st && k < 2 && e > 1e-13; k++) {
        double *dx = b->r; /* (saddle_once uses t, dx, w) */
        memcpy(b->w, ru, (size_t)n * sizeof(double));
        st = saddle_once(b, &S, b->w, ru + n, dx, dm);
        if (st) break;
        for (long i = 0; i < n; i++) x[i] += dx[i];
        for (long r = 0; r < nr; r++) mult[r] += dm[r];
        const double e2 = saddle_residual(b, &S, rhs, c, fs, x, mult, ru, ru + n);
        b->info.refinements++;
        if (!(e2 < 0.5 * e)) { e = e2; break; }
        e = e2;
    }
    b->info.residual = e;
    free(S.A); free(S.piv); free(S.W); free(S.v); free(ru); free(dm);
    if (!st && !(e <= 1e-6)) st = FFC_ERR_SINGULAR;
    return st;
}
