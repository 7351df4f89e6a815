/* ffc/nts.h: node-to-surface Lagrange multipliers: slave nodes, constraint rows, updates; a scene's nts pairs. */
#ifndef FFC_API_NTS_H
#define FFC_API_NTS_H

#include "status.h"
#include "search.h"
#include "link.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------- node-to-surface Lagrange multipliers */
/* Each slave node c is paired with the master facet (i, j, k) under it:
 * area coordinates L of the foot, unit master normal n, gap
 * g = n . (x_c - sum_a L_a x_a).  With the relative displacement
 * D u = u_c - sum_a L_a u_a (3 x ndof), the constraint rows are
 *   slide:  n^T D u = n^T D u^k - g^k        (one row: the linearized gap
 *                                             vanishes; exact for flat facets)
 *   stick:  the slide row and t_i^T D u = t_i^T D u^n, i = 1, 2  (no
 *           tangential motion over the master since the last converged
 *           step u^n; t_1, t_2 an orthonormal tangent basis of n)
 *   slide with friction: the slide row and two sliding rows, Coulomb's
 *           law linearized at the last iterate (see ffc_nts_rows)
 *   open:   none.
 * The saddle-point system  [K  Bf^T; B  C] [u; m] = [f; c]  gives the
 * multipliers m; the contact force on the slave node is -(Bf^T m) at its
 * dofs: F = -m_n n - m_1 t_1 - m_2 t_2 with friction (stick or slide),
 * F = -m_n n without; all scaled by law->scale.  Bf = B and C = 0 except
 * on sliding rows with friction, whose B holds M t_a (the slip's part)
 * and C the multipliers' part of the linearized law.
 * Transitions (ffc_nts_update): open -> contact when g < -gtol (stick if
 * nu_s > 0 and the node has not moved tangentially since u^n, else slide
 * along that motion); contact -> open when F_n < -ftol max F_n
 * (tension release); stick -> slide when |F_t| > nu_s F_n (1 + 1e-9)
 * (d = -F_t/|F_t|);
 * slide -> stick when |q| <= nu_d F_n, with q = -F_t + c s, s the
 * tangential slip since the last converged step, c = law->scale (the
 * projection form of Coulomb's law: a primal-dual active-set rule, noise
 * in s does not flip the state); else the node slides along d = q / |q|.
 * With the sliding rows' Newton linearization the active-set loop is a
 * semi-smooth Newton method.  Chattering guard: once a node has changed state
 * max_flips times in one load step, each update makes one change only,
 * at the first node in order that asks for one (the least-index rule,
 * which terminates for frictionless contact, a P-matrix complementarity
 * problem, where changing every violated node at once may cycle).  A
 * node that has changed state 2 max_flips times stays open for the rest of
 * the step (stats->locked; its penetration is min_gap_open). */
enum { FFC_NTS_OPEN = 0, FFC_NTS_STICK = 1, FFC_NTS_SLIDE = 2 };

typedef struct {
    double nu_s;       /* static friction coefficient (1), >= 0 */
    double nu_d;       /* dynamic friction coefficient (1), 0 <= nu_d <= nu_s */
    double gtol;       /* an open node enters contact when g < -gtol (length), >= 0 */
    double ftol;       /* tension release when F_n < -ftol * max F_n (1), >= 0 */
    int max_flips;     /* state changes of a node per load step before the
                          chattering guard acts (>= 1) */
    double scale;      /* rows and right-hand sides are multiplied by scale (force/length,
                          e.g. E h: balances the saddle-point matrix); > 0 */
} ffc_nts_law;

/* One slave node: its state (carried across iterations and steps) and its
 * geometry and force (refreshed by each call). */
typedef struct {
    long node;         /* slave node (pair numbering) */
    double area;       /* tributary area int N_c dA on the slave surface (length^2) */
    int state;         /* FFC_NTS_* */
    int flips;         /* state changes in the current load step */
    int chatter;       /* 1 once the node reached max_flips changes in this step */
    double dir[3];     /* sliding direction d of the slave over the master (1) */
    long mf;           /* master facet under the node, -1 for none */
    double L[3];       /* area coordinates of the foot (1) */
    double n[3];       /* unit master normal at the foot (1) */
    double gap;        /* g (length) */
    double slip[3];    /* tangential motion over the master since u^n (length) */
    long row;          /* first constraint row, -1 for none */
    int rmask;         /* rows present: bit 0 normal, bits 1, 2 tangents (friction) */
    double nr[3];      /* normal the rows were built with (1) */
    double f[3];       /* contact force on the slave node (force) */
    double fn;         /* its normal part n_r . f, > 0 compressive (force) */
    long mfprev;       /* master facet before the last change of mf in this step, -1 for none */
    int frozen;        /* 1: mf is kept for the rest of the step (no search) */
    int tfix;          /* prescribed tangential dof of the node (set by ffc_nts_rows):
                          0 none, k + 1 for dof k, 4 for two or more */
} ffc_nts_node;

/* Summary of an update. */
typedef struct {
    long changes;      /* state changes made by this update */
    long open, stick, slide; /* nodes in each state after it */
    long chatter;      /* nodes that reached max_flips: the guard acts (one change per update) */
    long released;     /* contact -> open changes in this update */
    long locked;       /* open nodes that penetrate but were kept open: they changed
                          state 2 max_flips times in this step (min_gap_open shows
                          their penetration) */
    double max_pen;    /* largest penetration max(0, -g) over contact nodes (length) */
    double min_fn;     /* smallest F_n over the nodes that had rows (force; 0 if none):
                          negative when a node was released */
    double min_gap_open; /* smallest gap over open nodes with a partner (length; 0 if none) */
    double max_ddir;   /* largest change |d_new - d_old| of a sliding direction (1) */
    double force[3];   /* total contact force on the slave nodes (force) */
    double max_ratio;  /* largest |F_t| / F_n over contact nodes (1) */
    double max_gap_err; /* largest |g| over nodes that had rows and stay in contact:
                          the geometric error of the linearized rows (length) */
    double max_slide_res; /* largest |F_t + nu_d F_n d| over nodes that slide on,
                          divided by the largest F_n: Coulomb's law's residual (1) */
} ffc_nts_stats;

/* The distinct nodes of the slave facets of pair (3-node facets), in
 * ascending order, with their tributary areas in the reference
 * configuration; state open.  cap: capacity of out[].  Returns the
 * number of nodes (FFC_ERR_CAPACITY with *need set when cap is short). */
long ffc_nts_nodes(const ffc_pair *pair, long cap, ffc_nts_node out[], long *need);

/* Pairs each node with the master facet under it at x = X + u (search
 * options o, NULL for the defaults) and refreshes mf, L, n, gap and
 * slip (against pair->u_prev; zero when it is NULL).  A contact node
 * whose facet returns to the one it had before (A -> B -> A: it sits in a
 * valley of the master between two facets, and one facet's constraint
 * puts it into the other) is frozen: it keeps that facet, projected onto
 * it (onto its boundary when the foot is outside), until the caller
 * clears frozen and mfprev (at the next load step).  A contact node the
 * search leaves without a partner keeps its facet when its foot lies past
 * the master's rim by no more than its distance |g| to the facet's plane
 * (a node held in a symmetry plane that cuts the master at its rim).  A
 * contact node whose foot lies on its facet to 1e-9 in local coordinates
 * keeps it where the search gives another (a vertex or an edge the two
 * share: which one is round-off, and their normals differ).  With init != 0 the
 * state is also set: contact (stick if law->nu_s > 0, else slide) when
 * g <= law->gtol, open otherwise. */
int ffc_nts_locate(const ffc_pair *pair, const ffc_nts_law *law, const ffc_search_opts *o,
                   int init, long nn, ffc_nts_node nodes[]);

/* Constraint rows of the contact nodes (geometry of the last locate), as
 * triplets (Bi, Bj) with values Bv (B) and Fv (Bf), and right-hand side
 * c[]; a column Bj >= 3 nv is column Bj - 3 nv of the multiplier block C
 * (value in Bv, Fv = 0: sliding rows with friction); entries on dofs with fixed[dof] != 0 (Dirichlet; fixed may be
 * NULL) are moved to c with the value in pair->u, and a row left empty
 * is dropped.  cap: capacity of the triplet arrays, ccap of c.
 * Writes *ntrip and *nrows (or the sizes needed with FFC_ERR_CAPACITY)
 * and each node's row, nr and tfix.  With friction, a contact node whose
 * slave dof k is held at zero in a tangential direction (fixed > 0,
 * |n_k| < 0.9, e.g. on a symmetry plane) has no row along that direction
 * t1 (e_k in the tangent plane: the support carries that force, and the
 * row would be nearly empty); stick and slide act along t2 = n x t1 alone
 * (Coulomb's law in one dimension); with two such dofs the node keeps its
 * normal row only.  A dof moved (fixed < 0: a face pushed along the
 * contact plane) keeps its row. */
int ffc_nts_rows(const ffc_pair *pair, const ffc_nts_law *law, const double fixed[],
                 long nn, ffc_nts_node nodes[], long cap, long Bi[], long Bj[],
                 double Bv[], double Fv[], long ccap, double c[], long *ntrip, long *nrows);

/* After a solve: forces from the multipliers m[nrows] of the rows built
 * last, then the transitions (see above) with the geometry of the last
 * locate (call ffc_nts_locate at the new displacement first). */
int ffc_nts_update(const ffc_nts_law *law, long nrows, const double m[], long nn,
                   ffc_nts_node nodes[], ffc_nts_stats *st);

/* Number of rows the nodes' row and rmask fields describe (the size of the
 * multiplier vector of the last ffc_nts_rows). */
long ffc_nts_nrows(long nn, const ffc_nts_node nodes[]);

/* One row per node in the columns of ffc_points, P[nn*FFC_POINT_COLS]:
 * x, y, z at X + u (nv nodes), gap, pressure F_n / area (0 when open),
 * in contact, area, master facet, tangential traction on the slave
 * F_t / area (x, y, z), state FFC_NTS_*, dissipation density
 * |F_t . slip| / area.  Returns the nodes in contact; FFC_ERR_INDEX or
 * FFC_ERR_VALUE (area <= 0) with *bad = the node row at fault. */
int ffc_nts_points(long nv, const double X[], const double u[], long nn, const ffc_nts_node nodes[],
                   double P[], long *bad);

/* -------------------------------------- a scene's node-to-surface pairs */
/* Node-to-surface pairs (FFC_METHOD_NTS; a scene's pairs all use one
 * method).  Each such pair keeps the table of its slave nodes
 * (ffc_nts_node: state, partner facet, force), checkpointed by commit and
 * restored by restore like the multipliers of the other method; search,
 * assembly and augmentation pass over it.  In a step: ffc_scene_nts_step
 * (a new step: per-step flips, kept facets and forces cleared), then
 * repeat: ffc_scene_nts_rows (locate the nodes at u, the constraint rows
 * of every pair stacked: see ffc_nts_rows; rows of pair k follow those of
 * pairs < k, and a C-block column Bj >= 3 nv is shifted likewise), the
 * saddle-point solve, ffc_scene_nts_update (locate again, forces from the
 * multipliers m[nrows], transitions; *changes in all pairs), until no
 * node changes, the gaps close and Coulomb's law holds (statistics
 * "changes", "gapErr", "slideRes").  The node-to-surface law of a pair
 * takes nu_s = mu, and mu_d, gtol, ftol, max_flips, scale from its
 * options.  FFC_ERR_VALUE without a row scale (no option, no bulk);
 * FFC_ERR_CAPACITY with the sizes needed in *ntrip, *nrows. */
int ffc_scene_nts_step(ffc_scene *s);
int ffc_scene_nts_rows(ffc_scene *s, const double u[], const double fixed[], long cap, long Bi[], long Bj[],
                       double Bv[], double Fv[], long ccap, double c[], long *ntrip, long *nrows, long *bad);

/* The saddle-point solve of a node-to-surface step on the factored bulk
 * (ffc_scene_set_bulk): the rows at u (ffc_scene_nts_rows with fixed[n])
 * and [K Bf'; B Cm] [x; m] = [rhs; c] solved for x[n] and the
 * multipliers m[*nrows] (mcap: capacity of m).
 *
 * Formulation: with K factored once, x0 = K^-1 rhs (Dirichlet values
 * lifted as in ffc_scene_solve) and G the compliance of the free dofs C
 * the rows touch (columns kept with the other solves'), x = x0 - K^-1
 * Bf' m and the rows give the Schur complement system
 *     (Cm - B_C G Bf_C') m = c - B x0        (nr x nr, dense LU),
 * then x by one back-solve.  When K is singular and shifted (K + S, see
 * ffc_scene_solve), K^-1 does not exist: y = x_C and m solve the coupled
 *     [I - G S_C, G Bf_C'; B_C, Cm] [y; m] = [x0_C; c]
 * (order |C| + nr) and x = x0 + (K + S)^-1 (S_C y - Bf' m).  Up to two
 * steps of iterative refinement on the whole system's residual.
 * FFC_ERR_EMPTY without a bulk, FFC_ERR_CAPACITY when m is too small
 * (*nrows = the count needed) or C would hold more than the bulk's mmax
 * dofs (*bad = their count), FFC_ERR_SINGULAR when the system cannot be
 * factorized or its residual stays above 1e-6 relative; the errors of
 * ffc_scene_nts_rows. */
int ffc_scene_nts_solve(ffc_scene *s, const double u[], const double fixed[], const double rhs[], double x[],
                        long mcap, double m[], long *nrows, long *bad);
int ffc_scene_nts_update(ffc_scene *s, const double u[], long nrows, const double m[], long *changes, long *bad);

/* The contact residual of the node-to-surface pairs, which
 * ffc_scene_assemble leaves out (their forces come from multipliers):
 * added into R[nv*3] from the forces of the last ffc_scene_nts_update,
 * -f on each contact node and L_a f on the nodes of its master facet (f
 * the force on the slave node, L its foot's area coordinates), the sign
 * of ffc_scene_assemble's residual.  The supports' reactions of a
 * node-to-surface scene need it where a prescribed dof carries contact. */
int ffc_scene_nts_force(const ffc_scene *s, double R[]);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_NTS_H */
