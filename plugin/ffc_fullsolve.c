/* ffc_fullsolve.c: a full Newton system A x = b (general sparse: not
 * symmetric with friction, indefinite with multipliers) on a linear
 * engine: UMFPACK in one process, analysed once per pattern; parallel
 * MUMPS over the ranks of a communicator. */
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

/* A full solver: the engine and the pattern it analysed. */
struct ffc_full {
    ffc__engine *eng;          /* UMFPACK */
    ffc_solve_info info;       /* its counters */
    long n, nt;                /* the order and the entries of the analysed pattern */
    long *pi, *pj;             /* [nt] its indices */
    long analyses;             /* patterns analysed (count) */
};

int ffc_full_create(ffc_full **out)
{
    if (!out) return FFC_ERR_NULL;
    ffc_full *f = calloc(1, sizeof *f);
    if (!f) return FFC_ERR_MEMORY;
    const int st = ffc__umfpack_create(&f->info, &f->eng);
    if (st) { free(f); return st; }
    *out = f;
    return FFC_OK;
}

void ffc_full_free(ffc_full *f)
{
    if (!f) return;
    if (f->eng) f->eng->op->free(f->eng);
    free(f->pi); free(f->pj);
    free(f);
}

/* 1 when (Ti, Tj)[nt] is the analysed pattern */
static int same_pattern(const ffc_full *f, long n, long nt, const long Ti[], const long Tj[])
{
    if (!f->pi || n != f->n || nt != f->nt) return 0;
    return memcmp(Ti, f->pi, (size_t)nt * sizeof *Ti) == 0 && memcmp(Tj, f->pj, (size_t)nt * sizeof *Tj) == 0;
}

static int keep_pattern(ffc_full *f, long n, long nt, const long Ti[], const long Tj[])
{
    free(f->pi); free(f->pj);
    f->pi = malloc((size_t)(nt > 0 ? nt : 1) * sizeof *f->pi);
    f->pj = malloc((size_t)(nt > 0 ? nt : 1) * sizeof *f->pj);
    if (!f->pi || !f->pj) {
        free(f->pi); free(f->pj);
        f->pi = f->pj = NULL;
        return FFC_ERR_MEMORY;
    }
    if (nt > 0) {
        memcpy(f->pi, Ti, (size_t)nt * sizeof *Ti);
        memcpy(f->pj, Tj, (size_t)nt * sizeof *Tj);
    }
    f->n = n;
    f->nt = nt;
    f->analyses++;
    return FFC_OK;
}

int ffc_full_solve(ffc_full *f, long n, long nt, const long Ti[], const long Tj[], const double Tv[],
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
    const ffc__tri A = {n, nt, ti, tj, tv, 0};
    if (!same_pattern(f, n, nt, Ti, Tj)) {
        st = f->eng->op->analyze(f->eng, &A);
        if (!st) st = keep_pattern(f, n, nt, Ti, Tj);
        if (st) { free(f->pi); free(f->pj); f->pi = f->pj = NULL; }
    }
    if (!st) st = f->eng->op->factorize(f->eng, &A);
    if (!st) {
        f->info.factorizations++;
        st = f->eng->op->solve(f->eng, b, x);
        f->info.backsolves += st == FFC_OK;
    }
    free(ti); free(tj); free(tv);
    if (st && err) *err = f->eng->err;
    return st;
}

int ffc_full_info(const ffc_full *f, ffc_solve_info *info, long *analyses)
{
    if (!f || !info) return FFC_ERR_NULL;
    *info = f->info;
    if (analyses) *analyses = f->analyses;
    return FFC_OK;
}
