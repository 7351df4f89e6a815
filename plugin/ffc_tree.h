/* ffc_tree.h: the bounding-volume tree over the master facets, shared by
 * its build (ffc_tree.c), its queries (ffc_search.c) and mortar pairing
 * (ffc_pairs.c); not part of the public interface. */
#ifndef FFC_TREE_H
#define FFC_TREE_H

#include "ffc.h"

#define FFC__LEAF 2      /* facets per leaf (2 measured fastest of 2, 4, 8) */
#define FFC__STACK 256   /* traversal stack (depth <= 64 levels, 2 per level) */

struct ffc_tree {
    int nn;            /* nodes per facet: 3 or 6 */
    long nf;           /* facets */
    long nv;           /* node positions expected by refit */
    long P;            /* leaves rounded up to a power of two */
    long *F;           /* [nf*nn] connectivity (original facet order) */
    long *slot2f;      /* [nf] tree slot -> facet */
    long *f2slot;      /* [nf] facet -> tree slot */
    double *hf;        /* [nf] longest edge of each facet, by facet (length) */
    unsigned char *degen; /* [nf] by slot: 1 for a linear facet ffc_project refuses (no area), which no
                             query takes */
    double *fx;        /* [nf*nn*3] facet node positions, tree order (length) */
    double *box;       /* [2P*6] node boxes lo[3], hi[3] (length) */
    float *qb;         /* [P/2*24] the traversal's boxes: at 24 i those of node i's four grandchildren
                          4i..4i+3, lo x, y, z then hi x, y, z, four values each, relative to qo in
                          units of qscale, widened (see fill_quad_boxes; NULL when P < 4) */
    int depth;         /* log2 P: the leaves' level (the root's is 0) */
    double qo[3];      /* qb's origin: the root box's centre (length) */
    double qscale;     /* the root box's largest half-width (length) */
    int qfast;         /* 1: qb usable (qscale between 1e-30 and 1e30) */
    long *nbr;         /* [nf*3] facet across edge e (vertices e, e+1), -1 on the rim */
    unsigned char *vrim; /* [nf*3] 1 when vertex a lies on the rim of the surface */
    double hmax;       /* longest facet edge (length) */
};

/* the box b = lo[3], hi[3] of a facet's nn nodes X[nn*3] (a quadratic
 * facet's: the hull of its Bezier control points) */
void ffc__facet_box(int nn, const double *X, double b[6]);

#endif
