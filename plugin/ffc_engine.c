/* ffc_engine.c: what the linear engines share: failure records, the
 * ranks' shares of a piece of work, the inverse's entries by solves. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ffc_engine.h"

int ffc__engine_fail(ffc__engine *e, int st, ffc_where kind, long index, const char *fmt, ...)
{
    e->err.status = st;
    e->err.where = kind;
    e->err.index = index;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->err.msg, sizeof e->err.msg, fmt, ap);
    va_end(ap);
    return st;
}

void ffc__ranks_share(ffc__ranks *r, long n, long unit, long *lo, long *hi)
{
    for (int k = 0; k < r->size; k++) r->count[k] = (n * (k + 1) / r->size - n * k / r->size) * unit;
    *lo = n * r->rank / r->size;
    *hi = n * (r->rank + 1) / r->size;
}

void ffc__ranks_share_by(ffc__ranks *r, long n, const double w[], long unit, long *lo, long *hi)
{
    double all = 0.0, acc = 0.0;
    for (long k = 0; k < n; k++) all += w[k];
    for (long q = 0, k0 = 0, k = 0; q < r->size; q++, k0 = k) {
        const double goal = all * (double)(q + 1) / r->size;
        while (k < n && (q == r->size - 1 || acc + 0.5 * w[k] < goal)) acc += w[k++];
        r->count[q] = (k - k0) * unit;
        if (q == r->rank) { *lo = k0; *hi = k; }
    }
}

int ffc__inverse_by_solves(ffc__engine *e, long nc, const long cols[], long nrows, const long rows[],
                           ffc__inv_sink sink, void *ctx)
{
    const long n = e->n;
    double *b = calloc((size_t)(n > 0 ? n : 1), sizeof *b), *x = malloc((size_t)(n > 0 ? n : 1) * sizeof *x);
    double *V = malloc((size_t)(nrows > 0 ? nrows : 1) * sizeof *V);
    int st = e->op->agree(e, b && x && V) ? FFC_OK : ffc__engine_fail(e, FFC_ERR_MEMORY, FFC_AT_COUNT, n,
        "%s: out of memory for the work of the inverse's columns (order %ld)", e->op->name, n);
    for (long k = 0; k < nc && !st; k++) {
        b[cols[k]] = 1.0;
        st = e->op->solve(e, b, x);
        b[cols[k]] = 0.0;
        e->info->backsolves++;
        for (long r = 0; r < nrows && !st; r++) V[r] = x[rows[r]];
        if (!st) st = sink(ctx, 1, cols + k, V);
    }
    free(b); free(x); free(V);
    return st;
}
