/* ffc_internal.h: small vector helpers and constants shared by the kernels
 * (not part of the public interface). */
#ifndef FFC_INTERNAL_H
#define FFC_INTERNAL_H

/* A facet is degenerate when its area element is below this fraction of
 * its squared size (a sliver with angles below ~1e-10 rad). */
#define FFC__DEGEN_REL 1e-12

static inline double ffc__dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void ffc__cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

double ffc__facet_size2(const double X[][3]);

#include "ffc.h"
/* Foot on the facet's extension (no clamping): xi = xi_free. */
int ffc__project_free(int nn, const double X[][3], const double p[3], ffc_proj *out);

/* LU with partial pivoting of the column-major A[m*m] in place, then b =
 * A^-1 b (LAPACK); piv[m] work.  FFC_ERR_SINGULAR for a pivot below 1e-15
 * of the largest entry, FFC_ERR_NONFINITE for a non-finite entry
 * (ffc_reduced.c). */
int ffc__lu_solve(long m, double A[], long piv[], double b[]);

#endif
