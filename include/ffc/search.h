/* ffc/search.h: contact search: options, links, the search tree, closest-facet queries. */
#ifndef FFC_API_SEARCH_H
#define FFC_API_SEARCH_H

#include "status.h"
#include "geom.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --------------------------------------------------------------- search */
/* Contact search: for each quadrature point of each slave facet, the
 * closest point on the master surface (exact: a bounding-volume tree with
 * branch-and-bound), classified as interior, on an edge or vertex shared by
 * master facets (a link with the foot clamped there), or beyond the edge of
 * the master surface (outside the footprint: no link).  A point counts as
 * beyond the edge when its distance past the rim, in the tangent plane of
 * the facet, exceeds edge_tol h_f plus its distance |g| to the facet's
 * plane (the cone over the rim's edge): a point in a symmetry plane, or on
 * a slave surface flush with the master's rim, whose foot on a facet that
 * the deformation tilted falls just past the rim, keeps its link, open or
 * penetrating (the node-to-surface rim rule alike). */

typedef struct {
    double capture_rel;  /* capture distance relative to the partner master
                            facet's longest edge (1); >= 0 */
    double capture_abs;  /* absolute capture distance (length); >= 0.  A point
                            gets a link when its distance to the master
                            surface is <= max(capture_abs, capture_rel h_f) */
    double edge_tol;     /* a foot outside its facet by at most this much in
                            local coordinates still counts as inside (1); >= 0 */
    int self;            /* 1: self-contact, the slave facets are the master
                            facets, in the same order (ffc_search): a point
                            links only to a facet of higher index (each two
                            facing facets once: one pass), that shares no
                            vertex with its own facet and whose normal
                            opposes its facet's (n_m . n_s < 0; not where
                            the surface merely curves); ffc_mortar_pairs
                            alike, facet by facet; 0: surfaces apart */
} ffc_search_opts;

/* Defaults: capture_rel 2, capture_abs 0, edge_tol 1e-9, self 0. */
ffc_search_opts ffc_search_defaults(void);

/* One contact link: a slave quadrature point and its master partner. */
typedef struct {
    long sf;        /* slave facet (index into the slave facet array) */
    int q;          /* quadrature point index in the slave facet */
    double xs[2];   /* slave local coordinates of the quadrature point (1) */
    long mf;        /* master facet, -1 when the point has no partner */
    double xm[2];   /* master local coordinates of the foot (1) */
    double gap;     /* signed normal gap n . (x_s - x_m) (length) */
    double n[3];    /* unit master normal at the foot (1) */
    int where;      /* FFC_FOOT_* of the foot on the master facet */
    double w;       /* segment links (q = -1, see ffc_mortar_search): the
                       point's weight on the slave facet's reference
                       triangle of area 1/2 (1); unused otherwise (the
                       rule's weight of point q applies) */
} ffc_link;

/* Opaque search structure over one master surface (owns its memory). */
typedef struct ffc_tree ffc_tree;

/* Builds the tree of the master surface F[nf*nn] with node positions
 * x[nv*3] (current configuration).  *out is NULL on error. */
int ffc_tree_build(int nn, long nf, const long F[], long nv, const double x[],
                   ffc_tree **out);

/* Updates the bounding boxes for new node positions x[nv*3] keeping the
 * tree's order (cheaper than a rebuild; queries stay exact, they only get
 * slower if facets moved far relative to each other). */
int ffc_tree_refit(ffc_tree *t, const double x[]);

/* Frees the tree (NULL allowed). */
void ffc_tree_free(ffc_tree *t);

/* Bytes held by the tree. */
long ffc_tree_bytes(const ffc_tree *t);

/* Closest master facet to p within distance rmax: *facet (or -1) and its
 * projection. */
int ffc_tree_nearest(const ffc_tree *t, const double p[3], double rmax,
                     long *facet, ffc_proj *pr);

/* Links of the slave surface Fs[nfs*nns] (positions xs_nodes[*3], usually
 * the same array as the master's) against the tree, Gauss rule of degree
 * qdeg: nfs * ffc_quad_size(qdeg) links, in the order (facet, point).
 * cap is the capacity of links[].  Returns the number of links that have
 * a partner, or an error (FFC_ERR_CAPACITY: cap too small). */
int ffc_search(const ffc_tree *t, int nns, long nfs, const long Fs[],
               long nvs, const double xs_nodes[], int qdeg,
               const ffc_search_opts *o, long cap, ffc_link links[]);

/* The same result from a loop over all master facets (reference for tests
 * and benchmarks). */
int ffc_search_brute(const ffc_tree *t, int nns, long nfs, const long Fs[],
                     long nvs, const double xs_nodes[], int qdeg,
                     const ffc_search_opts *o, long cap, ffc_link links[]);

/* Links of np points p[np*3] (e.g. slave nodes) against the tree, with
 * the footprint and capture rules of ffc_search; links[k].sf = k, q = 0.
 * Returns the number of points with a partner, or an error. */
int ffc_search_points(const ffc_tree *t, long np, const double p[],
                      const ffc_search_opts *o, ffc_link links[]);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_SEARCH_H */
