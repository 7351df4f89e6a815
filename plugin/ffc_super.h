/* ffc_super.h: the supernodal Cholesky factorization by subtrees (internal) */
#ifndef FFC_SUPER_H
#define FFC_SUPER_H

#include <suitesparse/cholmod.h>

typedef struct ffc__super ffc__super;

/* The work of a factorization of A (lower triangle, packed, real) into
 * the numeric supernodal factor L of its analysis (L->x allocated, its
 * values to come), its supernodes split into `parts` sets of whole
 * subtrees and the supernodes above them.  NULL when out of memory or
 * when L's structure is not one this factorization reads (then *status
 * says which: FFC_ERR_MEMORY, FFC_ERR_UNAVAILABLE). */
ffc__super *ffc__super_create(const cholmod_factor *L, const cholmod_sparse *A, int parts, int *status);
void ffc__super_free(ffc__super *w);

/* The values of the supernodes of set `part` (0..parts-1: its subtrees;
 * every part's call first, in any order or at once, each with a work of
 * its own, into the same Lx), then those of part -1 (the supernodes
 * above them, once every part's values are in Lx; with a work that made
 * some part's call: it followed the other parts' lists of updates).
 * FFC_ERR_SINGULAR where a pivot is not positive (A not positive
 * definite); FFC_ERR_SIZE for a part out of range. */
int ffc__super_numeric(ffc__super *w, const cholmod_factor *L, double Lx[], int part);

/* the set of each supernode [L->nsuper]: 0..parts-1, or -1 above the subtrees */
const signed char *ffc__super_parts(const ffc__super *w);

/* the share of the estimated flops of part `part` (-1: above the subtrees) */
double ffc__super_share(const ffc__super *w, int part);

#endif
