/* ffc_sparse.c: sparse-matrix utilities: the duplicates of a triplet list
 * summed, rows grouped (what the plugin hands to FreeFEM). */
#include <math.h>

#include "ffc.h"
#include "ffc_internal.h"

long ffc_triplets_sum(long n, long nt, const long Ti[], const long Tj[], const double Tv[], long Ci[],
                      long Cj[], double Cv[], long rp[], long w[])
{
    if (!rp || !w || (nt > 0 && (!Ti || !Tj || !Tv || !Ci || !Cj || !Cv))) return FFC_ERR_NULL;
    if (n <= 0 || nt < 0) return FFC_ERR_SIZE;
    for (long t = 0; t < nt; t++)
        if (Ti[t] < 0 || Ti[t] >= n || Tj[t] < 0 || Tj[t] >= n) return FFC_ERR_INDEX;
    /* rows: counts, then starts (rp), then the triplets scattered by row into
     * (Ci, Cj, Cv) with w as the fill pointer */
    for (long i = 0; i <= n; i++) rp[i] = 0;
    for (long t = 0; t < nt; t++) rp[Ti[t] + 1]++;
    for (long i = 0; i < n; i++) rp[i + 1] += rp[i];
    for (long i = 0; i < n; i++) w[i] = rp[i];
    for (long t = 0; t < nt; t++) {
        const long k = w[Ti[t]]++;
        Cj[k] = Tj[t];
        Cv[k] = Tv[t];
    }
    /* each row: w[col] = where the column's sum sits (< start: not yet in
     * this row), compacted in place; rows only move down */
    for (long i = 0; i < n; i++) w[i] = -1;
    long nz = 0;
    for (long i = 0; i < n; i++) {
        const long start = nz;
        for (long k = rp[i]; k < rp[i + 1]; k++) {
            const long j = Cj[k];
            if (w[j] >= start) Cv[w[j]] += Cv[k];
            else {
                w[j] = nz;
                Ci[nz] = i;
                Cj[nz] = j;
                Cv[nz++] = Cv[k];
            }
        }
    }
    return nz;
}

/* FFC_ERR_INDEX / FFC_ERR_NONFINITE (*bad = the triplet) for an index
 * outside [0, n) or a non-finite value among (Ti, Tj, Tv)[nt] */
int ffc__check_triplets(long n, long nt, const long Ti[], const long Tj[], const double Tv[], long *bad)
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
