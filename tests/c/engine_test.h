/* engine_test.h: what the engine tests share (internal interface): the
 * inverse's entries of an engine kept in the order asked for. */
#ifndef ENGINE_TEST_H
#define ENGINE_TEST_H

#include <string.h>

#include "ffc_engine.h"

typedef struct { const long *cols; long nc, nrows; double *X; } test_inv_keep;
static inline int test_inv_keep_piece(void *ctx, long nc, const long cols[], const double V[])
{
    test_inv_keep *k = ctx;
    for (long c = 0; c < nc; c++) {
        long at = 0;
        while (at < k->nc && k->cols[at] != cols[c]) at++;
        for (long r = 0; r < k->nrows; r++) k->X[r + at * k->nrows] = V[r + c * k->nrows];
    }
    return FFC_OK;
}
/* X[r + c * nrows] = (A^-1)[rows[r], cols[c]] by the engine e (nc <= 16) */
static inline int test_inverse(ffc__engine *e, long nc, const long cols[], long nrows, const long rows[], double X[])
{
    long c2[16];
    memcpy(c2, cols, (size_t)nc * sizeof *c2);
    test_inv_keep k = {cols, nc, nrows, X};
    return e->op->inverse(e, nc, c2, nrows, rows, test_inv_keep_piece, &k);
}

#endif
