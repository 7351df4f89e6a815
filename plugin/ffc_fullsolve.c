/* ffc_fullsolve.c: a full Newton system A x = b (general sparse: not
 * symmetric with friction, indefinite with multipliers) on a linear
 * engine: in one process CHOLMOD for a symmetric positive definite one,
 * UMFPACK otherwise, each analysed once per pattern, or PETSc's Krylov
 * solvers (the iterative path); parallel MUMPS over the ranks of a
 * communicator. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ffc_engine.h"
#include "ffc_internal.h"

/* (Ti, Tj, Tv)[nt] as the engines' int triplets (general); FFC_ERR_SIZE
 * past int's range, FFC_ERR_MEMORY */
static int int_triplets(long n, long nt, const long Ti[], const long Tj[], const double Tv[], int **ti, int **tj,
                        double **tv)
{
    *ti = *tj = NULL;
    *tv = NULL;
    if (n > 2147483647L) return FFC_ERR_SIZE;
    const size_t cap = (size_t)(nt > 0 ? nt : 1);
    *ti = malloc(cap * sizeof **ti);
    *tj = malloc(cap * sizeof **tj);
    *tv = malloc(cap * sizeof **tv);
    if (!*ti || !*tj || !*tv) {
        free(*ti); free(*tj); free(*tv);
        return FFC_ERR_MEMORY;
    }
    for (long k = 0; k < nt; k++) {
        (*ti)[k] = (int)Ti[k];
        (*tj)[k] = (int)Tj[k];
        (*tv)[k] = Tv[k];
    }
    return FFC_OK;
}

static int check_system(long n, long nt, const long Ti[], const long Tj[], const double Tv[], const double b[],
                        long *bad)
{
    int st = ffc__check_triplets(n, nt, Ti, Tj, Tv, bad);
    if (st) return st;
    for (long i = 0; i < n; i++)
        if (!isfinite(b[i])) { if (bad) *bad = i; return FFC_ERR_NONFINITE; }
    return FFC_OK;
}

int ffc_parallel_solve(const ffc_parallel *p, long n, long nt, const long Ti[], const long Tj[], const double Tv[],
                       const double b[], double x[], long *bad)
{
    if (!p || !b || !x || (nt > 0 && (!Ti || !Tj || !Tv))) return FFC_ERR_NULL;
    if (n <= 0 || nt < 0 || n > 2147483647L) return FFC_ERR_SIZE;
    if (!ffc_has_mpi()) return FFC_ERR_UNAVAILABLE;
    if (p->engine != FFC_ENGINE_MUMPS) return p->engine == FFC_ENGINE_CHOLMOD ? FFC_ERR_UNAVAILABLE : FFC_ERR_VALUE;
    int st = check_system(n, nt, Ti, Tj, Tv, b, bad);
    if (st) return st;
    int *ti, *tj;
    double *tv;
    if ((st = int_triplets(n, nt, Ti, Tj, Tv, &ti, &tj, &tv))) return st;
    const ffc__tri A = {n, nt, ti, tj, tv, 0};
    st = ffc__mumps_solve_once(p->comm, p->own, &A, b, x, NULL);
    free(ti); free(tj); free(tv);
    return st;
}

/* An engine and the pattern it analysed: by columns, rows ascending, as
 * the triplets (pi, pj)[nz] handed to it, with the values' buffer pv[nz].
 * A matrix whose entries all lie in that pattern is handed over on it
 * (zeros elsewhere): one analysis serves every matrix of a Newton solve
 * whose contact couples no new dofs. */
typedef struct {
    ffc__engine *eng;
    int sym;                   /* 1: the pattern is a symmetric matrix's lower triangle */
    int ready;                 /* 1: eng analysed the present pattern */
    long n, nz;                /* the order and the entries of the analysed pattern (0: none) */
    long *cp;                  /* [n + 1] column starts in pi */
    int *pi, *pj;              /* [nz] each entry's row and column */
    double *pv;                /* [nz] the values of the matrix at hand */
} pattern_engine;

/* A full solver: UMFPACK for any matrix, CHOLMOD for the symmetric ones
 * (their lower triangle), each with the pattern it analysed. */
struct ffc_full {
    pattern_engine lu, chol;   /* a general matrix (its LU), a symmetric one (its LL^T) */
    pattern_engine it;         /* the iterative path's (PETSc; eng NULL: none) */
    int iterative;             /* 1: general matrices go to it */
    long it_nv;                /* the nodes it was given (count; 0: none, every order goes to it) */
    ffc__ranks one;            /* CHOLMOD's ranks: this process */
    long one_count;            /* (its count array) */
    ffc_solve_info info;       /* the counters of both */
    long analyses;             /* patterns analysed, both engines (count) */
    long cholesky;             /* factorizations by CHOLMOD (count) */
    long not_posdef;           /* symmetric matrices CHOLMOD found not positive definite, solved by UMFPACK */
    long reuse;                /* GMRES iterations at most on the last factor before a new one (0: none) */
    long reused;               /* solves by GMRES on an earlier factor (count) */
    long krylov;               /* their iterations (count) */
    double *work;              /* [wcap] GMRES's basis and work */
    long wcap;
};

int ffc_full_create(ffc_full **out)
{
    if (!out) return FFC_ERR_NULL;
    ffc_full *f = calloc(1, sizeof *f);
    if (!f) return FFC_ERR_MEMORY;
    f->one = (ffc__ranks){0, 0, 1, &f->one_count};
    int st = ffc__umfpack_create(&f->info, &f->lu.eng);
    if (!st) st = ffc__cholmod_create(&f->info, &f->one, &f->chol.eng);
    if (st) { ffc_full_free(f); return st; }
    ffc__cholmod_set_rcond(f->chol.eng, 0.0);   /* (tgv rows: the caller checks the residual) */
    f->chol.sym = 1;
    *out = f;
    return FFC_OK;
}

static void pattern_free(pattern_engine *p)
{
    free(p->cp); free(p->pi); free(p->pj); free(p->pv);
    p->cp = NULL;
    p->pi = p->pj = NULL;
    p->pv = NULL;
    p->n = p->nz = 0;
    p->ready = 0;
}

void ffc_full_free(ffc_full *f)
{
    if (!f) return;
    if (f->lu.eng) f->lu.eng->op->free(f->lu.eng);
    if (f->chol.eng) f->chol.eng->op->free(f->chol.eng);
    if (f->it.eng) f->it.eng->op->free(f->it.eng);
    pattern_free(&f->lu);
    pattern_free(&f->chol);
    pattern_free(&f->it);
    free(f->work);
    free(f);
}

/* the position of row i in column j of p's pattern, or -1 */
static long find_entry(const pattern_engine *p, int i, int j)
{
    long lo = p->cp[j], hi = p->cp[j + 1] - 1;
    while (lo <= hi) {
        const long mid = (lo + hi) / 2;
        if (p->pi[mid] < i) lo = mid + 1;
        else if (p->pi[mid] > i) hi = mid - 1;
        else return mid;
    }
    return -1;
}

/* A's values on p's pattern (p->pv); 0 when an entry of A lies outside it */
static int scatter(pattern_engine *p, const ffc__tri *A)
{
    if (!p->cp || p->n != A->n) return 0;
    memset(p->pv, 0, (size_t)p->nz * sizeof *p->pv);
    for (long k = 0; k < A->nz; k++) {
        const long e = find_entry(p, A->i[k], A->j[k]);
        if (e < 0) return 0;
        p->pv[e] += A->v[k];
    }
    return 1;
}

/* p's pattern made the union of its own (when of the same order) and
 * A's, A's values scattered on it */
static int grow_pattern(pattern_engine *p, const ffc__tri *A)
{
    const long n = A->n, old = p->n == n ? p->nz : 0;
    long *cnt = calloc((size_t)n + 1, sizeof *cnt);
    int *ri = malloc((size_t)(A->nz + old + 1) * sizeof *ri);
    if (!cnt || !ri) { free(cnt); free(ri); return FFC_ERR_MEMORY; }
    for (long k = 0; k < A->nz; k++) cnt[A->j[k] + 1]++;
    for (long j = 0; j < n && old; j++) cnt[j + 1] += p->cp[j + 1] - p->cp[j];
    for (long j = 0; j < n; j++) cnt[j + 1] += cnt[j];
    long *fill = malloc((size_t)(n + 1) * sizeof *fill);
    if (!fill) { free(cnt); free(ri); return FFC_ERR_MEMORY; }
    memcpy(fill, cnt, (size_t)(n + 1) * sizeof *fill);
    for (long j = 0; j < n && old; j++)
        for (long e = p->cp[j]; e < p->cp[j + 1]; e++) ri[fill[j]++] = p->pi[e];
    for (long k = 0; k < A->nz; k++) ri[fill[A->j[k]]++] = A->i[k];
    /* each column sorted, its duplicates dropped, compacted */
    long nz = 0;
    for (long j = 0; j < n; j++) {
        int *c = ri + cnt[j];
        const long m = cnt[j + 1] - cnt[j];
        for (long a = 1; a < m; a++) { /* insertion sort: columns hold a few dozen rows */
            const int v = c[a];
            long b = a - 1;
            while (b >= 0 && c[b] > v) { c[b + 1] = c[b]; b--; }
            c[b + 1] = v;
        }
        const long start = nz;
        for (long a = 0; a < m; a++)
            if (a == 0 || c[a] != c[a - 1]) ri[nz++] = c[a];
        cnt[j] = start;
    }
    cnt[n] = nz;
    free(fill);
    pattern_free(p);
    p->cp = cnt;
    p->pi = ri;
    p->pj = malloc((size_t)(nz > 0 ? nz : 1) * sizeof *p->pj);
    p->pv = malloc((size_t)(nz > 0 ? nz : 1) * sizeof *p->pv);
    if (!p->pj || !p->pv) { pattern_free(p); return FFC_ERR_MEMORY; }
    for (long j = 0; j < n; j++)
        for (long e = cnt[j]; e < cnt[j + 1]; e++) p->pj[e] = (int)j;
    p->n = n;
    p->nz = nz;
    scatter(p, A);
    return FFC_OK;
}

/* y[n] = A x on p's pattern and values (by columns; a lower triangle
 * stands for its symmetric matrix) */
static void pattern_mult(const pattern_engine *p, const double x[], double y[])
{
    memset(y, 0, (size_t)p->n * sizeof *y);
    for (long j = 0; j < p->n; j++) {
        const double xj = x[j];
        for (long e = p->cp[j]; e < p->cp[j + 1]; e++) {
            const long i = p->pi[e];
            y[i] += p->pv[e] * xj;
            if (p->sym && i != j) y[j] += p->pv[e] * x[i];
        }
    }
}

static double norm2(long n, const double x[])
{
    double s = 0.0;
    for (long i = 0; i < n; i++) s += x[i] * x[i];
    return sqrt(s);
}

/* Formulation: A x = b for A on p's pattern (its values p->pv) by GMRES,
 * right-preconditioned with the factor M that p's engine holds of an
 * earlier matrix (a Newton tangent a few iterations older): the
 * preconditioned operator is near the identity.  The rows whose diagonal
 * is a tgv (>= 1e20: Dirichlet rows) are scaled by it (S = their
 * inverse), so that they weigh as the displacement they impose: the
 * system solved is (S A P^-1) y = S b, x = P^-1 y, P^-1 v = M^-1 S^-1 v.
 * Converged at a true scaled residual |S (b - A x)| <= 1e-13 |S b| (the
 * direct solve's own level: looser costs Newton iterations on
 * penalty-stiff systems), in at most f->reuse iterations, one cycle.
 * Returns the iterations, or -1 (x unspecified: the caller factorizes). */
static long gmres_reuse(ffc_full *f, const pattern_engine *p, const double b[], double x[])
{
    ffc__engine *prec = p->eng;
    const long n = p->n, m = f->reuse, m1 = m + 1;
    const long need = n * (m1 + 3) + m1 * m + 3 * m1;
    if (need > f->wcap) {
        double *w = realloc(f->work, (size_t)need * sizeof *w);
        if (!w) return -1;
        f->work = w;
        f->wcap = need;
    }
    double *V = f->work, *sc = V + n * m1, *w = sc + n, *z = w + n, *H = z + n, *cs = H + m1 * m, *sn = cs + m1,
           *g = sn + m1;
    for (long i = 0; i < n; i++) {
        const long e = find_entry(p, (int)i, (int)i);
        const double d = e >= 0 ? fabs(p->pv[e]) : 0.0;
        sc[i] = d >= 1e20 ? 1.0 / d : 1.0;
    }
    for (long i = 0; i < n; i++) V[i] = sc[i] * b[i];
    const double bn = norm2(n, V);
    if (!(bn > 0.0)) { memset(x, 0, (size_t)n * sizeof *x); return 0; }
    for (long i = 0; i < n; i++) V[i] /= bn;
    for (long i = 0; i < m1; i++) g[i] = 0.0;
    g[0] = bn;
    long j = 0;
    for (; j < m; j++) {
        /* V[:, j + 1] = S A M^-1 S^-1 V[:, j] */
        for (long i = 0; i < n; i++) w[i] = V[j * n + i] / sc[i];
        if (prec->op->solve(prec, w, z)) return -1;
        double *v1 = V + (j + 1) * n;
        pattern_mult(p, z, v1);
        for (long i = 0; i < n; i++) v1[i] *= sc[i];
        double *h = H + j * m1;
        for (long i = 0; i <= j; i++) { /* modified Gram-Schmidt */
            double d = 0.0;
            for (long r = 0; r < n; r++) d += v1[r] * V[i * n + r];
            h[i] = d;
            for (long r = 0; r < n; r++) v1[r] -= d * V[i * n + r];
        }
        h[j + 1] = norm2(n, v1);
        if (h[j + 1] > 0.0)
            for (long r = 0; r < n; r++) v1[r] /= h[j + 1];
        if (ffc__gmres_rotate(j, h, cs, sn, g)) return -1;
        if (fabs(g[j + 1]) <= 1e-13 * bn) { j++; break; }
        /* given up from the third iteration once off course for 1e-13 by
         * the m-th (more than 1e3 x the geometric course 1e-13^(k/m) after
         * k iterations): the factorization it would end in comes sooner.
         * (The soft ball at 19,014 dofs: the solves that reach 1e-13 are
         * below 1e-3 after 3 iterations; 65 of its 122 attempts stay above
         * 1e-2 and failed after all 8, 520 solves on the factor for nothing.) */
        if (j >= 2 && fabs(g[j + 1]) > 1e3 * pow(1e-13, (double)(j + 1) / (double)m) * bn) return -1;
    }
    if (!(fabs(g[j]) <= 1e-13 * bn) && j == m) return -1;
    /* y = H^-1 g (upper triangular, j x j), x = M^-1 S^-1 V y */
    for (long i = j - 1; i >= 0; i--) {
        double t = g[i];
        for (long k = i + 1; k < j; k++) t -= H[k * m1 + i] * g[k];
        g[i] = t / H[i * m1 + i];
    }
    memset(w, 0, (size_t)n * sizeof *w);
    for (long k = 0; k < j; k++)
        for (long i = 0; i < n; i++) w[i] += g[k] * V[k * n + i];
    for (long i = 0; i < n; i++) w[i] /= sc[i];
    if (prec->op->solve(prec, w, x)) return -1;
    /* the true scaled residual */
    pattern_mult(p, x, z);
    for (long i = 0; i < n; i++) z[i] = sc[i] * (b[i] - z[i]);
    return norm2(n, z) <= 1e-13 * bn ? j : -1;
}

/* A on p's engine: its entries scattered on the analysed pattern (grown
 * to the union of both when A has others); GMRES on the engine's last
 * factor (f->reuse iterations at most), else the pattern analysed if it
 * is new, A factorized (the next call's preconditioner) and solved.
 * (Tried and dropped for a general A: CHOLMOD's LL^T of its symmetric part
 * (A + A^T) / 2 as the preconditioner. The soft ball's contact tangents
 * are too far from symmetric: 10 GMRES iterations a solve, 89 s against
 * 82 s at 19,014 dofs.) */
static int pattern_solve(ffc_full *f, pattern_engine *p, const ffc__tri *A, const double b[], double x[])
{
    int st;
    if (!scatter(p, A)) {
        if ((st = grow_pattern(p, A))) { pattern_free(p); return st; }
        p->ready = 0;   /* (analysed when next factorized; the last factor stays a preconditioner) */
    }
    if (f->reuse > 0 && p != &f->it && p->eng->factored && p->eng->n == p->n) {
        const long it = gmres_reuse(f, p, b, x);
        if (it >= 0) {
            f->reused++;
            f->krylov += it;
            return FFC_OK;
        }
    }
    const ffc__tri P = {p->n, p->nz, p->pi, p->pj, p->pv, p->sym};
    if (!p->ready) {
        if ((st = p->eng->op->analyze(p->eng, &P))) return st;
        f->analyses++;
        p->ready = 1;
    }
    if ((st = p->eng->op->factorize(p->eng, &P))) return st;
    f->info.factorizations++;
    st = p->eng->op->solve(p->eng, b, x);
    f->info.backsolves += st == FFC_OK;
    return st;
}

int ffc_full_solve(ffc_full *f, long n, long nt, const long Ti[], const long Tj[], const double Tv[], int sym,
                   const double b[], double x[], ffc_error *err)
{
    long bad = -1;
    if (!f || !b || !x || (nt > 0 && (!Ti || !Tj || !Tv))) return FFC_ERR_NULL;
    if (n <= 0 || nt < 0) return FFC_ERR_SIZE;
    int st = check_system(n, nt, Ti, Tj, Tv, b, &bad);
    if (st) {
        if (err) {
            *err = (ffc_error){st, st == FFC_ERR_NONFINITE && bad < n && bad >= 0 && nt == 0 ? FFC_AT_DOF
                                                                                              : FFC_AT_TRIPLET, bad, ""};
            snprintf(err->msg, sizeof err->msg, "%s at entry %ld", ffc_strerror(st), bad);
        }
        return st;
    }
    int *ti, *tj;
    double *tv;
    if ((st = int_triplets(n, nt, Ti, Tj, Tv, &ti, &tj, &tv))) return st;
    if (sym) {
        /* the lower triangle, in place after the whole (kept for UMFPACK):
         * CHOLMOD's LL^T; not positive definite: UMFPACK below */
        int *li = malloc((size_t)(nt > 0 ? nt : 1) * sizeof *li), *lj = malloc((size_t)(nt > 0 ? nt : 1) * sizeof *lj);
        double *lv = malloc((size_t)(nt > 0 ? nt : 1) * sizeof *lv);
        if (!li || !lj || !lv) st = FFC_ERR_MEMORY;
        long nl = 0;
        for (long k = 0; k < nt && !st; k++)
            if (ti[k] >= tj[k]) { li[nl] = ti[k]; lj[nl] = tj[k]; lv[nl++] = tv[k]; }
        if (!st) {
            const ffc__tri L = {n, nl, li, lj, lv, 1};
            const long nf = f->info.factorizations;
            st = pattern_solve(f, &f->chol, &L, b, x);
            if (!st) f->cholesky += f->info.factorizations - nf;   /* (none for a solve on the last factor) */
            else if (st == FFC_ERR_SINGULAR) { f->not_posdef++; st = 1; }   /* (to UMFPACK) */
        }
        free(li); free(lj); free(lv);
        if (st && st != 1) {
            if (err) *err = f->chol.eng->err;
            free(ti); free(tj); free(tv);
            return st;
        }
        if (!st) { free(ti); free(tj); free(tv); return FFC_OK; }
    }
    const ffc__tri A = {n, nt, ti, tj, tv, 0};
    pattern_engine *p = f->iterative && (f->it_nv == 0 || n == 3 * f->it_nv) ? &f->it : &f->lu;
    st = pattern_solve(f, p, &A, b, x);
    free(ti); free(tj); free(tv);
    if (st && err) *err = p->eng->err;
    return st;
}

int ffc_full_set_reuse(ffc_full *f, long maxit)
{
    if (!f) return FFC_ERR_NULL;
    if (maxit < 0 || maxit > 1000) return FFC_ERR_VALUE;
    f->reuse = maxit;
    return FFC_OK;
}

int ffc_full_reuse_info(const ffc_full *f, long *reused, long *krylov)
{
    if (!f) return FFC_ERR_NULL;
    if (reused) *reused = f->reused;
    if (krylov) *krylov = f->krylov;
    return FFC_OK;
}

int ffc_full_info(const ffc_full *f, ffc_solve_info *info, long *analyses, long *cholesky, long *not_posdef)
{
    if (!f || !info) return FFC_ERR_NULL;
    *info = f->info;
    if (analyses) *analyses = f->analyses;
    if (cholesky) *cholesky = f->cholesky;
    if (not_posdef) *not_posdef = f->not_posdef;
    return FFC_OK;
}

int ffc_full_set_iterative(ffc_full *f, const ffc_iterative *opt)
{
    if (!f || !opt || (opt->nv > 0 && !opt->xyz)) return FFC_ERR_NULL;
    if (!opt->on) {
        f->iterative = 0;
        return FFC_OK;
    }
    if (opt->shared && !ffc_has_mpi()) return FFC_ERR_UNAVAILABLE;
    if (!(opt->rtol > 0.0 && opt->rtol < 1.0) || opt->maxit < 1 || opt->maxit > 100000 || opt->nv < 0 ||
        (opt->pc != FFC_PC_GAMG && opt->pc != FFC_PC_HYPRE && opt->pc != FFC_PC_MUMPS))
        return FFC_ERR_VALUE;
    for (long k = 0; k < 3 * opt->nv; k++)
        if (!isfinite(opt->xyz[k])) return FFC_ERR_NONFINITE;
    ffc__engine *e = NULL;
    const int st = ffc__petsc_create(&f->info, opt, &e);
    if (st) return st;
    if (f->it.eng) f->it.eng->op->free(f->it.eng);
    pattern_free(&f->it);
    f->it.eng = e;
    f->iterative = 1;
    f->it_nv = opt->nv;
    return FFC_OK;
}

int ffc_full_iterative_info(const ffc_full *f, ffc_iterative_info *info)
{
    if (!f || !info) return FFC_ERR_NULL;
    memset(info, 0, sizeof *info);
    return f->it.eng ? ffc__petsc_info(f->it.eng, info) : FFC_OK;
}

int ffc_full_set_block(ffc_full *f, long n, long nb, const long dofs[])
{
    if (!f || (nb > 0 && !dofs)) return FFC_ERR_NULL;
    if (nb < 0 || nb > n) return FFC_ERR_SIZE;
    for (long k = 0; k < nb; k++)
        if (dofs[k] < 0 || dofs[k] >= n || (k > 0 && dofs[k] <= dofs[k - 1])) return FFC_ERR_INDEX;
    if (!f->it.eng) return FFC_OK;
    return ffc__petsc_set_block(f->it.eng, nb, dofs);
}
