/* ffc/mortar.h: mortar segments: clipping, segment points, moving edges, the dual basis, facet pairs, links. */
#ifndef FFC_API_MORTAR_H
#define FFC_API_MORTAR_H

#include "status.h"
#include "geom.h"
#include "search.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --------------------------------------------------- mortar segments */
/* Segment-to-segment integration (mortar): each slave facet is clipped
 * against the projections of the master facets it overlaps, and the
 * contact integrals are evaluated with a Gauss rule on each piece, so
 * that integrands that are smooth on each piece but kink at master edges
 * are integrated exactly (the contact patch test).  Linear facets. */
#define FFC_CLIPMAX 8   /* vertices of an input polygon of ffc_clip_polygon */

/* Intersection of the convex counter-clockwise polygons a[na] and b[nb]
 * (3 <= na, nb <= FFC_CLIPMAX) into out[cap] (cap >= na + nb),
 * counter-clockwise.  Returns its vertex count (0: they do not overlap,
 * or only along an edge or at a point), or FFC_ERR_NULL, _SIZE,
 * _CAPACITY, _NONFINITE, _DEGENERATE (an input that is not
 * counter-clockwise with a positive area). */
int ffc_clip_polygon(int na, const double a[][2], int nb, const double b[][2], int cap, double out[][2]);

/* The integration points of the slave facet Xs[3][3] (vertex positions)
 * over the part covered by the master facet Xm[3][3] projected along the
 * slave normal: xi[cap][2] local coordinates on the slave facet, w[cap]
 * weights on its reference triangle (area 1/2), the Gauss rule of degree
 * qdeg on each triangle of the clipped polygon; *covered = the covered
 * area in local coordinates (1/2: all).  With exi != NULL also the points
 * of the segment's moving edges (those on a projected master edge):
 * exi[ecap][2], and edv[ecap][18] their weight times the outward normal
 * velocity of the edge per unit change of each dof (slave facet nodes,
 * then master facet nodes; x, y, z each), *ne their count: the boundary
 * term of the segment's motion (see ffc_mortar.c).  Returns the number of
 * points (0: no overlap), FFC_ERR_CAPACITY when cap or ecap is too small,
 * or an error. */
int ffc_mortar_segment(int qdeg, const double Xs[3][3], const double Xm[3][3], long cap, double xi[][2],
                       double w[], long ecap, double exi[][2], double edv[][18], long *ne, double *covered);

/* A moving-edge point of a segment: where the segment's boundary follows
 * a master edge, the boundary term of its motion in the tangent. */
typedef struct {
    long sf, mf;       /* slave facet, master facet */
    double xs[2];      /* slave local coordinates of the point (1) */
    double dv[FFC_MAXDOF]; /* line weight x outward normal velocity per unit change of each dof of
                          the slave facet's nn nodes then the master facet's nn, x, y, z each, as a
                          link's dofs (1/length; the first 3 nodes' entries only: a segment
                          follows the vertex triangles) */
} ffc_mortar_edge;

/* Dual (biorthogonal) multiplier basis of a linear slave facet from the
 * points xi[n], w[n] of its covered part: Phi_a = sum_b A[a][b] N_b with
 * sum_q w_q Phi_a N_b = delta_ab sum_q w_q N_a (see ffc_mortar.c).  A = I
 * (standard basis) for n = 0 or a nearly singular coverage. */
int ffc_dual_basis(long n, const double xi[][2], const double w[], double A[3][3]);

/* Segment links of the slave surface Fs[nfs*nn] (positions x[nvs*3])
 * against the tree's master surface (nn = the tree's nodes per facet, 3
 * or 6; the segments of 6-node facets are those of their vertex
 * triangles, see ffc_mortar_links): for every slave
 * facet, every master facet that faces it (normals opposed) and whose box
 * overlaps the slave facet's box grown by the capture distance of
 * ffc_search gives the points of ffc_mortar_segment, provided one of them
 * lies within that distance at its segment's centre (a facet is in the
 * band or not, never cut by its edge); each link has q = -1, its weight w, the
 * master facet and the foot of the point on the facet's plane.  Links of
 * a facet are consecutive, facets in order.  Returns the number of links
 * written; FFC_ERR_CAPACITY with *need the count when cap is too small. */
int ffc_mortar_search(const ffc_tree *t, long nfs, const long Fs[], long nvs, const double x[], int qdeg,
                      const ffc_search_opts *o, long cap, ffc_link links[], long *need);

/* The facet pairs of ffc_mortar_search (slave facets Fs[nfs*nn], nn the
 * tree's nodes per facet): pairs[2 k] the slave facet,
 * pairs[2 k + 1] the master facet of pair k (cap pairs at most; *need the
 * count).  Returns the count or an error (FFC_ERR_CAPACITY).  With
 * o->self (the slave facets are the tree's, in the same order): no pair
 * of a facet with itself, with one of lower index or with one sharing a
 * corner vertex. */
int ffc_mortar_pairs(const ffc_tree *t, long nfs, const long Fs[], long nvs, const double x[],
                     const ffc_search_opts *o, long cap, long pairs[], long *need);

/* The segments of given facet pairs at positions x[nvs*3] (slave facets
 * Fs[nfs*nn], master facets Fm[nfm*nn], nn = 3 or 6 nodes each): their
 * links (as ffc_mortar_search,
 * whatever the capture distance: the pairs were chosen by it) into
 * links[lcap] (*lneed their count) and, with edges != NULL, their
 * moving-edge points into edges[ecap] (*eneed).  Returns the link count,
 * FFC_ERR_CAPACITY (the needs set) or an error (*lneed = the pair at
 * fault for FFC_ERR_INDEX).  6-node facets: the segments are clipped on
 * the vertex triangles (exact for straight-sided facets, the curved
 * facet's edges to O(h^2 / R) otherwise), each point xi lies on the
 * curved slave facet x(xi) = sum_a N_a(xi) x_a and its foot on the curved
 * master facet; the edge points' velocities have the vertices' dofs only. */
int ffc_mortar_links(int nn, long nfs, const long Fs[], long nfm, const long Fm[], long nvs, const double x[], int qdeg,
                     long npairs, const long pairs[], long lcap, ffc_link links[], long *lneed, long ecap,
                     ffc_mortar_edge edges[], long *eneed);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_MORTAR_H */
