/* ffc_csolve.c: one solve of (K + Kc) x = b on the contact dofs: two
 * back-solves with K's factor and a dense LU of I + G Kc on C, then
 * iterative refinement. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc_bulk_state.h"
#include "ffc_internal.h"

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
    ffc__bulk_lift(b, nt, Ti, Tj, Tv, rhs, t);
    int st = ffc__bulk_backsolve(b, t, x);
    if (st) return st;
    if (b->m > 0 && !ffc__bulk_dense_a(b)) return FFC_ERR_MEMORY;
    st = ffc_reduced_solve(n, b->ld, b->m, b->dof, b->G, nt, Ti, Tj, b->kv, b->sh, x, b->xc, b->w, b->A, b->piv,
                           b->pos);
    if (st) return st;
    st = ffc__bulk_backsolve(b, b->w, b->r);
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
    ffc__bulk_clear_error(b);
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
        st = ffc__bulk_factorize_first(b, nnew, b->nd);
        if (st) return st;
    }
    if (nnew) {
        st = ffc__bulk_add_columns(b, nnew, b->nd);
        if (st) return st;
    }
    b->info.m = b->m;
    st = solve_once(b, nt, Ti, Tj, Tv, rhs, x);
    if (st) return st;
    /* iterative refinement: at most two corrections, while they help */
    ffc__bulk_residual(b, nt, Ti, Tj, Tv, rhs, x, b->r);
    double e = residual_size(b, rhs, x, b->r);
    for (int k = 0; k < 2 && e > 1e-13; k++) {
        double *dx = b->dx;
        memcpy(b->w, b->r, (size_t)n * sizeof(double)); /* solve_once overwrites w and r */
        st = solve_once(b, nt, Ti, Tj, Tv, b->w, dx);
        if (st) return st;
        for (long i = 0; i < n; i++) x[i] += dx[i];
        ffc__bulk_residual(b, nt, Ti, Tj, Tv, rhs, x, b->r);
        const double e2 = residual_size(b, rhs, x, b->r);
        b->info.refinements++;
        if (!(e2 < 0.5 * e)) { e = e2; break; }
        e = e2;
    }
    b->info.residual = e;
    if (!(e <= 1e-6)) return FFC_ERR_SINGULAR;
    return FFC_OK;
}

