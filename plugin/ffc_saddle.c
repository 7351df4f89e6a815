/* ffc_saddle.c: the node-to-surface saddle point [K Bf'; B Cm] [x; m] =
 * [f; c] on the bulk's factor: the Schur complement on the constraint
 * rows (or, with a shifted K, the system coupled with C), then iterative
 * refinement. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc_bulk_state.h"
#include "ffc_internal.h"

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
    ffc__bulk_lift(b, 0, NULL, NULL, NULL, rhs, t);
    int st = ffc__bulk_backsolve(b, t, x0);
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
    st = ffc__bulk_backsolve(b, t, x);
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
    ffc__bulk_residual(b, 0, NULL, NULL, NULL, rhs, x, ru);
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

/* The dense system of one saddle solve into S->A (S->W: G Bf'), from the
 * rows and G (b->pos: -1 on entry and on return) */
static void saddle_build(ffc__bulk *b, saddle_sys *S)
{
    const long n = b->n, m = b->m, ld = b->ld, nt = S->nt, nr = S->nr, na = S->na;
    const long *Bi = S->Bi, *Bj = S->Bj;
    const double *Bv = S->Bv, *Fv = S->Fv;
    for (long k = 0; k < m; k++) b->pos[b->dof[k]] = k;
    if (!S->coupled) {
        /* W = G Bf' (m x nr), column by row: G's column of each entry's dof */
        double *W = S->W, *A = S->A;
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
    } else {
        /* [I - G S_C, G Bf'; B, Cm] */
        double *A = S->A;
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
    ffc__bulk_clear_error(b);
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
    if (!b->factored && (st = ffc__bulk_factorize_first(b, nnew, b->nd))) return st;
    if ((st = ffc__bulk_add_to_c(b, nnew, b->nd, b->mmax, bad)) || (st = ffc__bulk_shifted_into_c(b, b->mmax, bad))) return st;
    const int coupled = b->info.shift != 0.0; /* (the factor is of K + S) */
    b->info.solves++;
    const long m = b->m, na = coupled ? m + nr : nr;
    if (na > 46340) return FFC_ERR_SIZE; /* (na^2 within an int for LAPACK) */
    saddle_sys S = {nt, nr, Bi, Bj, Bv, Fv, coupled, na, NULL, NULL, NULL, NULL};
    S.A = malloc((size_t)(na * na + 1) * sizeof(double));
    S.piv = malloc((size_t)(na + 1) * sizeof(int));
    S.W = coupled ? NULL : malloc((size_t)(m * nr + 1) * sizeof(double));
    S.v = malloc((size_t)(na + 1) * sizeof(double));
    double *ru = malloc((size_t)(n + nr + 1) * sizeof(double)), *dm = malloc((size_t)(nr + 1) * sizeof(double));
    if (!S.A || !S.piv || (!coupled && !S.W) || !S.v || !ru || !dm) st = FFC_ERR_MEMORY;
    if (!st) saddle_build(b, &S);
    if (!st && na > 0) {
        const int nai = (int)na;
        int info = 0;
        dgetrf_(&nai, &nai, S.A, &nai, S.piv, &info);
        if (info) st = FFC_ERR_SINGULAR;
    }
    /* the scale of the residual test: the free rows of the lifted rhs */
    double fs = 0.0;
    ffc__bulk_lift(b, 0, NULL, NULL, NULL, rhs, b->t);
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
