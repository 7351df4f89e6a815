/* ffc_scene_state.h: a scene's internal state (struct ffc_scene, its pairs) and what its files share. */
#ifndef FFC_SCENE_STATE_H
#define FFC_SCENE_STATE_H

#include "ffc.h"
#include "ffc_bulk.h"

typedef struct {
    ffc_pair_opts o;   /* method, law and search options */
    long nfs, nfm;     /* slave, master facets */
    long *Fs, *Fm;     /* [nfs*nper], [nfm*nper] facet nodes */
    ffc_tree *tree;    /* over the master facets (built at the first search) */
    int nq;            /* quadrature points per slave facet */
    long nl;           /* links: nfs * nq (mortar: as the last search found) */
    long lcap;         /* capacity of links (mortar) */
    long nsn;          /* distinct slave vertices (the rows of node output: mortar, nodal pairs asked for nodes) */
    long *mp, nmp, mpcap; /* mortar: the facet pairs of the last search [2 mpcap], their count */
    ffc_mortar_edge *edges; /* [ecap] mortar: the moving-edge points of the segments */
    long ne, ecap;
    ffc_link *links;   /* [nl] */
    double *dual;      /* [9 nfs] mortar: the dual basis of each slave facet (ffc_dual_basis) */
    long nlam;         /* multipliers: nv (nodal) or nl (pointwise) */
    double *lam, *lam_t;   /* [nlam], [3 nlam] */
    double *lam0, *lam_t0; /* the same at the last commit */
    signed char *fst, *fst0; /* [nlam] friction: each multiplier's state (FFC_FRIC_*) at the last
                          augmentation, and at the last commit: what the step's end reports (read
                          again there, where nothing has slipped since, every traction passes the
                          stick test); all open before any augmentation */
    ffc_stats st;      /* last assembly, with the augmentation's own fields
                          (max_dlam, max_dlam_t, max_pen_node) of the last augmentation */
    ffc_stats st_step; /* st at the last commit: the converged step's statistics */
    /* node-to-surface (o.method == FFC_METHOD_NTS) */
    long nn;           /* slave nodes */
    ffc_nts_node *nodes, *nodes0; /* [nn] their table, and at the last commit */
    int located;       /* 1 once the nodes were located (their states set) */
    long row0, nr;     /* its rows in the stacked rows of the last ffc_scene_nts_rows */
    ffc_nts_stats nst, nst_step; /* the last update, and at the last commit */
    /* a rigid obstacle as the master (obst = 1; nfm = 0, Fm NULL) */
    int obst;
    ffc_obstacle ob, ob0; /* its placement now (ob.d: its motion since ob0, ffc__obstacle_motion),
                          and at the last commit */
    ffc_obstacle base; /* its placement at load factor 0 */
    double move[3];    /* its translation from there at load factor 1 (length) */
} scene_pair;

struct ffc_scene {
    int nper;          /* nodes per facet: 3 (linear) or 6 (quadratic) */
    long nv;           /* nodes */
    double *X;         /* [nv*3] reference positions (length) */
    long nt;           /* tetrahedra (for the inversion check; 0: none) */
    long *T;           /* [nt*4] corner nodes of each tetrahedron */
    double *v0;        /* [nt] six times each one's reference volume (length^3) */
    ffc_effects fx;    /* the scene's effects (friction: per pair, mu > 0) */
    double *u_prev;    /* [nv*3] displacement at the last commit (length) */
    double *v;         /* [nv*3] velocities (dynamic; length/time) */
    double dt, dvdu;   /* dynamic: time step (time), dv/du (1/time) */
    double *x;         /* [nv*3] work: current positions */
    int np, cap;       /* pairs, capacity */
    scene_pair *p;     /* [cap] */
    ffc__bulk *bulk;   /* the bulk factorization (NULL: none set) */
    ffc_parallel par;  /* where the bulk matrix is factorized */
    double *fixed;     /* [nv*3] prescribed dofs (nonzero), or NULL: none given */
    ffc_settings set;  /* the driver's settings */
    ffc_bulk_law law;  /* what the bulk is (its kind, linear, symmetric, finite deformation) */
    ffc_linesearch ls; /* the driver's Newton line search in progress */
};

/* The rule the kernels take: the pair's, or 0 for segment links */
static inline int ffc__pair_qdeg(const scene_pair *p) { return p->o.method == FFC_METHOD_MORTAR ? 0 : p->o.qdeg; }

/* What the kernels take for one pair: its nodes, its law, its effects. */
typedef struct {
    ffc_pair v;
    ffc_law law;
    ffc_effects fx;
} pair_call;

/* The ranks of a communicator sharing out a pair's links (the condensed
 * Newton's contact evaluations on several ranks): rank r takes the linked
 * links [n r / size, n (r + 1) / size) of the n in the links' order (by
 * slave facet: a share is a strip of slave facets); the node sums,
 * the residual at the pair's dofs, the triplets and the link statistics
 * are summed over the ranks in rank order, so that every rank gets the
 * same bits.  Every call that takes one is collective: each rank makes the same
 * ones, also on failure (the first failing rank's status is every rank's). */
typedef struct {
    int comm, rank, size;
} share_ctx;

/* ---- ffc_scene.c */

/* The slave node table of a node-to-surface pair, every node open and
 * not located (and its checkpoint); on failure the pair keeps its own. */
int ffc__nts_alloc(const ffc_scene *s, scene_pair *p);

/* An obstacle pair's motion ob.d from its placements: quasi-static
 * ob.c - ob0.c, dynamic (ob.c - ob0.c) / dt. */
void ffc__obstacle_motion(const ffc_scene *s, scene_pair *p);

/* ---- ffc_scene_eval.c */

/* Current positions x = X + u; FFC_ERR_NONFINITE (*bad = node) otherwise. */
int ffc__scene_positions(ffc_scene *s, const double u[], long *bad);
/* The kernels' view of pair p at displacement u, and its law. */
pair_call ffc__pair_view(const ffc_scene *s, const scene_pair *p, const double u[], int tangent);
/* 1 when every pair has its normal penalty; else 0 with *bad = the first
 * pair without one. */
int ffc__penalties_set(const ffc_scene *s, long *bad);
/* ffc_scene_assemble; with share (not NULL), the augmented Lagrangian's
 * nodal pairs without segments share out their links over its ranks
 * where the tangent is none or ranked (the others evaluate whole on every
 * rank) */
int ffc__scene_assemble(ffc_scene *s, const double u[], int tangent, double R[], long cap, long Ti[], long Tj[],
                        double Tv[], long *ntrip, long *bad, const share_ctx *share, int *shared);

/* ---- ffc_scene_out.c */

/* mean longest edge (vertices 0-2) of nf facets F[nf*nper] at positions X */
double ffc__mean_size(int nper, long nf, const long F[], const double X[]);

#endif
