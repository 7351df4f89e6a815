/* ffc_reduced.c: the contact-reduced linear solve of a small-strain step:
 * the compliance G of the contact dofs, grown column by column, and the
 * dense system (I + G Kcc) x_C = y_C that replaces a factorization of
 * K + Kc (see ffc/bulk.h). */
#include "ffc.h"
#include "ffc_internal.h"

#include <math.h>
#include <string.h>

int ffc_reduced_missing(long n, long m, const long dof[], long nt, const long Ti[], const long Tj[],
                        const double Tv[], long cap, long out[], long *nout, long pos[])
{
    if (!nout || !pos || (m > 0 && !dof) || (nt > 0 && (!Ti || !Tj || !Tv)) || (cap > 0 && !out)) return FFC_ERR_NULL;
    if (n <= 0 || m < 0 || m > n || nt < 0 || cap < 0) return FFC_ERR_SIZE;
    for (long i = 0; i < n; i++) pos[i] = -1;
    for (long k = 0; k < m; k++) {
        if (dof[k] < 0 || dof[k] >= n) return FFC_ERR_INDEX;
        pos[dof[k]] = k;
    }
    /* pos = -2 marks a new dof (counted once) */
    long cnt = 0;
    int s = FFC_OK;
    for (long t = 0; t < nt && !s; t++) {
        if (Tv[t] == 0.0) continue;
        const long ij[2] = {Ti[t], Tj[t]};
        for (int e = 0; e < 2; e++) {
            const long d = ij[e];
            if (d < 0 || d >= n) { s = FFC_ERR_INDEX; break; }
            if (pos[d] == -1) { pos[d] = -2; cnt++; }
        }
    }
    *nout = cnt;
    if (!s && cnt > cap) s = FFC_ERR_CAPACITY;
    long c = 0;
    for (long i = 0; i < n; i++) {
        if (pos[i] == -2 && !s) out[c++] = i;
        pos[i] = -1;
    }
    return s;
}

int ffc_reduced_add(long n, long ld, long m, long dof[], double G[], const double x[], long j)
{
    if (!dof || !G || !x) return FFC_ERR_NULL;
    if (n <= 0 || m < 0 || ld <= 0) return FFC_ERR_SIZE;
    if (m >= ld) return FFC_ERR_CAPACITY;
    if (j < 0 || j >= n) return FFC_ERR_INDEX;
    for (long i = 0; i < m; i++)
        if (dof[i] == j || dof[i] < 0 || dof[i] >= n) return FFC_ERR_INDEX;
    for (long i = 0; i < m; i++)
        if (!isfinite(x[dof[i]])) return FFC_ERR_NONFINITE;
    if (!isfinite(x[j])) return FFC_ERR_NONFINITE;
    for (long i = 0; i < m; i++) {
        G[i + m * ld] = x[dof[i]];
        G[m + i * ld] = x[dof[i]];
    }
    G[m + m * ld] = x[j];
    dof[m] = j;
    return FFC_OK;
}

/* LAPACK (the BLAS-3 blocked LU: m reaches a few thousand) */
void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a, const int *lda, const int *ipiv,
             double *b, const int *ldb, int *info);

/* LU with partial pivoting of the column-major A[m*m] in place, then the
 * solve of A z = b (b overwritten by z); the pivots are kept as ints in
 * piv's storage.  A pivot below 1e-15 of the largest entry is a singular
 * system (rank lost to round-off). */
int ffc__lu_solve(long m, double A[], long piv[], double b[])
{
    if (m == 0) return FFC_OK;
    if (m > 2147483647L / m) return FFC_ERR_SIZE;
    double amax = 0.0;
    for (long k = 0; k < m * m; k++) amax = fmax(amax, fabs(A[k]));
    if (!isfinite(amax)) return FFC_ERR_NONFINITE;
    const int mi = (int)m, one = 1;
    int *ip = (int *)piv, info = 0;
    dgetrf_(&mi, &mi, A, &mi, ip, &info);
    if (info < 0) return FFC_ERR_VALUE;
    for (long k = 0; k < m; k++)
        if (!(fabs(A[k + k * m]) > 1e-15 * amax)) return FFC_ERR_SINGULAR;
    dgetrs_("N", &mi, &one, A, &mi, ip, b, &mi, &info);
    return info ? FFC_ERR_VALUE : FFC_OK;
}

int ffc_reduced_solve(long n, long ld, long m, const long dof[], const double G[], long nt, const long Ti[],
                      const long Tj[], const double Tv[], const double sh[], const double y[], double xc[],
                      double w[], double A[], long piv[], long pos[])
{
    if (!y || !w || !pos || (m > 0 && (!dof || !G || !xc || !A || !piv)) || (nt > 0 && (!Ti || !Tj || !Tv)))
        return FFC_ERR_NULL;
    if (n <= 0 || m < 0 || m > n || ld < m || nt < 0) return FFC_ERR_SIZE;
    for (long i = 0; i < n; i++) { pos[i] = -1; w[i] = 0.0; }
    int s = FFC_OK;
    for (long k = 0; k < m && !s; k++) {
        if (dof[k] < 0 || dof[k] >= n) s = FFC_ERR_INDEX;
        else pos[dof[k]] = k;
    }
    for (long t = 0; t < nt && !s; t++) {
        if (Ti[t] < 0 || Ti[t] >= n || Tj[t] < 0 || Tj[t] >= n) s = FFC_ERR_INDEX;
        else if (!isfinite(Tv[t])) s = FFC_ERR_NONFINITE;
        else if (Tv[t] != 0.0 && (pos[Ti[t]] < 0 || pos[Tj[t]] < 0)) s = FFC_ERR_INDEX;
    }
    if (sh)
        for (long i = 0; i < n && !s; i++) {
            if (!isfinite(sh[i])) s = FFC_ERR_NONFINITE;
            else if (sh[i] != 0.0 && pos[i] < 0) s = FFC_ERR_INDEX;
        }
    if (!s) {
        /* A = I + G Kcc: column pos(j) gains v G(:, pos(i)) for Kcc(i, j) = v */
        for (long k = 0; k < m * m; k++) A[k] = 0.0;
        for (long k = 0; k < m; k++) A[k + k * m] = 1.0;
        for (long t = 0; t < nt; t++) {
            if (Tv[t] == 0.0) continue;
            const double v = Tv[t];
            const double *gi = G + pos[Ti[t]] * ld;
            double *aj = A + pos[Tj[t]] * m;
            for (long r = 0; r < m; r++) aj[r] += v * gi[r];
        }
        if (sh) /* Kcc' = Kcc - diag(sh): column k gains -sh G(:, k) */
            for (long k = 0; k < m; k++) {
                const double v = -sh[dof[k]];
                if (v == 0.0) continue;
                const double *gk = G + k * ld;
                double *ak = A + k * m;
                for (long r = 0; r < m; r++) ak[r] += v * gk[r];
            }
        for (long k = 0; k < m; k++) {
            xc[k] = y[dof[k]];
            if (!isfinite(xc[k])) s = FFC_ERR_NONFINITE;
        }
    }
    if (!s) s = ffc__lu_solve(m, A, piv, xc);
    if (!s) { /* w = P Kcc' x_C */
        for (long t = 0; t < nt; t++)
            if (Tv[t] != 0.0) w[Ti[t]] += Tv[t] * xc[pos[Tj[t]]];
        if (sh)
            for (long k = 0; k < m; k++) w[dof[k]] -= sh[dof[k]] * xc[k];
    }
    for (long k = 0; k < m; k++)
        if (dof[k] >= 0 && dof[k] < n) pos[dof[k]] = -1;
    return s;
}
