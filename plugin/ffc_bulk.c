/* ffc_bulk.c: the bulk stiffness of a small-strain scene factorized once
 * (CHOLMOD) and the Newton systems (K + Kc) x = b solved on the contact
 * dofs (the compliance G grown by block back-solves, see ffc.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <suitesparse/cholmod.h>

#include "ffc_bulk.h"

enum { BLOCK = 32 };   /* compliance columns per block back-solve */

struct ffc__bulk {
    long n;                    /* dofs */
    long nt;                   /* triplets of K */
    long *Ti, *Tj;             /* [nt] K's triplets (both triangles) */
    double *Tv;                /* [nt] (force/length) */
    double *diag;              /* [n] K's diagonal */
    unsigned char *big;        /* [n] 1 on Dirichlet rows (diagonal >= 1e12 x the median) */
    double kfree;              /* mean diagonal of the other rows (force/length) */
    double *sh;                /* [n] shift s on the dofs of the first contact tangent */
    int started;               /* cholmod_start called */
    cholmod_common cc;
    cholmod_factor *L;         /* of K + diag(sh); NULL until the first solve */
    cholmod_dense *B, *X, *Y, *E;       /* one right-hand side and solve2's work */
    cholmod_dense *Bb, *Xb, *Yb, *Eb;   /* a block of BLOCK right-hand sides */
    long m, ld;                /* contact dofs, leading dimension of G */
    long *dof;                 /* [ld] contact dofs */
    double *G;                 /* [ld*ld] compliance (column-major) */
    long *pos;                 /* [n] work (-1) */
    long *nd;                  /* [n] work: new contact dofs */
    double *A;                 /* [ld*ld] work: I + G Kcc */
    long *piv;                 /* [ld] work */
    double *xc, *w, *r, *dx, *t; /* [ld], [n], [n], [n], [n] work */
    double *kv;                /* [kvcap] work: Kc's values without Dirichlet rows and columns */
    long kvcap;
    long mmax;                 /* contact dofs this path takes at most */
    ffc_solve_info info;
};

static void bulk_free_factor(ffc__bulk *b)
{
    if (!b->started) return;
    cholmod_dense **d[] = {&b->B, &b->X, &b->Y, &b->E, &b->Bb, &b->Xb, &b->Yb, &b->Eb};
    for (size_t k = 0; k < sizeof d / sizeof *d; k++)
        if (*d[k]) cholmod_free_dense(d[k], &b->cc);
    if (b->L) cholmod_free_factor(&b->L, &b->cc);
    b->m = 0;
}

void ffc__bulk_free(ffc__bulk *b)
{
    if (!b) return;
    bulk_free_factor(b);
    if (b->started) cholmod_finish(&b->cc);
    free(b->Ti); free(b->Tj); free(b->Tv); free(b->diag); free(b->big); free(b->sh);
    free(b->dof); free(b->G); free(b->pos); free(b->nd); free(b->A); free(b->piv);
    free(b->xc); free(b->w); free(b->r); free(b->dx); free(b->t); free(b->kv);
    free(b);
}

/* FFC_ERR_INDEX / FFC_ERR_NONFINITE (*bad = the triplet) for an index
 * outside [0, n) or a non-finite value among (Ti, Tj, Tv)[nt] */
static int check_triplets(long n, long nt, const long Ti[], const long Tj[], const double Tv[], long *bad)
{
    for (long t = 0; t < nt; t++) {
        const int st = Ti[t] < 0 || Ti[t] >= n || Tj[t] < 0 || Tj[t] >= n ? FFC_ERR_INDEX
                       : !isfinite(Tv[t])                                  ? FFC_ERR_NONFINITE
                                                                           : FFC_OK;
        if (st) {
            if (bad) *bad = t;
            return st;
        }
    }
    return FFC_OK;
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
    const int st = check_triplets(n, nt, Ti, Tj, Tv, bad);
    if (st) return st;
    ffc__bulk *b = calloc(1, sizeof *b);
    if (!b) return FFC_ERR_MEMORY;
    b->n = n;
    b->nt = nt;
    b->mmax = mmax;
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
    *out = b;
    return FFC_OK;
}

/* grows G (and the dense work) to hold m contact dofs */
static int grow(ffc__bulk *b, long m)
{
    if (m <= b->ld) return FFC_OK;
    long ld = b->ld ? b->ld : 64;
    while (ld < m) ld *= 2;
    double *G = calloc((size_t)ld * ld, sizeof(double));
    double *A = malloc((size_t)ld * ld * sizeof(double));
    long *dof = malloc((size_t)ld * sizeof(long)), *piv = malloc((size_t)ld * sizeof(long));
    double *xc = malloc((size_t)ld * sizeof(double));
    if (!G || !A || !dof || !piv || !xc) {
        free(G); free(A); free(dof); free(piv); free(xc);
        return FFC_ERR_MEMORY;
    }
    for (long c = 0; c < b->m; c++) {
        memcpy(G + c * ld, b->G + c * b->ld, (size_t)b->m * sizeof(double));
        dof[c] = b->dof[c];
    }
    free(b->G); free(b->A); free(b->dof); free(b->piv); free(b->xc);
    b->G = G; b->A = A; b->dof = dof; b->piv = piv; b->xc = xc;
    b->ld = ld;
    return FFC_OK;
}

/* y = (K + S)^-1 rhs, one back-solve */
static int backsolve(ffc__bulk *b, const double rhs[], double y[])
{
    memcpy(b->B->x, rhs, (size_t)b->n * sizeof(double));
    if (!cholmod_solve2(CHOLMOD_A, b->L, b->B, NULL, &b->X, NULL, &b->Y, &b->E, &b->cc)) return FFC_ERR_MEMORY;
    memcpy(y, b->X->x, (size_t)b->n * sizeof(double));
    b->info.backsolves++;
    for (long i = 0; i < b->n; i++)
        if (!isfinite(y[i])) return FFC_ERR_NONFINITE;
    return FFC_OK;
}

/* the factorization of K' + S, S = diag(sh) on the dofs nd[nnew], K' = K
 * with each Dirichlet row and column replaced by kfree on the diagonal (the
 * values of those dofs are moved to the right-hand side: the same solution
 * as the tgv rows' to within 1/tgv, and a factor whose pivots show a
 * singular K: its estimated reciprocal condition below 1e-12 is refused) */
static int factorize(ffc__bulk *b, long nnew, const long nd[])
{
    if (!b->started) {
        cholmod_start(&b->cc);
        b->cc.print = 0;              /* kernels never print */
        b->cc.error_handler = NULL;
        b->started = 1;
    }
    for (long k = 0; k < nnew; k++) b->sh[nd[k]] = b->kfree;
    long nlow = 0;
    for (long t = 0; t < b->nt; t++) nlow += b->Ti[t] >= b->Tj[t] && !b->big[b->Ti[t]] && !b->big[b->Tj[t]];
    cholmod_triplet *T = cholmod_allocate_triplet((size_t)b->n, (size_t)b->n, (size_t)(nlow + b->n), -1,
                                                  CHOLMOD_REAL, &b->cc);
    if (!T) return FFC_ERR_MEMORY;
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
    cholmod_sparse *A = cholmod_triplet_to_sparse(T, (size_t)c, &b->cc);
    cholmod_free_triplet(&T, &b->cc);
    if (!A) return FFC_ERR_MEMORY;
    b->L = cholmod_analyze(A, &b->cc);
    int st = b->L ? FFC_OK : FFC_ERR_MEMORY;
    if (!st) {
        cholmod_factorize(A, b->L, &b->cc);
        if (b->cc.status == CHOLMOD_NOT_POSDEF || b->L->minor < b->L->n) st = FFC_ERR_SINGULAR;
        else if (b->cc.status < CHOLMOD_OK) st = FFC_ERR_MEMORY;
        else {
            b->info.rcond = cholmod_rcond(b->L, &b->cc);
            if (!(b->info.rcond >= 1e-12)) st = FFC_ERR_SINGULAR;
        }
    }
    cholmod_free_sparse(&A, &b->cc);
    if (!st) {
        b->B = cholmod_zeros((size_t)b->n, 1, CHOLMOD_REAL, &b->cc);
        b->Bb = cholmod_zeros((size_t)b->n, BLOCK, CHOLMOD_REAL, &b->cc);
        if (!b->B || !b->Bb) st = FFC_ERR_MEMORY;
    }
    if (st) {
        bulk_free_factor(b);
        for (long k = 0; k < nnew; k++) b->sh[nd[k]] = 0.0;
        return st;
    }
    b->info.factorizations++;
    b->info.shift = nnew ? b->kfree : 0.0;
    return FFC_OK;
}

/* the compliance columns of the dofs nd[nnew], BLOCK back-solves at a time */
static int add_columns(ffc__bulk *b, long nnew, const long nd[])
{
    int st = grow(b, b->m + nnew);
    if (st) return st;
    const long n = b->n;
    for (long k0 = 0; k0 < nnew; k0 += BLOCK) {
        const long nb = nnew - k0 < BLOCK ? nnew - k0 : BLOCK;
        double *bx = b->Bb->x;
        memset(bx, 0, (size_t)n * BLOCK * sizeof(double));
        for (long k = 0; k < nb; k++) bx[nd[k0 + k] + k * n] = 1.0;
        if (!cholmod_solve2(CHOLMOD_A, b->L, b->Bb, NULL, &b->Xb, NULL, &b->Yb, &b->Eb, &b->cc))
            return FFC_ERR_MEMORY;
        b->info.backsolves += nb;
        const double *xb = b->Xb->x;
        for (long k = 0; k < nb; k++) {
            st = ffc_reduced_add(n, b->ld, b->m, b->dof, b->G, xb + k * n, nd[k0 + k]);
            if (st) return st;
            b->m++;
        }
    }
    b->info.columns += nnew;
    return FFC_OK;
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
static int solve_once(ffc__bulk *b, long nt, const long Ti[], const long Tj[], const double Tv[],
                      const double rhs[], double x[])
{
    const long n = b->n;
    double *t = b->t;
    memcpy(t, rhs, (size_t)n * sizeof(double));
    for (long i = 0; i < n; i++)
        if (b->big[i]) t[i] = b->kfree * (rhs[i] / b->diag[i]);
    for (long k = 0; k < b->nt; k++)
        if (b->big[b->Tj[k]] && !b->big[b->Ti[k]]) t[b->Ti[k]] -= b->Tv[k] * (rhs[b->Tj[k]] / b->diag[b->Tj[k]]);
    for (long k = 0; k < nt; k++)
        if (b->big[Tj[k]] && !b->big[Ti[k]]) t[Ti[k]] -= Tv[k] * (rhs[Tj[k]] / b->diag[Tj[k]]);
    int st = backsolve(b, t, x);
    if (st) return st;
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
    int st = check_triplets(n, nt, Ti, Tj, Tv, bad);
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
    if (!b->L) {
        /* the first factorization: the dofs of this contact tangent carry the
         * shift (they hold any body that only contact holds) */
        st = factorize(b, nnew, b->nd);
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
}

long ffc__bulk_n(const ffc__bulk *b) { return b ? b->n : 0; }

double ffc__bulk_kfree(const ffc__bulk *b) { return b ? b->kfree : 0.0; }
