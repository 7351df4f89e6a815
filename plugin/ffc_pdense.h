/* ffc_pdense.h: a dense LU shared over the ranks of an MPI communicator
 * (ScaLAPACK, columns block-cyclic on a 1 x N grid); internal. */
#ifndef FFC_PDENSE_H
#define FFC_PDENSE_H

typedef struct ffc__pdense ffc__pdense;

/* On the Fortran communicator fcomm (every rank makes the same calls with
 * the same arguments).  FFC_ERR_UNAVAILABLE in a build without MPI. */
int ffc__pdense_create(int fcomm, ffc__pdense **out);
void ffc__pdense_free(ffc__pdense *d);
/* Local storage for an a x a matrix: returns this rank's column block
 * (column-major, leading dimension a) or NULL (no memory, on any rank). */
double *ffc__pdense_reserve(ffc__pdense *d, long a);
/* The local index of global column j on this rank, or -1 when another
 * rank holds it. */
long ffc__pdense_local(const ffc__pdense *d, long j);
/* LU of the reserved matrix (its local columns filled), kept for solves;
 * FFC_ERR_SINGULAR for a pivot below 1e-15 of the largest entry. */
int ffc__pdense_factor(ffc__pdense *d, long a);
/* t[a] (the same on every rank) overwritten by the kept LU's solution,
 * on every rank. */
int ffc__pdense_solve(ffc__pdense *d, long a, double t[]);

#endif
