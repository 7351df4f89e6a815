/* ffc/surface.h: labelled boundary surfaces: selection, checks, area, normals; the inversion check. */
#ifndef FFC_API_SURFACE_H
#define FFC_API_SURFACE_H

#include "status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------- surfaces */
/* A labelled surface: the boundary faces of a volume mesh that carry one of
 * a set of labels.  Node indices refer to the volume mesh numbering. */

/* Selects the boundary faces whose label is in labs[nlab].
 *   nbe faces, be[nbe*nn] node indices, belab[nbe] labels, beopp[nbe] the
 *   node of the adjacent tetrahedron opposite the face (for orientation),
 *   X[nv*3] node positions.
 * Writes the selected faces, oriented so that the normal points out of
 * the body, into F[cap*nn] and returns their count.
 * Errors: FFC_ERR_LABEL (*bad = the missing label), FFC_ERR_EMPTY,
 * FFC_ERR_INDEX / FFC_ERR_NONFINITE / FFC_ERR_DEGENERATE (*bad = face
 * index), FFC_ERR_CAPACITY (*bad = needed count). */
int ffc_surface_select(int nn, long nbe, const long be[], const long belab[],
                       const long beopp[], long nv, const double X[],
                       int nlab, const long labs[], long cap, long F[],
                       long *bad);

/* Distinct labels among belab[nbe], ascending, into out[cap]; returns the
 * number of distinct labels (may exceed cap: only cap are written). */
long ffc_labels_present(long nbe, const long belab[], long cap, long out[]);

/* Checks a surface F[nf*nn] against nv nodes at positions X[nv*3] + u[nv*3]
 * (u may be NULL): indices in range, finite positions, non-degenerate
 * facets.  On error *bad is the facet index (or node index for
 * FFC_ERR_NONFINITE). */
int ffc_surface_check(int nn, long nf, const long F[], long nv,
                      const double X[], const double u[], long *bad);

/* Area of the surface F[nf*nn] at positions X + u (u may be NULL),
 * integrated with the Gauss rule of the given degree. */
int ffc_surface_area(int nn, long nf, const long F[], long nv,
                     const double X[], const double u[], int degree,
                     double *area);

/* Checks the nt tetrahedra T[nt*4] at positions X + u: FFC_ERR_INVERTED
 * (*bad = the tetrahedron) when one has turned inside out or collapsed
 * (its signed volume, relative to the reference one, below 1e-12), e.g.
 * after a diverged Newton step. */
int ffc_volume_check(long nt, const long T[], long nv, const double X[],
                     const double u[], long *bad);

/* The shape quality of the nt tetrahedra T[nt*4] at X: the mean ratio
 * 12 (3 |V|)^(2/3) / (sum of the squared edge lengths), 1 for the regular
 * tetrahedron and 0 for a flat one.  *worst and *worst_tet: the lowest and
 * the first tetrahedron that has it; *below: how many lie below qbelow.
 * FFC_ERR_NULL, FFC_ERR_SIZE (nt or nv not positive), FFC_ERR_VALUE
 * (qbelow negative or NaN); FFC_ERR_INDEX and FFC_ERR_NONFINITE with
 * *worst_tet = the tetrahedron with a vertex out of range or a coordinate
 * not finite. */
int ffc_mesh_quality(long nt, const long T[], long nv, const double X[], double qbelow, double *worst,
                     long *worst_tet, long *below);

/* Unit normals N[nf*3] at the centroid of each facet of F[nf*nn], at
 * positions X + u (u may be NULL).  Errors as ffc_surface_check. */
int ffc_surface_normals(int nn, long nf, const long F[], long nv,
                        const double X[], const double u[], double N[],
                        long *bad);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_SURFACE_H */
