/* ffc_mumps.h: the parallel MUMPS engine of a scene's bulk matrix (internal). */
#ifndef FFC_MUMPS_H
#define FFC_MUMPS_H

typedef struct ffc__mumps ffc__mumps;

/* A MUMPS instance on the Fortran communicator fcomm (every rank of it
 * makes the same calls, in the same order, with the same arguments).
 * FFC_ERR_UNAVAILABLE in a build without MPI. */
int ffc__mumps_create(int fcomm, ffc__mumps **out);
void ffc__mumps_free(ffc__mumps *m);
/* Analysis and LDL^T factorization of the symmetric positive definite
 * matrix of order n from its lower triangle (ti, tj, tv)[nz] (0-based,
 * duplicates summed), the same list on every rank: each rank hands MUMPS
 * its share (distributed input).  FFC_ERR_SINGULAR for a negative pivot
 * or one below 1e-12 of K's norm, FFC_ERR_MEMORY. */
int ffc__mumps_factor(ffc__mumps *m, long n, long nz, const int ti[], const int tj[], const double tv[]);
/* B[n*nrhs] (column-major) overwritten by the solution, on every rank. */
int ffc__mumps_solve(ffc__mumps *m, long nrhs, double B[]);
/* Entries of the inverse of the factorized matrix:
 * X[r + c * nrows] = (K^-1)[rows[r], cols[c]] (0-based; no index twice in
 * either list), on every rank.  MUMPS prunes its forward and backward
 * solves to the tree paths of the rows and columns asked for (ICNTL(30)),
 * which makes a block of compliance columns on a contact surface several
 * times cheaper than as dense right-hand sides.  FFC_ERR_VALUE for an index
 * given twice, FFC_ERR_EMPTY before a factorization, FFC_ERR_MEMORY on every
 * rank when X is NULL on one (its allocation failed) or MUMPS fails. */
int ffc__mumps_inverse(ffc__mumps *m, long ncols, const long cols[], long nrows, const long rows[], double X[]);
/* 1 when ok is 1 on every rank of m's communicator (a collective call:
 * a local failure becomes every rank's, so that all take one branch);
 * ok itself without m */
int ffc__mumps_agree(ffc__mumps *m, int ok);
/* ranks, and this rank's and the largest rank's factorization memory (MB) */
void ffc__mumps_info(const ffc__mumps *m, int *ranks, double *mb_rank, double *mb_max);

#endif
