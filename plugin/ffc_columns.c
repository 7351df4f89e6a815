/* ffc_columns.c: the compliance of the contact dofs C (G = P_C K'^-1
 * P_C^T, and its columns on the rows R the contact reads, H), grown
 * column by column from the engine's entries of the inverse; its
 * Cholesky factor. */
#include <stdlib.h>
#include <string.h>

#include "ffc_bulk_state.h"
#include "ffc_internal.h"

/* grows G (and the dense work) to hold m contact dofs: by a quarter at
 * least, in steps of 64 (doubling left up to three quarters of G, Gc and
 * A untouched but paid for, the kernel zeroing whole huge pages of them:
 * 4,459 contact dofs took 8,192^2 entries each, 512 MB) */
int ffc__bulk_grow(ffc__bulk *b, long m)
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
    b->G = G; b->A = NULL; b->dof = dof; b->piv = piv; b->xc = xc; /* (A: at its first use, ffc__bulk_dense_a) */
    b->ld = ld;
    return FFC_OK;
}

/* the dense work A (ld x ld), allocated at its first use: the ranked
 * condensed Newton never needs it (NULL when out of memory) */
double *ffc__bulk_dense_a(ffc__bulk *b)
{
    if (!b->A) b->A = malloc((size_t)b->ld * b->ld * sizeof(double));
    return b->A;
}

/* the columns handed over by the engine, kept: each on the rows read,
 * into G (and H on the rows R) */
typedef struct {
    ffc__bulk *b;
    double *x;          /* [n] zero outside the rows */
    long nrows;
    const long *rows;   /* [nrows] */
} column_sink;

static int keep_columns(void *ctx, long nc, const long cols[], const double V[])
{
    const column_sink *k = ctx;
    ffc__bulk *b = k->b;
    double *x = k->x;
    int st = FFC_OK;
    for (long c = 0; c < nc && !st; c++) {
        for (long r = 0; r < k->nrows; r++) x[k->rows[r]] = V[r + c * k->nrows];
        st = ffc_reduced_add(b->n, b->ld, b->m, b->dof, b->G, x, cols[c]);
        for (long r = 0; r < b->nr && !st; r++) b->H[r + b->m * b->nr] = x[b->rows[r]];
        for (long r = 0; r < k->nrows; r++) x[k->rows[r]] = 0.0;
        if (!st) b->m++;
    }
    return st;
}

/* The compliance columns of the dofs nd[nnew]: their values on the rows
 * read (C, the new dofs, R: each once), from the engine's entries of
 * K'^-1 (in the order it hands them over).  With several ranks every rank
 * takes the same branches: a failure on one is every rank's
 * (FFC_ERR_MEMORY when it was another's). */
static int add_columns_timed(ffc__bulk *b, long nnew, const long nd[])
{
    int st = ffc__bulk_agree(b, ffc__bulk_grow(b, b->m + nnew));
    if (st) return st;
    const long n = b->n, m0 = b->m;
    long *rows = malloc((size_t)(m0 + nnew + b->nr + 1) * sizeof *rows), nrows = 0;
    long *d = malloc((size_t)(nnew + 1) * sizeof *d);
    double *x = calloc((size_t)n, sizeof *x);
    if (rows && x)
        for (long k = 0; k < m0 + nnew + b->nr; k++) {
            const long i = k < m0 ? b->dof[k] : k < m0 + nnew ? nd[k - m0] : b->rows[k - m0 - nnew];
            if (!x[i]) { x[i] = 1.0; rows[nrows++] = i; }
        }
    if (rows && x)
        for (long r = 0; r < nrows; r++) x[rows[r]] = 0.0;
    st = ffc__bulk_agree(b, rows && d && x ? FFC_OK : FFC_ERR_MEMORY);
    if (!st) {
        memcpy(d, nd, (size_t)nnew * sizeof *d);
        column_sink k = {b, x, nrows, rows};
        st = b->eng->op->inverse(b->eng, nnew, d, nrows, rows, keep_columns, &k);
    }
    free(rows); free(d); free(x);
    if (st) return st;
    b->info.columns += nnew;
    return FFC_OK;
}

int ffc__bulk_add_columns(ffc__bulk *b, long nnew, const long nd[])
{
    const double t0 = ffc__seconds();
    const int st = add_columns_timed(b, nnew, nd);
    b->info.t_columns += ffc__seconds() - t0;
    return st;
}

/* The rows R: the dofs rows[nr] the contact evaluation may read.  A set
 * that is not within the kept one joins it and drops the compliance
 * columns (they lack the new rows; they are computed again as needed). */
int ffc__bulk_set_rows(ffc__bulk *b, long nr, const long rows[], long *bad)
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
int ffc__bulk_add_to_c(ffc__bulk *b, long nnew, const long nd[], long cap, long *bad)
{
    if (!nnew) return FFC_OK;
    if (b->m + nnew > cap) { *bad = b->m + nnew; return FFC_ERR_CAPACITY; }
    const int st = ffc__bulk_add_columns(b, nnew, nd);
    b->info.m = b->m;
    return st;
}

/* ------------------------------------------------- test hooks (ffc_bulk.h) */

void ffc__bulk_set_columns_mode(ffc__bulk *b, int supernodal, int prune)
{
    if (b) ffc__cholmod_set_mode(b->eng, supernodal, prune);
}

int ffc__bulk_columns(ffc__bulk *b, long nr, const long rows[], long nnew, const long nd[], long *bad)
{
    if (!b || (nr > 0 && !rows) || (nnew > 0 && !nd) || !bad) return FFC_ERR_NULL;
    if (nr < 0 || nnew < 0) return FFC_ERR_SIZE;
    for (long k = 0; k < nnew; k++)
        if (nd[k] < 0 || nd[k] >= b->n) { *bad = k; return FFC_ERR_INDEX; }
    int st = b->factored ? FFC_OK : ffc__bulk_factorize(b, 0, NULL);
    if (!st) st = ffc__bulk_set_rows(b, nr, rows, bad);
    if (!st) st = ffc__bulk_add_to_c(b, nnew, nd, b->mmax, bad);
    return st;
}

long ffc__bulk_compliance(const ffc__bulk *b, const long **dof, const double **G, long *ld, const double **H,
                          int *supernodal, double *pruned)
{
    ffc__cholmod_mode(b->eng, supernodal, pruned);
    if (dof) *dof = b->dof;
    if (G) *G = b->G;
    if (ld) *ld = b->ld;
    if (H) *H = b->H;
    return b->m;
}

/* The free dofs of cand[nc] (each once), or with whole = 1 every free
 * dof of their nodes, into b->nd[*nnew] */
int ffc__bulk_free_dofs(ffc__bulk *b, long nc, const long cand[], int whole, long *nnew, long *bad)
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
int ffc__bulk_shifted_into_c(ffc__bulk *b, long cap, long *bad)
{
    for (long k = 0; k < b->m; k++) b->pos[b->dof[k]] = k;
    long nnew = 0;
    for (long i = 0; i < b->n; i++)
        if (b->sh[i] != 0.0 && b->pos[i] == -1) b->nd[nnew++] = i;
    for (long k = 0; k < b->m; k++) b->pos[b->dof[k]] = -1;
    return ffc__bulk_add_to_c(b, nnew, b->nd, cap, bad);
}

/* Gc = the Cholesky factor L of G, extended to the columns added since
 * the last call: with G = [G11 G12; G21 G22] and L11 known,
 * L21 = (L11^-1 G12)^T and L22 = chol(G22 - L21 L21^T), O(mc^2 k) for k
 * new columns (a factorization from scratch would take m^3 / 3 at every
 * growth of C) */
int ffc__bulk_factor_g(ffc__bulk *b)
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
void ffc__bulk_g_inverse(const ffc__bulk *b, double x[])
{
    const int mi = (int)b->m, one = 1, ldi = (int)b->ld;
    int info = 0;
    if (mi) dpotrs_("L", &mi, &one, b->Gc, &ldi, x, &mi, &info);
}

