/* ffc/mpi.h: several processes: whether MPI is built in, ranks, reductions, gathers, barrier, peak memory. */
#ifndef FFC_API_MPI_H
#define FFC_API_MPI_H

#include "status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------- several processes */
/* 1 in a build with MPI and parallel MUMPS (-DFFC_MPI), else 0. */
int ffc_has_mpi(void);

/* MPI_COMM_WORLD: this process's rank, the ranks, the communicator as a
 * Fortran handle (0, 1, 0 in a build without MPI or outside MPI_Init). */
int ffc_mpi_world(int *rank, int *size, int *fcomm);
/* v[n] replaced on every rank by its sum (op 0), largest (1) or smallest
 * (2) value over the ranks; a collective call (nothing with one rank). */
int ffc_mpi_allreduce(double v[], long n, int op);
/* Every rank's triplets (Ti, Tj, Tv)[nt], concatenated in the order of
 * the ranks, into (Oi, Oj, Ov)[cap] on every rank; *total = their count
 * (FFC_ERR_CAPACITY when cap is smaller: call again with cap >= *total;
 * FFC_ERR_SIZE for a negative count or cap, or over 2^31 - 1 in all).
 * Pieces of one matrix assembled on parts of a mesh become its triplets on
 * every rank (ffc_triplets_sum sums them, the same bits everywhere).  A
 * collective call: a bad argument on one rank is every rank's error (the
 * most negative status).  One rank: a copy. */
int ffc_mpi_gather_triplets(long nt, const long Ti[], const long Tj[], const double Tv[], long cap, long Oi[],
                            long Oj[], double Ov[], long *total);
/* Waits for every rank (nothing with one rank). */
int ffc_mpi_barrier(void);
/* This process's peak resident memory (MB). */
double ffc_peak_mb(void);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_MPI_H */
