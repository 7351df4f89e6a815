/* ffc/link.h: contact links: a pair's nodes, the contact law, normal and frictional links, assembly, output. */
#ifndef FFC_API_LINK_H
#define FFC_API_LINK_H

#include "status.h"
#include "geom.h"
#include "search.h"
#include "mortar.h"
#include "obstacle.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------ normal contact links */
/* Augmented-Lagrangian normal contact (after Laursen; the seed's
 * ContactLink3D).  Sign convention: gap g = n2 . (x1 - x2) >= 0 when open;
 * contact pressure t_N = <lambda_N - eps_N g> (Macaulay bracket), >= 0.
 * The seed writes g_seed = -g, t_N = <lambda_N + eps_N g_seed>: the same. */

/* State of one link after an evaluation. */
typedef struct {
    double x[3];       /* slave point, current configuration (length) */
    double xi[2];      /* master foot on the facet's extension (1) */
    double n[3];       /* unit master normal at the foot (1) */
    double gap;        /* g (length) */
    double tn;         /* contact pressure t_N (force/length^2) */
    double da;         /* w * area element: the point's area (length^2) */
    int active;        /* 1 when lambda_N - eps_N g > 0 */
    double slip[3];    /* friction: relative motion r of the slave point over
                          the master since the last converged step (length) */
    double t[3];       /* friction: tangential traction T resisting the slip;
                          the slave is pushed by -T (force/length^2) */
    int fstate;        /* friction: FFC_FRIC_OPEN, _STICK or _SLIP */
} ffc_link_state;

/* Residual and tangent of one link: slave facet Xs[ns][3] (current
 * positions), its reference positions Xs0[ns][3] (area element when
 * effects->finite_def == 0), slave point xs with quadrature weight w,
 * master facet Xm[nm][3] (current); multiplier lambda (force/length^2),
 * penalty eps (force/length^3, > 0).  Unknowns: [slave nodes, master
 * nodes] x (x, y, z), nd = 3 (ns + nm).
 * Outputs: st; R[nd] the contribution to the internal-force residual;
 * K[nd][nd] (row stride FFC_MAXDOF) its derivative, or K == NULL for the
 * residual only.  An inactive link gives R = 0, K = 0. */
int ffc_link_normal(const ffc_effects *effects, int ns, const double Xs[][3],
                    const double Xs0[][3], const double xs[2], double w,
                    int nm, const double Xm[][3], double lambda, double eps,
                    ffc_link_state *st, double R[FFC_MAXDOF],
                    double K[FFC_MAXDOF][FFC_MAXDOF]);

/* The nodes of one contact pair: slave and master facets into a common
 * node numbering; node i has reference position X[3i..3i+2] and
 * displacement u[3i..3i+2]; its degrees of freedom are 3i, 3i+1, 3i+2. */
typedef struct {
    int ns;            /* nodes per slave facet (3 or 6) */
    long nfs;          /* slave facets */
    const long *Fs;    /* [nfs*ns] slave facet nodes */
    int nm;            /* nodes per master facet (3 or 6) */
    long nfm;          /* master facets */
    const long *Fm;    /* [nfm*nm] master facet nodes */
    long nv;           /* nodes */
    const double *X;   /* [nv*3] reference positions (length) */
    const double *u;   /* [nv*3] displacements (length) */
    const double *u_prev; /* [nv*3] displacements at the last converged step
                          (length); read only when friction is on in a
                          quasi-static scene */
    const double *v;   /* [nv*3] velocities at the end of the step (length/time);
                          read only when friction is on in a dynamic scene
                          (effects->dynamic), in place of u_prev */
    const ffc_obstacle *obst; /* NULL: the master is the facets Fm; else a rigid
                          obstacle (ffc/obstacle.h): nm = 0, Fm and nfm unused,
                          a linked link has mf = 0 and only slave unknowns */
} ffc_pair;

/* The form of a contact tangent: what a scene's assembly writes, a law's
 * tangent, the condensed Newton's choice (one coding everywhere). */
enum {
    FFC_TANGENT_NONE = 0,       /* residual only */
    FFC_TANGENT_CONSISTENT = 1, /* exact derivative of the residual */
    FFC_TANGENT_MATERIAL = 2,   /* without the geometric terms (the variation of the normal, the foot and
                                   the area): positive semi-definite, for a descent direction when the
                                   consistent tangent is indefinite */
    FFC_TANGENT_RANKED = 3      /* the material tangent of the nodal law as a sum of low-rank terms,
                                   one to four per slave node: K = sum_k U_k V_k^T, written as
                                   triplets (dof, 2 k, U_k[dof]) and (dof, 2 k + 1, V_k[dof]); the
                                   condensed Newton then solves a system of the terms' count
                                   (Woodbury) instead of one of the tangent's support */
};

/* The contact law and where its multipliers live. */
typedef struct {
    double eps_n;      /* penalty (force/length^3), > 0 */
    int nodal;         /* 1: one multiplier per slave node, lambda[nv]; the
                          pressure at a point uses the interpolated
                          multiplier, and the Uzawa update drives the
                          weighted nodal gap  int N_a g dA / int N_a dA  to
                          zero (one constraint per node: well posed).
                          0: one multiplier per slave quadrature point,
                          lambda[nl], updated pointwise as in the seed (more
                          constraints than contact unknowns: the multipliers
                          may drift and Uzawa may stall) */
    int tangent;       /* the tangent's form: FFC_TANGENT_CONSISTENT (0 counts as it),
                          FFC_TANGENT_MATERIAL, or FFC_TANGENT_RANKED (the material
                          tangent in ranked form; the nodal law only) */
    double mu;         /* Coulomb coefficient (1), >= 0; read only when
                          effects->friction (mu = 0 then skips all friction work) */
    double eps_t;      /* tangential penalty, > 0 when friction: force/length^3
                          (quasi-static: T_tr = lambda_T + eps_t r), or
                          force*time/length^3 (dynamic: T_tr = lambda_T + eps_t v_rel) */
    double dt;         /* time step (time), > 0 when friction is on in a dynamic
                          scene: the slip reported over the step is dt v_rel */
    double dvdu;       /* dynamic friction: the time integrator's d v / d u at the
                          end of the step (1/time, e.g. gamma / (beta dt) for
                          Newmark), >= 0.  The tangent is K + dvdu D with
                          D = dR/dv the damping matrix; 0 gives K alone */
    const double *fixed; /* [3*nv] or NULL: nonzero where a node's dof is
                          prescribed (Dirichlet): > 0 held at zero (as on a
                          symmetry plane), < 0 moved.  Nodal friction drops a
                          direction e_k held at zero of a slave node that lies
                          in the contact plane (|n~_k| < 0.9, as node-to-surface
                          does): the k components of the node's weighted slip
                          and weighted normal are zeroed before its return
                          map (on a symmetry plane the mirror half's
                          contributions cancel them).  A moved direction (a
                          face pushed along the contact plane) keeps its
                          friction, which the support's reaction carries */
    const double *dual; /* [9 nfs] or NULL: nodal law with dual multipliers (on
                          6-node facets too: N_b the vertex triangle's linear
                          shape functions), Phi_a = sum_b A_ab N_b on slave facet f
                          with A = dual + 9 f (row-major, ffc_dual_basis) in place
                          of N_a, in the weighted gap, the pressure and the
                          friction sums alike; NULL: standard N_a */
    long nedge;        /* segment links (qdeg 0): the moving-edge points of their segments,
                          edge[nedge] (ffc_mortar_links), whose motion enters the tangent;
                          0: the tangent at fixed segments */
    const ffc_mortar_edge *edge;
    int tdual;         /* 1: the nodal law's friction sums (the weighted slip and
                          normal, the point traction) use the dual basis of a full
                          linear facet, Phi_a = 4 N_a - 1, so that a node's weighted
                          slip is its own, not an average with its neighbours';
                          needs dual NULL, nedge 0 and linear slave facets (else
                          ignored); the weighted gap and the pressure keep N_a.
                          0: the friction sums use the normal part's shape values */
    const unsigned char *lsel; /* [nl] or NULL (every link): the nodal law's residual,
                          statistics and ranked tangent (FFC_TANGENT_NONE or
                          FFC_TANGENT_RANKED; not with dual, nedge or another
                          tangent: FFC_ERR_VALUE) from the links k with lsel[k]
                          != 0 only, a share of them: the shares' sums are the
                          whole's, with nsum completing the node sums */
    int (*nsum)(void *ctx, int st, long n, double buf[]);
                       /* with lsel: called once per assembly, on every path, with
                          this share's status st and its partial node sums buf[n]
                          (8 per node of the linked links' slave facets, ascending
                          node index:
                          G_a, W_a, the weighted slip's and normal's sums); it
                          replaces buf by the sums over every share and returns
                          their combined status (FFC_OK only when every share's
                          st is; buf may be NULL when st is not FFC_OK) */
    void *nsum_ctx;    /* nsum's first argument */
} ffc_law;

/* ------------------------------------------------------ Coulomb friction */
/* Formulation.  Two forms of the same law, chosen by effects->dynamic.
 * Quasi-static (incremental): the slip r is the relative motion of the
 * slave point over the master material point under it since the last
 * converged step,
 *     r = sum_a N1_a (x_a - x_a^n) - sum_b N2_b(xi) (x_b - x_b^n).
 * Dynamic (the seed's velocity form): the relative velocity
 *     r = v_rel = sum_a N1_a v_a - sum_b N2_b(xi) v_b
 * takes its place, with eps_T in force*time/length^3.  With the
 * tangential multiplier lambda_T (a 3-vector in the tangent plane), the
 * trial traction is
 *     T_tr = P (lambda_T + eps_T r),   P = I - n n^T,
 * whose Euclidean norm equals the metric norm sqrt(t_a m^ab t_b) of its
 * covariant components.  Return map: stick when |T_tr| < mu t_N (T =
 * T_tr), slip otherwise (T = mu t_N T_tr / |T_tr|), with the current
 * t_N so that the slip bound is linearized with it.  T resists the slip:
 * the slave is pushed by -T, the master by +T.
 * The two forms agree when the velocity is the backward difference
 * v = (x - x^n) / dt and eps_T(dynamic) = eps_T(quasi-static) dt.  In the
 * velocity form the derivative of the residual splits into a stiffness
 * K = dR/du at fixed velocities (the foot slides, the normal turns) and
 * the damping matrix D = dR/dv; with the integrator's v(u) the tangent
 * is K + (dv/du) D (law->dvdu). */
enum { FFC_FRIC_OPEN = 0, FFC_FRIC_STICK = 1, FFC_FRIC_SLIP = 2 };

/* Result of the return map at one point. */
typedef struct {
    double t[3];        /* traction T (force/length^2) */
    double dt_dr[3][3]; /* dT/dr (force/length^3) */
    double dt_dn[3][3]; /* dT/dn (force/length^2) */
    double dt_dtn[3];   /* dT/dt_N (1) */
    int state;          /* FFC_FRIC_* (OPEN when t_N <= 0: T = 0) */
} ffc_fric;

/* Return map at one point: unit normal n[3], multiplier lam_t[3], slip
 * r[3], mu >= 0, eps_t > 0, pressure tn.  No division by zero: t_N = 0
 * gives OPEN, and |T_tr| = 0 with mu t_N = 0 gives T = 0.
 * FFC_ERR_NULL, FFC_ERR_VALUE (mu, eps_t), FFC_ERR_NONFINITE. */
int ffc_friction_map(const double n[3], const double lam_t[3], const double r[3],
                     double mu, double eps_t, double tn, ffc_fric *out);

/* Residual and tangent of one link with the law's friction: as
 * ffc_link_normal with, when effects->friction and law->mu > 0, the
 * motion of the nodes Ds[ns][3], Dm[nm][3] (quasi-static: x - x^n since
 * the last converged step; dynamic: the velocities) and the multiplier
 * lam_t[3].  Friction residual da S^T T with S = dr/dD at fixed foot;
 * its tangent includes the slip of the foot, the turning of the normal
 * and the pressure's variation (non-symmetric); dynamic: K + law->dvdu D.
 * st->slip is r (quasi-static) or law->dt r (dynamic). */
int ffc_link_contact(const ffc_effects *effects, int ns, const double Xs[][3],
                     const double Xs0[][3], const double Ds[][3], const double xs[2],
                     double w, int nm, const double Xm[][3], const double Dm[][3],
                     double lambda, const double lam_t[3], const ffc_law *law,
                     ffc_link_state *st, double R[FFC_MAXDOF],
                     double K[FFC_MAXDOF][FFC_MAXDOF]);

/* The same against a rigid obstacle (ffc/obstacle.h) as the master:
 * unknowns the slave nodes only, nd = 3 ns; the gap, normal and its
 * curvature exact; friction against the obstacle's motion ob->d.
 * FFC_ERR_DEGENERATE where the obstacle has no normal (ffc_obstacle_gap). */
int ffc_link_obstacle(const ffc_effects *effects, int ns, const double Xs[][3], const double Xs0[][3],
                      const double Ds[][3], const double xs[2], double w, const ffc_obstacle *ob, double lambda,
                      const double lam_t[3], const ffc_law *law, ffc_link_state *st, double R[FFC_MAXDOF],
                      double K[FFC_MAXDOF][FFC_MAXDOF]);

/* Summary of an assembly or augmentation. */
typedef struct {
    long linked;       /* links with a master partner */
    long active;       /* links with t_N > 0 */
    double max_pen;    /* largest penetration max(0, -g) over linked points (length) */
    double max_pen_node; /* largest weighted nodal penetration (nodal law, augmentation) */
    double max_dlam;   /* largest |lambda_new - lambda| (augmentation only) */
    double max_tn;     /* largest contact pressure */
    double force[3];   /* total normal contact force on the slave side (force) */
    long stick, slip;  /* friction: sticking, sliding links (pointwise law) or
                          slave nodes (nodal law) */
    double max_dlam_t; /* friction: largest |lambda_T,new - lambda_T| (augmentation) */
    double max_tt;     /* friction: largest tangential traction |T| */
    double force_t[3]; /* friction: total friction force on the slave side (force) */
    double dissipation; /* friction: sum over points of da T . r, the work
                          dissipated by slip since the last converged step (force*length) */
    double max_slip;   /* friction: largest tangential slip |r_T| of a pressed point (pointwise
                          law) or slave node (nodal law, weighted slip) since the last converged
                          step (length; dynamic: dt |v_rel,T|) */
} ffc_stats;

/* Adds the contact residual of all links into R[3nv] and writes the
 * tangent as triplets (Ti, Tj, Tv)[cap] (NULL: residual only).  lambda:
 * [nv] per node or [nl] per link, as law->nodal says; lam_t the
 * tangential multipliers, 3 per node [nv*3] or per link [nl*3] likewise
 * (read only with friction on and law->mu > 0, NULL allowed otherwise;
 * the tangent is then non-symmetric).  The nodal law applies the return
 * map at the nodes to the weighted slip (see ffc_nodal.c).
 * *ntrip is the number of triplets written, or the number needed when
 * FFC_ERR_CAPACITY is returned (R is then incomplete).
 * On error *bad is the link at fault. */
int ffc_assemble(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
                 long nl, const ffc_link links[], const double lambda[],
                 const double lam_t[], const ffc_law *law, double R[], long cap, long Ti[], long Tj[],
                 double Tv[], long *ntrip, ffc_stats *stats, long *bad);

/* Uzawa update: pointwise lambda_q <- <lambda_q - eps g_q> (0 without a
 * partner), or nodal lambda_a <- <lambda_a - eps g_a> with the weighted
 * gap g_a = sum_q N_a da g / sum_q N_a da over linked points (0 at slave
 * nodes without linked points; the entries of nodes that are not slave
 * nodes of this pair are left as they are, so pairs may share lambda);
 * stats->max_dlam measures the change.  With
 * friction, lam_t <- T of each node or link (0 where t_N = 0), evaluated
 * with the pressures before the normal update; stats->max_dlam_t. */
int ffc_augment(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
                long nl, const ffc_link links[], double lambda[], double lam_t[],
                const ffc_law *law, ffc_stats *stats, long *bad);

/* Per-link output P[nl*FFC_POINT_COLS], its columns by name (the plugin's
 * constants ffcPtX ... ffcPtDiss): the current slave point, gap, t_N,
 * active, area da, master facet; with friction (zeros without) the
 * traction on the slave -T, the friction state FFC_FRIC_*, and the
 * dissipation density T . r (force/length). */
enum {
    FFC_PT_X = 0, FFC_PT_Y = 1, FFC_PT_Z = 2, /* the slave point (length) */
    FFC_PT_GAP = 3,                           /* gap, >= 0 open (length) */
    FFC_PT_P = 4,                             /* pressure t_N (force/length^2) */
    FFC_PT_ACTIVE = 5,                        /* 1 in contact, 0 open */
    FFC_PT_AREA = 6,                          /* weight or tributary area (length^2) */
    FFC_PT_FACET = 7,                         /* the master facet (-1: none) */
    FFC_PT_TX = 8, FFC_PT_TY = 9, FFC_PT_TZ = 10, /* friction traction on the slave (force/length^2) */
    FFC_PT_STATE = 11,                        /* friction state: 0 open, 1 stick, 2 slip */
    FFC_PT_DISS = 12,                         /* dissipation density (force/length) */
    FFC_POINT_COLS = 13
};
int ffc_points(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
               long nl, const ffc_link links[], const double lambda[],
               const double lam_t[], const ffc_law *law, double P[], long *bad);

/* The same columns per slave node of the nodal law (ascending node index,
 * every vertex of a slave facet: the multipliers' nodes, also of 6-node
 * facets): current position, weighted gap (NaN
 * without weight), nodal pressure t_a, active (t_a > 0), the node's
 * weight W_a = sum_q N_a da (its tributary area), the master facet of its
 * first link (-1: none); with friction the nodal traction on the slave
 * -T_a, its state and T_a . r~_a (the weighted slip).  *n the rows
 * (needed, with FFC_ERR_CAPACITY when cap is smaller); FFC_ERR_VALUE for
 * the pointwise law.  Mortar scenes report these (the dual multipliers'
 * pointwise values are no pressures). */
int ffc_points_nodes(const ffc_effects *effects, const ffc_pair *pair, int qdeg, long nl, const ffc_link links[],
                     const double lambda[], const double lam_t[], const ffc_law *law, long cap, double P[], long *n,
                     long *bad);

/* Writes the rows of ffc_points (n points) as a legacy-VTK point cloud
 * with scalar fields gap, pressure, status (0 open, 1 stick, 2 slip or
 * frictionless contact), dissipation and the vector friction_traction;
 * FFC_ERR_VALUE if the file cannot be written. */
int ffc_points_vtk(const char *path, long n, const double P[]);

/* Writes the rows k of the column-major table A[ncol*n] (column j holds
 * A[j*n .. j*n + n-1]) whose mask[k] is non-zero (mask NULL: all rows) as
 * whitespace-separated text, after a header line "# " + header;
 * FFC_ERR_VALUE if the file cannot be written. */
int ffc_write_columns(const char *path, const char *header, long n, int ncol,
                      const double A[], const double mask[]);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_LINK_H */
