/* ffc_eng_umfpack.c: the UMFPACK engine: a general sparse matrix (LU
 * with partial pivoting, one process); the symmetric lower triangle is
 * expanded to the whole matrix. */
#include <stdlib.h>
#include <string.h>

#include <suitesparse/umfpack.h>

#include "ffc_engine.h"

typedef struct {
    ffc__engine base;
    long nz;                 /* entries of the analysed pattern (count) */
    SuiteSparse_long *Ap, *Ai; /* [n + 1], [nz] the matrix by columns (sorted rows, duplicates summed) */
    double *Ax;              /* [nz] */
    long tn;                 /* the triplets last converted (count; 0: no map) */
    int tsym;                /* ... their sym */
    int *ti, *tj;            /* [tn] ... their rows and columns */
    SuiteSparse_long *map;   /* [tn + its mirrored entries] where each went in Ax (triplet_to_col's Map) */
    void *symbolic, *numeric;
    double control[UMFPACK_CONTROL];
} ffc__umf;

static int umf_agree(const ffc__engine *e, int ok) { (void)e; return ok; }

static void umf_release(ffc__engine *e)
{
    ffc__umf *u = (ffc__umf *)e;
    if (u->numeric) umfpack_dl_free_numeric(&u->numeric);
    e->factored = 0;
}

static void drop_map(ffc__umf *u)
{
    free(u->ti); free(u->tj); free(u->map);
    u->ti = u->tj = NULL;
    u->map = NULL;
    u->tn = 0;
}

static void drop_all(ffc__umf *u)
{
    umf_release(&u->base);
    if (u->symbolic) umfpack_dl_free_symbolic(&u->symbolic);
    free(u->Ap); free(u->Ai); free(u->Ax);
    u->Ap = u->Ai = NULL;
    u->Ax = NULL;
    drop_map(u);
}

static void umf_free(ffc__engine *e)
{
    drop_all((ffc__umf *)e);
    free(e);
}

/* A by columns into u (a symmetric lower triangle with its upper part),
 * keeping A's (i, j) and where each entry went (the map by which the next
 * matrix of the same triplets is filled: same_triplets, refill);
 * FFC_ERR_MEMORY, or FFC_ERR_INDEX for an entry outside the order */
static int to_columns(ffc__umf *u, const ffc__tri *A)
{
    const long n = A->n;
    long nz = 0;
    for (long k = 0; k < A->nz; k++) nz += 1 + (A->sym && A->i[k] != A->j[k]);
    SuiteSparse_long *Ti = malloc((size_t)(nz ? nz : 1) * sizeof *Ti), *Tj = malloc((size_t)(nz ? nz : 1) * sizeof *Tj);
    double *Tx = malloc((size_t)(nz ? nz : 1) * sizeof *Tx);
    free(u->Ap); free(u->Ai); free(u->Ax);
    drop_map(u);
    u->Ap = malloc((size_t)(n + 1) * sizeof *u->Ap);
    u->Ai = malloc((size_t)(nz ? nz : 1) * sizeof *u->Ai);
    u->Ax = malloc((size_t)(nz ? nz : 1) * sizeof *u->Ax);
    u->map = malloc((size_t)(nz ? nz : 1) * sizeof *u->map);
    u->ti = malloc((size_t)(A->nz ? A->nz : 1) * sizeof *u->ti);
    u->tj = malloc((size_t)(A->nz ? A->nz : 1) * sizeof *u->tj);
    int st = Ti && Tj && Tx && u->Ap && u->Ai && u->Ax && u->map && u->ti && u->tj ? FFC_OK : FFC_ERR_MEMORY;
    for (long k = 0, c = 0; k < A->nz && !st; k++) {
        if (A->i[k] < 0 || A->i[k] >= n || A->j[k] < 0 || A->j[k] >= n) { st = FFC_ERR_INDEX; break; }
        Ti[c] = A->i[k]; Tj[c] = A->j[k]; Tx[c++] = A->v[k];
        if (A->sym && A->i[k] != A->j[k]) { Ti[c] = A->j[k]; Tj[c] = A->i[k]; Tx[c++] = A->v[k]; }
    }
    if (!st && umfpack_dl_triplet_to_col(n, n, nz, Ti, Tj, Tx, u->Ap, u->Ai, u->Ax, u->map) != UMFPACK_OK)
        st = FFC_ERR_MEMORY;
    free(Ti); free(Tj); free(Tx);
    if (!st) {
        memcpy(u->ti, A->i, (size_t)A->nz * sizeof *u->ti);
        memcpy(u->tj, A->j, (size_t)A->nz * sizeof *u->tj);
        u->tn = A->nz;
        u->tsym = A->sym;
    } else drop_map(u);
    u->nz = st ? 0 : u->Ap[n];
    return st;
}

/* 1 when A's triplets are those to_columns converted last (the same
 * entries in the same order) */
static int same_triplets(const ffc__umf *u, const ffc__tri *A)
{
    return u->map && u->tn == A->nz && u->tn > 0 && u->tsym == A->sym && A->n == u->base.n &&
           !memcmp(u->ti, A->i, (size_t)A->nz * sizeof *A->i) && !memcmp(u->tj, A->j, (size_t)A->nz * sizeof *A->j);
}

/* A's values into Ax through the map (A: same_triplets) */
static void refill(ffc__umf *u, const ffc__tri *A)
{
    memset(u->Ax, 0, (size_t)u->nz * sizeof *u->Ax);
    for (long k = 0, c = 0; k < A->nz; k++) {
        u->Ax[u->map[c++]] += A->v[k];
        if (A->sym && A->i[k] != A->j[k]) u->Ax[u->map[c++]] += A->v[k];
    }
}

static int umf_analyze(ffc__engine *e, const ffc__tri *A)
{
    ffc__umf *u = (ffc__umf *)e;
    drop_all(u);
    if (A->n <= 0) return ffc__engine_fail(e, FFC_ERR_SIZE, FFC_AT_COUNT, A->n, "UMFPACK: order %ld", A->n);
    e->n = A->n;
    int st = to_columns(u, A);
    if (st == FFC_ERR_INDEX) return ffc__engine_fail(e, st, FFC_AT_NONE, -1, "UMFPACK: an entry outside the order");
    /* from 10,000 rows METIS's nested dissection, below AMD: METIS leaves
     * less fill on 3D meshes but costs more to compute (measured: the soft
     * ball at 19,014 dofs 62 s against 85 s with AMD, the LU factorizations
     * most of it; the ironing at 4,371 dofs, analysed often, 159 s against
     * 138 s); UMFPACK takes AMD where it was built without METIS */
    u->control[UMFPACK_ORDERING] = A->n >= 10000 ? UMFPACK_ORDERING_METIS : UMFPACK_ORDERING_AMD;
    if (!st && umfpack_dl_symbolic(A->n, A->n, u->Ap, u->Ai, u->Ax, &u->symbolic, u->control, NULL) != UMFPACK_OK)
        st = FFC_ERR_MEMORY;
    if (st)
        return ffc__engine_fail(e, st, FFC_AT_COUNT, A->n, "UMFPACK: out of memory analysing a matrix of order %ld "
                                "with %ld entries", A->n, A->nz);
    return FFC_OK;
}

static int umf_factorize(ffc__engine *e, const ffc__tri *A)
{
    ffc__umf *u = (ffc__umf *)e;
    if (!u->symbolic || A->n != e->n) return ffc__engine_fail(e, FFC_ERR_EMPTY, FFC_AT_NONE, -1, "UMFPACK: not analysed");
    umf_release(e);
    const long nz0 = u->nz;
    int st = FFC_OK;
    if (same_triplets(u, A)) refill(u, A);   /* (no new conversion: the analysed triplets' values) */
    else st = to_columns(u, A);
    if (!st && u->nz != nz0)
        return ffc__engine_fail(e, FFC_ERR_VALUE, FFC_AT_COUNT, u->nz, "UMFPACK: %ld entries, the analysed pattern "
                                "has %ld", u->nz, nz0);
    double info[UMFPACK_INFO];
    const int us = st ? UMFPACK_ERROR_out_of_memory
                      : umfpack_dl_numeric(u->Ap, u->Ai, u->Ax, u->symbolic, &u->numeric, u->control, info);
    if (us == UMFPACK_WARNING_singular_matrix || us == UMFPACK_WARNING_determinant_underflow ||
        us == UMFPACK_WARNING_determinant_overflow) {
        e->info->rcond = info[UMFPACK_RCOND];
        if (us == UMFPACK_WARNING_singular_matrix)
            return ffc__engine_fail(e, FFC_ERR_SINGULAR, FFC_AT_NONE, -1, "UMFPACK: the matrix is singular (a zero "
                                    "pivot)");
    } else if (us != UMFPACK_OK)
        return ffc__engine_fail(e, FFC_ERR_MEMORY, FFC_AT_COUNT, A->n, "UMFPACK: out of memory factorizing a "
                                "matrix of order %ld with %ld entries", A->n, u->nz);
    e->info->rcond = info[UMFPACK_RCOND];
    e->factored = 1;
    return FFC_OK;
}

static int umf_solve(ffc__engine *e, const double b[], double x[])
{
    ffc__umf *u = (ffc__umf *)e;
    if (!e->factored) return ffc__engine_fail(e, FFC_ERR_EMPTY, FFC_AT_NONE, -1, "UMFPACK: not factorized");
    const int us = umfpack_dl_solve(UMFPACK_A, u->Ap, u->Ai, u->Ax, x, b, u->numeric, u->control, NULL);
    if (us != UMFPACK_OK && us != UMFPACK_WARNING_singular_matrix)
        return ffc__engine_fail(e, FFC_ERR_MEMORY, FFC_AT_COUNT, e->n, "UMFPACK: a solve of order %ld failed "
                                "(status %d)", e->n, us);
    return FFC_OK;
}

static int umf_inverse(ffc__engine *e, long nc, long cols[], long nrows, const long rows[], ffc__inv_sink sink,
                       void *ctx)
{
    if (!e->factored) return ffc__engine_fail(e, FFC_ERR_EMPTY, FFC_AT_NONE, -1, "UMFPACK: not factorized");
    return ffc__inverse_by_solves(e, nc, cols, nrows, rows, sink, ctx);
}

static const ffc__engine_ops umf_ops = {"UMFPACK", umf_analyze, umf_factorize, umf_solve, umf_inverse,
                                        umf_agree, umf_release, umf_free};

int ffc__umfpack_create(ffc_solve_info *info, ffc__engine **out)
{
    if (!out || !info) return FFC_ERR_NULL;
    *out = NULL;
    ffc__umf *u = calloc(1, sizeof *u);
    if (!u) return FFC_ERR_MEMORY;
    u->base.op = &umf_ops;
    u->base.info = info;
    u->base.err.index = -1;
    umfpack_dl_defaults(u->control);
    u->control[UMFPACK_PRL] = 0;   /* kernels never print */
    /* no iterative refinement: each step is a back-solve and a product
     * more, and its callers check their residual (the full solver's GMRES
     * on an earlier factor: measured on the soft ball at 9,033 dofs, the
     * refinement doubled the back-solves' cost) */
    u->control[UMFPACK_IRSTEP] = 0;
    /* (the ordering: umf_analyze) */
    *out = &u->base;
    return FFC_OK;
}
