/* ffc_bulk.h: the bulk factorization a scene keeps and the solvers on it
 * (ffc_bulk.c, ffc_columns.c, ffc_csolve.c, ffc_cnewton.c, ffc_saddle.c);
 * not part of the public interface (ffc_scene_set_bulk, ffc_scene_solve,
 * ffc_scene_newton, ffc_scene_nts_solve are). */
#ifndef FFC_BULK_H
#define FFC_BULK_H

#include "ffc.h"

typedef struct ffc__bulk ffc__bulk;

/* Keeps a copy of K (n x n, triplets, both triangles; duplicates summed);
 * nothing is factorized until the first solve.  mmax: contact dofs the
 * solve takes at most.  FFC_ERR_INDEX / FFC_ERR_NONFINITE (*bad = the
 * triplet), FFC_ERR_SINGULAR for a diagonal entry that is not positive
 * (*bad = the row). */
int ffc__bulk_create(long n, long nt, const long Ti[], const long Tj[], const double Tv[], long mmax,
                     ffc__bulk **out, long *bad);
void ffc__bulk_free(ffc__bulk *b);
/* The reason of the engine's last failure (never NULL for a bulk). */
const ffc_error *ffc__bulk_error(const ffc__bulk *b);
/* st, the record cleared when st is FFC_OK, and when it is FFC_ERR_MEMORY from outside the engine (the dense
 * compliance, a direction's dense system) a record naming the sizes */
int ffc__bulk_note(ffc__bulk *b, int st);
/* the record cleared (at the start of each solve, Newton or saddle call) */
void ffc__bulk_clear_error(ffc__bulk *b);
/* Factorizes with parallel MUMPS over the Fortran communicator fcomm
 * instead of CHOLMOD (FFC_ERR_UNAVAILABLE in a build without MPI). */
int ffc__bulk_set_mumps(ffc__bulk *b, int fcomm);
/* Factorizes with CHOLMOD on every rank of the Fortran communicator fcomm
 * (each holds the whole factor; every rank makes the same calls) and
 * shares the compliance columns out over them (FFC_ERR_UNAVAILABLE in a
 * build without MPI). */
int ffc__bulk_set_replicated(ffc__bulk *b, int fcomm);
long ffc__bulk_n(const ffc__bulk *b);
/* The mean diagonal of K's rows that are not Dirichlet rows (force/length). */
double ffc__bulk_kfree(const ffc__bulk *b);

/* (K + Kc) x = rhs (see ffc_scene_solve). */
int ffc__bulk_solve(ffc__bulk *b, long nt, const long Ti[], const long Tj[], const double Tv[], const double rhs[],
                    double x[], long *bad);
void ffc__bulk_info(const ffc__bulk *b, ffc_solve_info *info);

/* The node-to-surface saddle point [K Bf'; B Cm] [x; mult] = [rhs; c]
 * (see ffc_scene_nts_solve): rows (Bi, Bj, Bv, Fv)[nt] of nr constraints
 * as ffc_nts_rows writes them. */
int ffc__bulk_saddle(ffc__bulk *b, long nt, const long Bi[], const long Bj[], const double Bv[], const double Fv[],
                     long nr, const double c[], const double rhs[], double x[], double mult[], long *bad);

/* The contact force of the scene at u added into R[n] and, unless tangent
 * is FFC_TANGENT_NONE, its tangent as triplets (ffc_scene_assemble's
 * contract: FFC_ERR_CAPACITY with the count needed in *nt); *fmag the
 * force scale of the convergence test (|Fx| + |Fy| + |Fz| of the total
 * normal contact force); state[3] the contact state it found (active,
 * sticking and sliding points: counts). */
typedef int (*ffc__contact_fn)(void *ctx, const double u[], int tangent, double R[], long cap, long Ti[], long Tj[],
                               double Tv[], long *nt, double *fmag, double state[3], long *bad);

/* Newton's method on the condensed contact problem (see ffc_scene_newton);
 * rows[nr] the dofs the contact evaluation may read or load (its force
 * on another dof is FFC_ERR_INDEX), cand[nc] those of the linked points
 * (a singular K is shifted on them; Dirichlet ones skipped). */
int ffc__bulk_newton(ffc__bulk *b, long nr, const long rows[], long nc, const long cand[], ffc__contact_fn fn,
                     void *ctx, const double r[], double u[], const ffc_newton_opts *o, ffc_newton_info *info,
                     long *bad);

/* Test hooks.  The factor's kind (supernodal = 1: CHOLMOD's supernodal
 * factor whatever the size; 0: CHOLMOD chooses) and the compliance
 * columns' solves (prune = 1: pruned to the paths of the rows read, the
 * default; 0: whole back-solves): the factor's kind from the next
 * factorization, the solves from the next compliance columns. */
void ffc__bulk_set_columns_mode(ffc__bulk *b, int supernodal, int prune);
/* Factorizes K if not yet, joins rows[nr] to the rows R and adds the
 * compliance columns of the dofs nd[nnew] (not yet in C). */
int ffc__bulk_columns(ffc__bulk *b, long nr, const long rows[], long nnew, const long nd[], long *bad);
/* The compliance kept: returns m = |C|; dof[m] C's dofs, G (m x m in a
 * leading dimension ld), H (|R| x m, leading dimension |R|), whether the
 * factor is supernodal and the share of its entries the last pruned
 * backward solves visited (0: none made). */
long ffc__bulk_compliance(const ffc__bulk *b, const long **dof, const double **G, long *ld, const double **H,
                          int *supernodal, double *pruned);

#endif
