/* ffc/solve.h: a scene's bulk factorization, engines, parallel and full solvers, the condensed solve and Newton. */
#ifndef FFC_API_SOLVE_H
#define FFC_API_SOLVE_H

#include "status.h"
#include "newton.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --------------------------------------------------- bulk factorization */
/* Bulk factorization of a small-strain scene.  The scene keeps the bulk
 * stiffness K (n = 3 nv dofs, node-major: dof 3 i + c is component c of
 * node i; symmetric positive definite once the Dirichlet rows carry a
 * large diagonal, FreeFEM's tgv) and solves each Newton system
 * (K + Kc) x = b on the contact dofs (the contact-reduced solve below):
 * K + S is factorized (CHOLMOD) at the first solve, S = s I on the dofs of
 * that first contact tangent (s the mean diagonal of the rows that are not
 * Dirichlet rows: a body that only contact holds makes K singular); the
 * compliance G of the contact dofs grows by block solves (pruned to
 * the rows read) when Kc touches new dofs; each solve is two back-solves and a dense LU of
 * I + G Kcc (m x m, LAPACK), then at most two steps of iterative
 * refinement.  Dirichlet rows are those whose diagonal is at least 1e12
 * times the median diagonal: their value is b_i / K_ii (the tgv rows'
 * solution to within 1/tgv) and they are eliminated before the
 * factorization, so that CHOLMOD's condition estimate shows a singular K
 * (below 1e-12: refused). */
typedef struct {
    long factorizations; /* of K + S (count) */
    long columns;        /* compliance columns computed (count) */
    long solves;         /* ffc_scene_solve calls (count) */
    long backsolves;     /* right-hand sides solved with the factor (count) */
    long refinements;    /* iterative-refinement steps (count) */
    long kept;           /* condensed Newton directions solved by GMRES preconditioned with the last dense LU
                            of the same support (count) */
    long m;              /* contact dofs in the compliance (count) */
    double shift;        /* s (force/length; 0: no shift) */
    long shifted;        /* dofs that carry the shift (count; 0: none) */
    double rcond;        /* CHOLMOD's estimate of the factor's reciprocal condition (1; 0 with MUMPS,
                            which refuses negative pivots and those below 1e-12 of K's norm instead) */
    int ranks;           /* the ranks that share the factorization (1: CHOLMOD) */
    double factor_mb;    /* MUMPS: this rank's factorization memory (MB; 0 with CHOLMOD) */
    double factor_mb_max; /* MUMPS: the largest rank's (MB) */
    double residual;     /* last solve: the free rows' residual / (|b_free| + max free
                            diagonal |x_free|), or a Dirichlet row's residual / (its
                            diagonal |x|_inf), the larger (1) */
    double t_factor;     /* wall time of the factorizations (seconds) */
    double t_columns;    /* wall time of the compliance columns (seconds) */
    long reused;         /* condensed Newton calls whose first solve was the last call's closing one (count) */
    double t_backsolves; /* wall time of the single back-solves (seconds) */
} ffc_solve_info;

/* Sets K from its triplets (Ti, Tj, Tv)[nt] (both triangles; duplicates
 * summed), n = 3 nv; any factorization and compliance of an earlier K are
 * dropped.  mmax: contact dofs a solve takes at most (its dense LU grows
 * as m^3).  FFC_ERR_INDEX / FFC_ERR_NONFINITE (*bad = the triplet),
 * FFC_ERR_SINGULAR for a diagonal entry that is not positive (*bad = the
 * dof), FFC_ERR_SIZE when n is not 3 nv. */
int ffc_scene_set_bulk(ffc_scene *s, long n, long nt, const long Ti[], const long Tj[], const double Tv[], long mmax,
                       long *bad);

/* Where a scene's bulk matrix is factorized and solved. */
typedef enum {
    FFC_ENGINE_CHOLMOD = 0,   /* CHOLMOD, in this process (the default) */
    FFC_ENGINE_MUMPS = 1,     /* parallel MUMPS over an MPI communicator: every rank of it holds the
                                 same scene and makes the same calls in the same order; each hands
                                 MUMPS a share of K's entries, and every rank receives each solution */
    FFC_ENGINE_REPLICATED = 2 /* CHOLMOD on every rank of an MPI communicator, each holding the whole
                                 factor (the same calls in the same order, as for MUMPS); the
                                 compliance columns of the condensed path are shared out over the
                                 ranks and gathered.  Small-strain bulks only (ffc_scene_set_bulk):
                                 faster than MUMPS on a few ranks while one process's memory holds
                                 the factor */
} ffc_engine;
typedef struct {
    ffc_engine engine;   /* the engine */
    int comm;            /* FFC_ENGINE_MUMPS: the communicator as a Fortran handle
                            (MPI_Comm_c2f(MPI_COMM_WORLD)) */
    int own;             /* ffc_parallel_solve: 0, every rank passes the same entries (each hands
                            MUMPS its share); 1, each rank passes its own (A is their sum: a
                            matrix assembled on each rank's part of the mesh) */
    int links;           /* ffc_scene_set_parallel: 1, the condensed Newton's contact evaluations
                            (augmented Lagrangian pairs with nodal multipliers, no mortar segments,
                            the residual and the ranked tangent) shared out, each rank the links of
                            its share of the slave facets, their sums gathered in rank order; 0,
                            every rank evaluates every link */
} ffc_parallel;
/* Sets the engine of the next ffc_scene_set_bulk.  FFC_ERR_VALUE for an
 * unknown engine, FFC_ERR_UNAVAILABLE for MUMPS or the replicated CHOLMOD
 * in a build without MPI (ffc_has_mpi() == 0) or for MUMPS before
 * MPI_Init (at ffc_scene_set_bulk). */
int ffc_scene_set_parallel(ffc_scene *s, const ffc_parallel *p);
/* Solves A x = b[n] once, A a general sparse matrix (a full Newton
 * system: non-symmetric with friction, indefinite with multipliers) from
 * its triplets (Ti, Tj, Tv)[nt] (duplicates summed), by parallel MUMPS
 * over p->comm: every rank passes the same b, and the same entries (each
 * hands MUMPS its share) or, with p->own, its own entries (A is their
 * sum); x on every rank.  FFC_ERR_INDEX /
 * FFC_ERR_NONFINITE (*bad = the triplet, or the entry of b),
 * FFC_ERR_SINGULAR (an exactly zero pivot; as with UMFPACK, a tiny one
 * gives a huge solution: the caller checks the residual), FFC_ERR_UNAVAILABLE
 * without MPI or for p->engine = FFC_ENGINE_CHOLMOD (one process: FreeFEM's
 * UMFPACK); FFC_ERR_VALUE for FFC_ENGINE_REPLICATED (a full system is
 * MUMPS's). */
int ffc_parallel_solve(const ffc_parallel *p, long n, long nt, const long Ti[], const long Tj[], const double Tv[],
                       const double b[], double x[], long *bad);
/* A full solver: A x = b for a general sparse A (a Newton system of the
 * whole mesh: not symmetric with friction, indefinite with multipliers),
 * in this process: UMFPACK's LU, or, for a matrix the caller declares
 * symmetric, CHOLMOD's LL^T of its lower triangle (about 3x faster on a
 * 3D mesh), UMFPACK taking the matrices CHOLMOD finds not positive
 * definite.  Each engine keeps the pattern it analysed last: a call with
 * the same order and the same (Ti, Tj) in the same order reuses its
 * analysis (ordering and symbolic factorization) and only factorizes
 * numerically. */
typedef struct ffc_full ffc_full;
int ffc_full_create(ffc_full **out);
void ffc_full_free(ffc_full *f);
/* Solves A x = b[n], A from its triplets (Ti, Tj, Tv)[nt] (duplicates
 * summed; both triangles), sym = 1 when A is symmetric (the lower
 * triangle's entries are used for CHOLMOD).  FFC_ERR_INDEX /
 * FFC_ERR_NONFINITE for a bad entry, FFC_ERR_SINGULAR for an exactly zero
 * pivot of the LU (a tiny one gives a huge solution: the caller checks
 * the residual), FFC_ERR_MEMORY; err (may be NULL) names the cause. */
int ffc_full_solve(ffc_full *f, long n, long nt, const long Ti[], const long Tj[], const double Tv[], int sym,
                   const double b[], double x[], ffc_error *err);
/* Its counters (factorizations, backsolves, rcond), the patterns both
 * engines analysed, the factorizations by CHOLMOD and the symmetric
 * matrices it found not positive definite (any pointer but f, info may be
 * NULL). */
int ffc_full_info(const ffc_full *f, ffc_solve_info *info, long *analyses, long *cholesky, long *not_posdef);
/* Factor reuse: a matrix on the pattern of the last factorized one is
 * first solved by GMRES preconditioned with that factor (Dirichlet rows
 * of a tgv diagonal scaled by it), to a true residual of 1e-13 of the
 * right-hand side in at most maxit iterations; only where that fails is
 * it factorized (maxit 0, the default: every matrix is; FFC_ERR_VALUE
 * outside [0, 1000]).  Newton's tangents change little from one iteration
 * to the next once the contact set settles: a few back-solves replace a
 * factorization.  ffc_full_reuse_info: the solves that reused a factor
 * and their GMRES iterations (counts). */
int ffc_full_set_reuse(ffc_full *f, long maxit);
int ffc_full_reuse_info(const ffc_full *f, long *reused, long *krylov);

/* The iterative path: the general (sym = 0) systems of a full solver
 * handed to PETSc instead of UMFPACK: GMRES (restarted every 100
 * iterations) right-preconditioned by pc, converged at a true residual
 * of rtol |b| (Dirichlet rows of a tgv diagonal scaled by it, their
 * values then set exactly: b_i / tgv), in this
 * process or (shared = 1, a build with MPI) with the rows shared out over
 * the ranks of the communicator fcomm (with nodes given, in compact
 * pieces: recursive coordinate bisection), every rank passing the same
 * system and getting the whole solution.  pc: FFC_PC_GAMG, PETSc's
 * smoothed-aggregation multigrid, whose near-null space is the six
 * rigid-body modes of the nodes xyz[3 nv] (a displacement field, dof
 * 3 i + c component c of node i; xyz NULL: the three translations); FFC_PC_HYPRE, hypre's BoomerAMG; FFC_PC_MUMPS, a direct
 * LU by MUMPS through PETSc (no Krylov iterations).  Each matrix builds
 * its preconditioner once (a "factorization" in the counters); the
 * symmetric systems stay with CHOLMOD, and, when nodes are given, the
 * systems of another order than 3 nv (a saddle-point matrix with
 * multipliers) with UMFPACK.  FFC_ERR_UNAVAILABLE in a build
 * without PETSc (ffc_has_petsc() == 0), FFC_ERR_VALUE for rtol outside
 * (0, 1), maxit outside [1, 100000] or an unknown pc.  A solve that does
 * not converge in maxit iterations returns FFC_ERR_NOCONV, err naming
 * the residual reached.  on = 0 returns to UMFPACK. */
enum { FFC_PC_GAMG = 0, FFC_PC_HYPRE = 1, FFC_PC_MUMPS = 2 };
typedef struct {
    int on;              /* 1: the iterative path */
    int shared;          /* 1: the rows shared out over the ranks of fcomm; 0: this process alone */
    int fcomm;           /* those ranks (a Fortran communicator handle) */
    int pc;              /* FFC_PC_GAMG, FFC_PC_HYPRE, FFC_PC_MUMPS */
    double rtol;         /* true residual <= rtol |b| (1) */
    long maxit;          /* Krylov iterations per solve at most (count) */
    long nv;             /* nodes of xyz (count; 0: none) */
    const double *xyz;   /* [3 nv] their coordinates (length; copied) */
} ffc_iterative;
typedef struct {
    long setups;         /* preconditioners built (count) */
    long solves;         /* solves (count) */
    long iterations;     /* Krylov iterations, all solves (count) */
    long last_iterations; /* of the last solve (count) */
    double t_setup;      /* wall time of the set-ups (seconds) */
    double t_solve;      /* wall time of the solves (seconds) */
} ffc_iterative_info;
int ffc_has_petsc(void);
int ffc_full_set_iterative(ffc_full *f, const ffc_iterative *opt);
/* The dofs[nb] (ascending, in [0, n)) that the iterative path's
 * preconditioner solves exactly after each multigrid cycle, from the next
 * solve on: those the contact couples (the rows of Kc), whose penalty
 * springs multigrid alone resolves poorly (a multiplicative composite of
 * the multigrid and an LU of A's block on them; on several ranks each
 * rank's share); nb = 0: the multigrid alone.  FFC_ERR_INDEX for a dof
 * out of range or out of order; nothing without the iterative path. */
int ffc_full_set_block(ffc_full *f, long n, long nb, const long dofs[]);
/* what the iterative path did (zeros before its first solve) */
int ffc_full_iterative_info(const ffc_full *f, ffc_iterative_info *info);

/* Solves (K + Kc) x = b[n], Kc from the triplets (Ti, Tj, Tv)[nt].
 * FFC_ERR_EMPTY without a K; FFC_ERR_INDEX / FFC_ERR_NONFINITE (*bad =
 * the triplet, or the entry of b); FFC_ERR_CAPACITY when Kc touches more
 * than mmax contact dofs (*bad = their count); FFC_ERR_SINGULAR when K + S
 * is not positive definite or the solve's residual stays above 1e-6. */
int ffc_scene_solve(ffc_scene *s, long nt, const long Ti[], const long Tj[], const double Tv[], const double b[],
                    double x[], long *bad);

/* Counters of the bulk solves since the last ffc_scene_set_bulk (zero
 * without a K). */
int ffc_scene_solve_info(const ffc_scene *s, ffc_solve_info *info);
/* The reason of the last failure of the scene's bulk solves (its linear
 * engine's record: status, what its index counts, a one-line message with
 * the sizes, e.g. "CHOLMOD: out of memory factorizing a matrix of order
 * 521592 with 20349867 entries"); status 0 when the last bulk call
 * (ffc_scene_solve, ffc_scene_newton, ffc_scene_nts_solve) did not fail in
 * its engine. */
int ffc_scene_solve_error(const ffc_scene *s, ffc_error *err);

/* ----------------------------------------------------- condensed Newton */
/* Newton's method on the condensed contact problem of a small-strain
 * augmented Lagrangian scene at fixed links and multipliers (the inner
 * loop of an augmentation, run in C on the contact dofs only).
 *
 * Formulation: the bulk is linear, r(u) = K u - f + F_c(u) on the free
 * dofs.  From u (residual r[n] given), the increment d solves
 * K d + F_c(u + d) = b' = -(r - F_c(u)).  Let C be the free dofs that
 * the contact force (or its tangent) has reached, G = P_C K^-1 P_C^T their
 * compliance (pruned block solves, kept between calls), d0 = K^-1 b'.  The
 * free dofs outside C carry no contact force, so with y = d_C the
 * interior is eliminated exactly and
 *     rho(y) = G^-1 (y - d0_C) + F_c(u + d)_C = 0     (m equations)
 * is the residual of the full system at the equilibrated interior.  Its
 * Jacobian is G^-1 + Kc_CC; the Newton step solves
 *     (I + G Kc_CC) dy = -G rho,
 * reduced to the dofs a that Kc touches (Kc_CC = E_a M E_a^T: t + G_aa M
 * t = -(G rho)_a, dy = -G rho - G_Ca M t), an |a| x |a| dense LU.  The
 * line search is the scene driver's: the root of g(s) = rho(y + s dy) . dy
 * by regula falsi (Illinois); a direction with g(0) >= 0 is replaced by
 * the material tangent's.  The primary unknown is the reaction
 * z = G^-1 (y - d0_C) that holds C at y: the Newton equation gives its
 * step, dz = -rho - Kc_CC dy, and y = d0_C + G z is recomputed from it
 * (no drift between the two; a Cholesky factor of G gives only the
 * start, y = 0: C held at u, the interior equilibrated).  C grows as the
 * contact does: the contact evaluation reads the dofs R of the pairs'
 * facets, whose displacement u + d0 + H z comes from the compliance
 * columns kept on those rows (H = P_R K^-1 P_C^T, |R| x |C|); a force or
 * tangent entry on a dof of R outside C makes it join C with z = 0 (the
 * same state), at the start (the start is then taken again: at the first
 * call of a load step the rest moves by the whole increment, and what it
 * reaches is held at u too), at an iterate, or at a line-search point
 * (the iteration is then taken again).  C thus holds the dofs in contact
 * at some point of the solve, not every linked point's (Hertz P1 h_c =
 * 0.025: 855 columns instead of 1,343).  At the end
 * d = d0 + K^-1 P_C^T z (one back-solve): the state whose residual is
 * rho.  With the shift S of a singular K (see above), K + S and
 * F_c - S y take the place of K and F_c.  A dynamic scene's velocities
 * follow u: v = v0 + dvdu (u + d - u).  Per call: two back-solves, one
 * contact evaluation per iteration and line-search point, a column per
 * dof that joins C, the Cholesky factor of G extended when C grew.  A
 * singular K (a body that only contact holds) is shifted on three nodes
 * far apart (by K's graph) in each body that the linked points' facets or
 * the contact force at u touch: no rigid motion of such a body leaves
 * them all at rest, and each shifted dof adds one term to the dense
 * systems (ffc_solve_info.shifted counts them); should K + S still be
 * singular, on the nodes the force reaches, then on the linked points'
 * facets.  The shifted dofs belong to C. */
/* Runs the condensed Newton from u[n] (n = 3 nv) with its residual r[n]
 * (FreeFEM's tgv rows included: a Dirichlet row's r / K_ii is the error
 * of its value, which the first step removes); u is the converged
 * displacement on FFC_NEWTON_CONVERGED, the last iterate on
 * FFC_NEWTON_MAXIT and FFC_NEWTON_NODESCENT (the returned reason),
 * unchanged on an error (a negative status).  FFC_ERR_EMPTY without a
 * bulk matrix, FFC_ERR_VALUE for a scene with node-to-surface pairs (or,
 * with FFC_TANGENT_RANKED, pairs with multipliers at quadrature points) or
 * options out of range, FFC_ERR_CAPACITY when C would hold more than
 * max_dofs (or the bulk's mmax) dofs (*bad = their count; the columns
 * added before stay, u is unchanged), FFC_ERR_SINGULAR when K + S or a
 * condensed system cannot be factorized, FFC_ERR_NONFINITE (*bad = the
 * entry of r or u). */
int ffc_scene_newton(ffc_scene *s, const double r[], double u[], const ffc_newton_opts *o, ffc_newton_info *info,
                     long *bad);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_SOLVE_H */
