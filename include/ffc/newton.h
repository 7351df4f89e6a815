/* ffc/newton.h: the Newton loops' line search, options, report and reasons to stop. */
#ifndef FFC_API_NEWTON_H
#define FFC_API_NEWTON_H

#include "status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------ line search */
/* The line search of every Newton loop (the condensed Newton here, the
 * scene driver's Newton in the script), by reverse communication: the
 * caller evaluates where it is told and reports.
 *
 * Formulation: along a direction d from u, g(a) = r(u + a d) . d (g(0) <
 * 0 for a descent direction).  Phase 1 (secant): the root of g on [0, a0]
 * by regula falsi (Illinois: a bound kept twice has its g halved), the
 * next point clamped to 5 % inside the bracket; a point is taken once
 * |g| <= ls_tol |g(0)|, or where g < 0 at the upper bound, or at a = 1
 * when the caller reports the full step taken (|r| at least halved with
 * the contact state unchanged: a tangent that is not symmetric can make
 * g(0) small against |r| |d|).  Phase 2 (guard): a step that makes |r|
 * more than ten times |r(u)| is halved.  Each phase takes at most max_ls
 * evaluations; a point the caller rejects (an inverted element) shortens
 * the step (phase 1: to the middle of the bracket, as its new upper
 * bound; phase 2: halved) and counts as an evaluation.  The point last
 * evaluated is not evaluated again. */
typedef struct {
    int max_ls;        /* evaluations per phase (>= 0) */
    double ls_tol;     /* phase 1's acceptance |g| <= ls_tol |g(0)| (0 < ls_tol < 1) */
    double g0, rn;     /* g(0) and |r(u)| */
    double a;          /* the point to evaluate, or the step taken at the end */
    double at;         /* the point last evaluated (-1: none) */
    double rt;         /* |r| there */
    double alo, glo, ahi, ghi; /* phase 1's bracket and g at its ends */
    int side;          /* the bound phase 1 moved last: -1 the lower, 1 the upper, 0 none */
    int phase;         /* 1 secant, 2 guard, 0 done */
    int guard;         /* 1: phase 2 follows phase 1 */
    int it;            /* evaluations in the present phase (count) */
    int waiting;       /* 1: a point was handed out and not yet reported */
    long cuts;         /* steps shortened (count) */
} ffc_linesearch;

/* Starts a search from a0 (the largest admissible step, <= 1) with g(0)
 * and |r(u)|; secant / guard: run phase 1 / phase 2.  FFC_ERR_VALUE for
 * max_ls < 0 or ls_tol outside (0, 1). */
int ffc_ls_start(ffc_linesearch *s, int max_ls, double ls_tol, double a0, double g0, double rn, int secant,
                 int guard);
/* 1: evaluate at *a, then ffc_ls_report (or ffc_ls_reject); 0: the search
 * is over, take the step *a. */
int ffc_ls_next(ffc_linesearch *s, double *a);
/* The evaluation at the point handed out: g there, |r| there, and (at
 * a = 1) whether the full step is taken on |r| alone. */
int ffc_ls_report(ffc_linesearch *s, double g, double rnorm, int full_taken);
/* The point handed out is not admissible (not evaluated). */
int ffc_ls_reject(ffc_linesearch *s);

/* --------------------------------------------------------- Newton loops */
/* The reasons a Newton loop stops, and the condensed Newton's options and
 * report (its formulation: ffc/solve.h, before ffc_scene_newton). */

/* the entries of ffc_newton_info.hist */
/* Why a load (or time) step of the scene driver stopped: solveScene()'s
 * status (the script's constants ffcStep...), which its augmentation loop
 * returns too. */
typedef enum {
    FFC_STEP_CONVERGED = 0,
    FFC_STEP_AUGMENT = 1,   /* the augmentations (node-to-surface: the active set) did not settle */
    FFC_STEP_NOPAIR = 5,    /* the scene has no contact pair */
    FFC_STEP_MATERIAL = 6,  /* a region without its material (or density, in time) */
    FFC_STEP_TIME = 7,      /* time steps asked of a scene that has none, or none of one that needs them */
    FFC_STEP_SETTINGS = 8,  /* settings that do not go together (a solver or a method the bulk cannot take) */
    FFC_STEP_SELF_PASSED = 9, /* points of a self-contact surface passed through it (ffc_scene_self_passed) */
    FFC_STEP_NEWTON = 10    /* plus an ffc_newton_reason: Newton stopped short */
} ffc_step_reason;
enum { FFC_NEWTON_HIST = 64 };
/* Why a Newton loop stopped: the condensed Newton's return value, and the
 * scene driver's Newton's (the same values in the script). */
typedef enum {
    FFC_NEWTON_CONVERGED = 0,  /* the residual met the tolerance */
    FFC_NEWTON_MAXIT = 1,      /* the iteration limit */
    FFC_NEWTON_NODESCENT = 2,  /* no direction that lowers the residual, or no admissible step along it */
    FFC_NEWTON_LINEAR = 3,     /* the linear solve failed (a singular or inaccurate system) */
    FFC_NEWTON_CAPACITY = 4    /* the condensed system would hold more contact dofs than allowed */
} ffc_newton_reason;
typedef struct {
    int max_iter;      /* Newton iterations at most (>= 1) */
    int max_ls;        /* line-search evaluations per iteration (>= 0; 0: full steps) */
    double ls_tol;     /* a step is taken once |g(s)| <= ls_tol |g(0)| (0 < ls_tol < 1) */
    double ftol;       /* converged when |rho| <= max(ftol, frel x the contact force
                          scale) (force), > 0 */
    double frel;       /* relative tolerance (1), >= 0; the scale is the largest
                          |Fx| + |Fy| + |Fz| of the total normal contact force met */
    int tangent;       /* FFC_TANGENT_CONSISTENT, FFC_TANGENT_MATERIAL or FFC_TANGENT_RANKED
                          (every pair on the nodal law; after two ranked iterations that did not
                          reduce the residual 10x, the call goes on with the consistent tangent) */
    long max_dofs;     /* contact dofs C may hold (count), >= 0; 0: the bulk's mmax */
    int min_iter;      /* iterations taken even when the start meets the tolerance (0 or 1; 1 after
                          an augmentation: multipliers that changed at a node of small weight move
                          the residual by less than the tolerance, and without a step the next
                          augmentation would repeat the same change) */
} ffc_newton_opts;

typedef struct {
    int iters;         /* Newton iterations (condensed linear solves) */
    int evals;         /* contact evaluations */
    int evals_shared;  /* of them, those whose links the ranks shared out (ffc_parallel.links) */
    double t_eval;     /* wall time of those evaluations (seconds) */
    int fallbacks;     /* directions taken from the material tangent */
    int switched;      /* 1: FFC_TANGENT_RANKED gave way to the consistent tangent (two ranked
                          iterations that did not reduce the residual 10x) */
    long m;            /* contact dofs of the condensed problem at the end (count) */
    long grown;        /* of them, those that joined during the call (count) */
    long support;      /* the largest dense system solved (count) */
    double res;        /* |rho| at the end (force) */
    int reason;        /* why it stopped (ffc_newton_reason) */
    int nhist;         /* entries of hist */
    double hist[FFC_NEWTON_HIST]; /* |rho| at each iteration's start, then the last (force) */
} ffc_newton_info;

/* Defaults: max_iter 25, max_ls 8, ls_tol 0.5, ftol 0 (must be set),
 * frel 0, consistent tangent, max_dofs 0, min_iter 0. */
ffc_newton_opts ffc_newton_defaults(void);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_NEWTON_H */
