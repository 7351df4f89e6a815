/* ffc/scene.h: contact scenes: pairs, options, bulk law, search, assembly, statistics, points, free motions. */
#ifndef FFC_API_SCENE_H
#define FFC_API_SCENE_H

#include "status.h"
#include "settings.h"
#include "geom.h"
#include "search.h"
#include "link.h"
#include "newton.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ----------------------------------------------------------------- scenes */
/* A contact scene: the nodes of one mesh (reference positions, and the
 * tetrahedra for the inversion check) and any number of contact pairs.
 * Each pair owns its slave and master facets, its search tree (built at
 * the first search, refitted at the next ones), its links, its
 * multipliers (never touched by another pair), their checkpoint at the
 * last commit, and its statistics.  The scene owns its memory; nothing is
 * global.  A pair with mu = 0 computes no friction term; the scene's
 * dynamic and finite_def effects apply to every pair. */
typedef struct ffc_scene ffc_scene;

enum {
    FFC_METHOD_AL = 0,          /* surface-to-surface augmented Lagrangian */
    FFC_METHOD_NTS = 1,         /* node-to-surface Lagrange multipliers (linear facets; see ffc_nts_*) */
    FFC_METHOD_MORTAR = 2       /* segment-to-segment augmented Lagrangian: the nodal law on the
                                   segment links (linear or 6-node facets, the multipliers at the
                                   vertices; qdeg is the rule on each segment triangle).
                                   ffc_scene_search chooses the facet pairs
                                   (ffc_mortar_pairs); every assembly and augmentation clips
                                   them again at its u (ffc_mortar_links), and the consistent
                                   tangent has the segments' motion (ffc_law.edge);
                                   ffc_scene_points reports the segments of the last of those */
};

/* A pair's method, law and search options. */
typedef struct {
    int method;        /* FFC_METHOD_* */
    int qdeg;          /* quadrature degree on slave facets (1..6) */
    int nodal;         /* 1: multipliers at slave nodes, 0: at quadrature points */
    double mu;         /* Coulomb coefficient (1), >= 0; 0: frictionless */
    double eps_n;      /* normal penalty (force/length^3), > 0; 0: not set yet (assembly and
                          augmentation refuse the scene until it is: ffc_scene_auto_penalty) */
    double eps_t;      /* tangential penalty (force/length^3; dynamic: force*time/length^3),
                          >= 0; 0: eps_n (dynamic: eps_n / dvdu, the same stiffness against the step's slip) */
    ffc_search_opts search; /* capture distances and edge tolerance */
    /* node-to-surface pairs (FFC_METHOD_NTS; the law's nu_s is mu) */
    double mu_d;       /* dynamic coefficient (1), 0 <= mu_d <= mu; < 0: mu */
    double gtol;       /* gap tolerance (length), >= 0; 0: 1e-11 x the pair's facet size */
    double ftol;       /* tension release below -ftol x the largest normal force (1), >= 0 */
    int max_flips;     /* state changes of a node per step before the chattering guard (>= 1) */
    double scale;      /* row scale (force/length), >= 0; 0: the mean free diagonal of the
                          scene's bulk matrix (ffc_scene_set_bulk) */
    /* mortar pairs (FFC_METHOD_MORTAR) */
    int dual;          /* 1: dual (biorthogonal) multipliers at the slave nodes, 0: standard */
    /* augmented Lagrangian pairs with the nodal law on linear facets */
    int dual_t;        /* 1: the friction sums in the dual basis (ffc_law.tdual), 0: in N_a;
                          1 elsewhere (another method, nodal 0, quadratic facets): FFC_ERR_VALUE
                          (FFC_ERR_NODES for quadratic facets) */
} ffc_pair_opts;

/* Defaults: augmented Lagrangian, qdeg 4, nodal, mu 0, eps_n 0 (must be
 * set), eps_t 0, ffc_search_defaults(); node-to-surface: mu_d -1 (mu),
 * gtol 0 (automatic), ftol 1e-9, max_flips 4, scale 0 (from the bulk);
 * mortar: dual 1; dual_t 0.  A mortar pair needs nodal = 1. */
ffc_pair_opts ffc_pair_defaults(void);

/* FFC_OK, or FFC_ERR_VALUE / FFC_ERR_QUAD for an option out of range. */
int ffc_pair_opts_check(const ffc_pair_opts *o);

/* A scene over nv nodes at reference positions X[nv*3], facets of nper
 * nodes (3 or 6), nt tetrahedra T[nt*4] (corner nodes; nt = 0: no
 * inversion check).  *out is NULL on error. */
int ffc_scene_create(int nper, long nv, const double X[], long nt, const long T[],
                     const ffc_effects *effects, ffc_scene **out);
void ffc_scene_free(ffc_scene *s);
/* The scene's driver settings (see "driver settings"; never NULL for a
 * scene): the script's driver reads and the user sets them by name. */
ffc_settings *ffc_scene_settings(ffc_scene *s);
/* The line search of the script driver's Newton loop, held by the scene
 * (ffc_ls_*, its settings maxLineSearch and lsTol). */
ffc_linesearch *ffc_scene_line_search(ffc_scene *s);

/* What the scene's bulk operator is: its law and what the law declares,
 * from which the driver chooses the solver path (a linear symmetric bulk:
 * factorized once, the contact condensed; otherwise the whole tangent at
 * every Newton iteration) and the contact kernels their geometry. */
typedef enum {
    FFC_BULK_LINEAR = 0,      /* linear elasticity (small strain) */
    FFC_BULK_NEOHOOKEAN = 1,  /* compressible Neo-Hookean (finite deformation, total Lagrangian) */
    FFC_BULK_USER = 2,        /* the scene's own residual and tangent */
    FFC_BULK_SVK = 3,         /* Saint Venant-Kirchhoff (finite deformation, total Lagrangian) */
    FFC_BULK_MOONEYRIVLIN = 4 /* compressible Mooney-Rivlin (finite deformation, total Lagrangian) */
} ffc_bulk_kind;
typedef struct {
    ffc_bulk_kind kind;
    int linear;        /* 1: the internal force is linear in u (its tangent constant) */
    int symmetric;     /* 1: the tangent is symmetric */
    int finite;        /* 1: finite deformation: contact geometry in the current configuration
                          (ffc_effects.finite_def) */
} ffc_bulk_law;
/* what a built-in law declares (FFC_BULK_USER: nonlinear, symmetric, small strain, until the scene says) */
ffc_bulk_law ffc_bulk_law_of(ffc_bulk_kind kind);
/* Sets the scene's bulk law (and its effects' finite_def).  FFC_ERR_VALUE
 * for an unknown kind, a flag other than 0 or 1, a linear finite law, or a
 * built-in law declared otherwise than it is. */
int ffc_scene_set_law(ffc_scene *s, const ffc_bulk_law *law);
int ffc_scene_law(const ffc_scene *s, ffc_bulk_law *law);
int ffc_scene_npairs(const ffc_scene *s);
int ffc_scene_effects(const ffc_scene *s, ffc_effects *fx);

/* Adds the pair of slave facets Fs[nfs*nper] and master facets
 * Fm[nfm*nper] (node indices; outward orientation) with options o;
 * returns its index (>= 0) or an error (FFC_ERR_INDEX: *bad = the facet
 * entry at fault; FFC_ERR_FUSED: *bad = a slave facet whose vertices are
 * all master nodes, the bodies being meshed as one; FFC_ERR_INTERIOR: *bad
 * = a facet that two of the scene's tetrahedra share, so that the bodies
 * on its two sides are one mesh there: a slave facet f as f, a master
 * facet f as nfs + f).  Self-contact (o->search.self = 1): Fs and Fm are
 * the same facets and the method the augmented Lagrangian or mortar
 * (FFC_ERR_VALUE for node-to-surface); each point's own facet, the facets sharing a vertex with it
 * and those not facing it are no partners (ffc_search_opts). */
int ffc_scene_add_pair(ffc_scene *s, long nfs, const long Fs[], long nfm, const long Fm[],
                       const ffc_pair_opts *o, long *bad);

/* Adds a pair of slave facets Fs[nfs*nper] on the rigid obstacle ob
 * (ffc/obstacle.h; ob->d is ignored: the scene keeps the obstacle's motion
 * from its placements) with options o (the augmented Lagrangian, self 0:
 * FFC_ERR_VALUE otherwise); returns its index or an error as
 * ffc_scene_add_pair.  The pair has no master facets (ffc_scene_nfacets
 * 0) and its links only slave unknowns; capture_rel counts in the slave
 * facet's size. */
int ffc_scene_add_obstacle(ffc_scene *s, long nfs, const long Fs[], const ffc_obstacle *ob, const ffc_pair_opts *o,
                           long *bad);
/* Places obstacle pair k's obstacle (the same kind; ob->d ignored) at
 * load factor 0, and its path: at load factor lf
 * (ffc_scene_obstacles_at) its centre (point) is ob->c + lf move[3]
 * (move NULL: it stays).  Its motion since the last commit
 * (ffc_scene_commit) is c - c at the commit, divided by dt in a dynamic
 * scene: the velocity its surface has for friction (a translation: a turn
 * of the shape gives its surface no velocity).  FFC_ERR_VALUE for a pair
 * without an obstacle or another kind; ffc_obstacle_check's errors.
 * ffc_scene_obstacle reads the placement back, with the motion in d. */
int ffc_scene_set_obstacle(ffc_scene *s, int k, const ffc_obstacle *ob, const double move[3]);
int ffc_scene_obstacles_at(ffc_scene *s, double lf);
int ffc_scene_obstacle(const ffc_scene *s, int k, ffc_obstacle *ob);
/* Obstacle pair k's path: move[3] (length), as ffc_scene_set_obstacle set it. */
int ffc_scene_obstacle_path(const ffc_scene *s, int k, double move[3]);

/* Self pairs (search.self): the slave points that crossed an opposite
 * facet of their own surface since the last commit, in one step: a point
 * behind a facet at u by more than the pair's capture distance (which
 * the search does not see: the contact cannot push it back) that was on
 * the facet's open side at the commit.  *n their count (0: none, or no
 * self pair); a step with *n > 0 passed a fold through itself and is to be
 * cut. */
int ffc_scene_self_passed(ffc_scene *s, const double u[], long *n, long *bad);

/* Options of pair k, and their change (a new qdeg or nodal setting
 * resets that pair's links and multipliers). */
int ffc_scene_pair_opts(const ffc_scene *s, int k, ffc_pair_opts *o);
int ffc_scene_set_pair_opts(ffc_scene *s, int k, const ffc_pair_opts *o);

/* Dynamic scenes: the velocities v[nv*3] at the end of the step, the
 * step dt and the integrator's dv/du, read by the friction terms. */
int ffc_scene_set_motion(ffc_scene *s, const double v[], double dt, double dvdu);

/* The prescribed dofs of the scene's nodes: fixed[nv*3] nonzero where a
 * dof is prescribed (Dirichlet), > 0 where it is held at zero (a symmetry
 * plane's), < 0 where it is moved; copied; NULL clears them.  Read by the
 * nodal friction law (ffc_law.fixed: a direction held at zero in a slave
 * node's contact plane is dropped from its return map) and by the free
 * rigid motions (ffc_scene_free_motions: any nonzero entry). */
int ffc_scene_set_fixed(ffc_scene *s, const double fixed[]);

/* Contact search of every pair at x = X + u[nv*3]; *linked (may be NULL)
 * the number of linked points.  On error *bad is the pair (or the node
 * with a non-finite position). */
int ffc_scene_search(ffc_scene *s, const double u[], long *linked, long *bad);

/* Adds the contact residual of every pair at u into R[nv*3] and, unless
 * tangent is FFC_TANGENT_NONE, writes the tangent as triplets (Ti, Tj,
 * Tv)[cap]; *ntrip the triplets written, or needed with FFC_ERR_CAPACITY
 * (R is then incomplete: call again with room).  FFC_TANGENT_RANKED
 * numbers the terms over all pairs (a pair's after the pairs before it);
 * FFC_ERR_VALUE (*bad = the pair) for an augmented Lagrangian pair with
 * multipliers at quadrature points. */
int ffc_scene_assemble(ffc_scene *s, const double u[], int tangent, double R[], long cap, long Ti[], long Tj[],
                       double Tv[], long *ntrip, long *bad);

/* Uzawa update of every pair's multipliers at u (see ffc_augment). */
int ffc_scene_augment(ffc_scene *s, const double u[], long *bad);

/* A converged step: u becomes the friction history and the multipliers
 * are checkpointed.  restore: back to the checkpoint (a step cut).
 * reset: zero history, velocities, multipliers, links. */
int ffc_scene_commit(ffc_scene *s, const double u[]);
int ffc_scene_restore(ffc_scene *s);
int ffc_scene_reset(ffc_scene *s);

/* Statistic `name` of pair k (k = -1: all pairs, summed or the largest)
 * from the last assembly (maxDlam, maxDlamT, maxPenNode: the last
 * augmentation), or with step != 0 as they were at the last commit (the
 * converged step: its slip and friction states, which an assembly after
 * the commit no longer sees).  FFC_ERR_LABEL for a name that is not a
 * statistic; ffc_scene_stat_name(i) lists them (NULL past the last). */
int ffc_scene_stat(const ffc_scene *s, int pair, const char *name, int step, double *value);
const char *ffc_scene_stat_name(int i);

/* Links of pair k (k = -1: all pairs). */
long ffc_scene_nlinks(const ffc_scene *s, int pair);

/* ffc_points rows of pair k (k = -1: every pair in order) into
 * P[cap*FFC_POINT_COLS]; *n the rows (needed, with FFC_ERR_CAPACITY).
 * Mortar pairs give the rows of ffc_points_nodes, one per slave node,
 * node-to-surface pairs one per slave node too; with nodes = 1 nodal
 * augmented Lagrangian pairs give ffc_points_nodes' rows as well (every
 * method's values on the slave nodes; FFC_ERR_VALUE for a pair with
 * pointwise multipliers). ffc_scene_npoints: the number of rows. */
long ffc_scene_npoints(const ffc_scene *s, int pair, int nodes);
int ffc_scene_points(const ffc_scene *s, const double u[], int pair, int nodes, long cap, double P[], long *n,
                     long *bad);

/* Copies of pair k's multipliers lam[nlam] and lam_t[3 nlam] (either may
 * be NULL); *n = nlam (nodes for the nodal law, links otherwise). */
int ffc_scene_multipliers(const ffc_scene *s, int pair, long cap, double lam[], double lam_t[], long *n);

/* The contact mesh size of pair k (k = -1: all pairs): the smaller of
 * the mean longest facet edge of its slave and of its master surface, in
 * the reference configuration (length); FFC_ERR_EMPTY without pairs. */
int ffc_scene_facet_size(const ffc_scene *s, int pair, double *h);

/* Plane-strain modulus E' = E / (1 - nu^2) = 4 mu (lambda + mu) / (lambda + 2 mu)
 * from Lame's constants (force/length^2). */
double ffc_plane_modulus(double lame1, double lame2);

/* Automatic penalty of pair k from the plane-strain modulus of the body
 * behind each facet, Ep_s[nfs] and Ep_m[nfm] (in the pair's facet order):
 *     eps_N = 200 / (1 / k_s + 1 / k_m),   k = mean over a side's facets of E' / h,
 * h the facet's longest edge.  k is the stiffness of one element layer
 * under that side; the two layers act in series.  For equal bodies and
 * facets this is 100 E' / h: before augmentation a pressure p penetrates by
 * p h / (100 E'), a hundredth of one layer's compliance, the value that
 * needed the fewest Newton iterations on the patch and Hertz cases (10x
 * smaller: 2-3x more augmentations; 10x larger: Newton fails on Hertz).
 * A soft body against a stiff one gets about 200 times the soft layer's
 * stiffness: the penetration stays a small part of the soft side's
 * deformation.  FFC_ERR_VALUE for a modulus that is not positive. */
/* An obstacle pair: the obstacle is rigid (k_m infinite: 200 k_s) and Ep_m
 * may be NULL. */
int ffc_scene_auto_penalty(const ffc_scene *s, int pair, const double Ep_s[], const double Ep_m[], double *eps);

/* Facets of pair k's slave (master = 0) or master side. */
long ffc_scene_nfacets(const ffc_scene *s, int pair, int master);

/* A rigid motion of one body: a translation (w = 0: t the unit direction,
 * p the body's centroid) or a turn about the axis through p along the unit
 * w, with the slide t along it per radian (0 for a pure rotation).
 * Translations and axes lie along the coordinate axes where the free
 * motions allow. */
typedef struct {
    long body;   /* the body's lowest node index */
    long tet;    /* the body's first tetrahedron (index into T) */
    double x[3]; /* that node's reference position (length) */
    double t[3]; /* translation direction (unit), or slide per radian along the axis (length) */
    double w[3]; /* unit axis of the turn; 0 for a translation */
    double p[3]; /* a point of the axis: the one nearest the body's centroid (length) */
    double amount; /* how far u moved the body along it (least squares over the body's nodes): a turn's
                      angle about w (radians), a translation's length along t at the centroid; 0 without u */
} ffc_motion;
/* The columns of a motion's row in the plugin's ffcFreeMotions (its
 * constants ffcMoBody ... ffcMoTet): t, w, p, x three each. */
enum {
    FFC_MO_BODY = 0, FFC_MO_T = 1, FFC_MO_W = 4, FFC_MO_P = 7, FFC_MO_X = 10, FFC_MO_AMOUNT = 13, FFC_MO_TET = 14,
    FFC_MOTION_COLS = 15
};

/* The rigid motions of each body that the prescribed dofs leave free: the
 * bodies are the tetrahedra T[nt*4] joined by shared nodes (nodes in no
 * tetrahedron are left out), fixed[nv*3] nonzero on a prescribed dof (NULL:
 * none).  Per body a basis of its free motions, translations first, each
 * with its amount in the displacement u[nv*3] (NULL: none); *n the count
 * over all bodies, FFC_ERR_CAPACITY (with *n) when it exceeds cap. */
int ffc_rigid_free(long nv, const double X[], long nt, const long T[], const double fixed[], const double u[],
                   long cap, ffc_motion out[], long *n);

/* ffc_rigid_free on the scene's tetrahedra and its prescribed dofs
 * (ffc_scene_set_fixed; none given: every rigid motion is free), amounts
 * in u (NULL: none); FFC_ERR_EMPTY for a scene made without tetrahedra. */
int ffc_scene_free_motions(const ffc_scene *s, const double u[], long cap, ffc_motion out[], long *n);

/* ffc_volume_check of the scene's tetrahedra at X + u. */
int ffc_scene_check_volume(const ffc_scene *s, const double u[], long *bad);

/* mask[n] (n = 3 nv): 1 on the three dofs of every node of a slave or a
 * master facet of any pair, 0 elsewhere.  Returns the number of such
 * nodes, or a negative status (FFC_ERR_SIZE for n != 3 nv). */
long ffc_scene_surface_mask(const ffc_scene *s, long n, double mask[]);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_SCENE_H */
